// obie: the whole chain on a football match (thesis chapter 7): events → emotions → expressions and
// utterances → channels → muscles → animated, rendered face (MP4 with speech), charts, key moments.
#include <chrono>
#include <filesystem>
#include <iostream>

#include "emoface/cli/cli.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/core/version.hpp"
#include "emoface/core/video.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/obie/bundle.hpp"
#include "emoface/obie/pipeline.hpp"
#include "emoface/parlee/io.hpp"

namespace ob = emoface::obie;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  CLI::App app{
      "obie: Obie watches a football match (thesis ch. 7): events -> emotions -> facial expressions and\n"
      "utterances -> muscle tracks -> animated face (glTF, MP4 with speech), emotion charts, key moments.\n"
      "Example:\n"
      "  obie --match data/obie/match_7_4.json --agent data/parlee/agents/neutral.json --out out/obie\n"
      "  obie convert --events data/parlee/match.ndjson --domain ../parlee/football.domain \\\n"
      "       --key-moment '12:0-1' --out data/obie/my_match.json"};
  app.set_version_flag("--version", emoface::kGenerator);
  std::string match_path, agent_path, out_dir, rig_path, utterances_path, view = "front";
  std::vector<std::string> weights_formats;
  ob::ObieOptions o;
  bool no_video = false, no_speech = false, quiet = false, no_blinks = false, no_gaze = false, no_head = false;
  app.add_option("--match", match_path, "match script (emoface.obie.match JSON, see docs/obie.md)");
  app.add_option("--agent", agent_path, "parlee agent file (e.g. data/parlee/agents/neutral.json)");
  app.add_option("--out", out_dir, "output directory (created)");
  app.add_option("--rig", rig_path, "rig file or a directory holding face.rig (retarget --out DIR); default: built-in face");
  app.add_option("--seed", o.seed, "seed of utterance choice, blinks, gaze and head noise")->capture_default_str();
  app.add_option("--fps", o.fps, "frames per second")->check(CLI::Range(1.0, 120.0))->capture_default_str();
  app.add_option("--width", o.width, "frame width, pixels")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--height", o.height, "frame height, pixels")->check(CLI::Range(16, 4096))->capture_default_str();
  app.add_option("--view", view, "front or threequarter")->check(CLI::IsMember({"front", "threequarter"}));
  app.add_option("--seconds-per-minute", o.time.seconds_per_minute, "animation seconds per match minute")
      ->check(CLI::Range(0.001, 60.0))->capture_default_str();
  app.add_option("--min-event-gap", o.time.min_event_gap, "animation seconds between events, at least")
      ->check(CLI::Range(0.0, 60.0))->capture_default_str();
  app.add_option("--voice", o.voice.voice, "espeak-ng voice")->capture_default_str();
  app.add_option("--rate", o.voice.rate, "speech rate, words per minute")->check(CLI::Range(80, 450))->capture_default_str();
  app.add_option("--utterances", utterances_path, "utterance rules (emoface.obie.utterances JSON); default: built-in");
  app.add_option("--gltf-fps", o.gltf_fps, "morph-target frames per second of face.glb (0 = no glTF)")
      ->check(CLI::Range(0.0, 120.0))->capture_default_str();
  app.add_option("--threads", o.threads, "deformation/rendering threads (0 = all cores, at most 8)")
      ->check(CLI::Range(0, 64))->capture_default_str();
  app.add_option("--weights", weights_formats,
                 "arkit,facs,livelink: also write the tracks as arkit.csv, facs.csv and/or "
                 "livelink_face.csv (Live Link Face CSV)")
      ->delimiter(',')
      ->check(CLI::IsMember({"arkit", "facs", "livelink"}));
  app.add_flag("--no-video", no_video, "skip rendering every frame and the MP4 (key moments are still rendered)");
  app.add_flag("--no-speech", no_speech, "no utterances (silent audio)");
  app.add_flag("--no-blinks", no_blinks, "no random blinks");
  app.add_flag("--no-gaze-noise", no_gaze, "no random gaze shifts");
  app.add_flag("--no-head-noise", no_head, "no random head drift");
  app.add_flag("--quiet,-q", quiet, "no progress on stderr");

  auto* convert = app.add_subcommand("convert", "parlee events NDJSON -> match script (emoface.obie.match)");
  std::string events_path, convert_out = "-", title, for_side = "team", for_name = "For", against_side = "oteam",
                           against_name = "Against";
  std::vector<std::string> domains, key_moments;
  double duration = 0;
  convert->add_option("--events", events_path, "parlee events (NDJSON)")->required();
  convert->add_option("--domain", domains, "domain file(s) as the script should reference them (relative to --out)")->required();
  convert->add_option("--out", convert_out, "output match script ('-' = stdout)")->capture_default_str();
  convert->add_option("--title", title, "title of the match");
  convert->add_option("--key-moment", key_moments, "MINUTE[:LABEL], repeatable");
  convert->add_option("--for", for_side, "domain side Obie supports")->capture_default_str();
  convert->add_option("--for-name", for_name, "its display name")->capture_default_str();
  convert->add_option("--against", against_side, "the other side")->capture_default_str();
  convert->add_option("--against-name", against_name, "its display name")->capture_default_str();
  convert->add_option("--duration", duration, "match minutes (0 = max(90, last event))");
  if (auto code = emoface::cli::parse(app, argc, argv)) return *code;

  return emoface::cli::run("obie", [&]() -> int {
    if (*convert) {
      ob::MatchScript m = ob::match_from_events(emoface::parlee::read_events_file(events_path));
      m.title = title;
      m.domain = domains;
      m.for_team = {for_side, for_name};
      m.against_team = {against_side, against_name};
      if (duration > 0) m.duration = duration;
      for (const auto& k : key_moments) try {
          m.key_moments.push_back(ob::parse_key_moment(k));
        } catch (const emoface::InvalidInput&) {
          throw emoface::cli::UsageError("--key-moment \"" + k + "\": expected MINUTE[:LABEL]");
        }
      emoface::cli::Output out(convert_out);
      out.write(ob::write_match(m));
      out.commit();
      return 0;
    }
    if (match_path.empty() || agent_path.empty() || out_dir.empty())
      throw emoface::cli::UsageError("--match, --agent and --out are required (see --help)");
    o.view = emoface::facemesh::view_from_string(view);
    o.speech = !no_speech;
    o.blinks = !no_blinks;
    o.gaze_noise = !no_gaze;
    o.head_noise = !no_head;
    o.render_frames = !no_video;
    if (!utterances_path.empty()) o.utterances = ob::read_utterances_file(utterances_path);
    try {
      o.validate();
    } catch (const emoface::InvalidInput& e) {
      throw emoface::cli::UsageError(e.what());
    }
    if (!no_video && !emoface::core::ffmpeg_available())
      throw emoface::cli::UsageError("ffmpeg is not installed (apt-get install ffmpeg), or pass --no-video");
    const ob::MatchScript match = ob::read_match_file(match_path);
    const emoface::parlee::AgentConfig agent = emoface::parlee::read_agent_file(agent_path);
    std::string rig_file = rig_path;
    if (!rig_file.empty() && fs::is_directory(rig_file)) rig_file = (fs::path(rig_file) / "face.rig").string();
    const emoface::facemesh::Face face =
        rig_file.empty()            ? emoface::facemesh::make_default_face()
        : rig_file == "generic" ? emoface::facemesh::make_generic_face()
                                : emoface::facemesh::load_face(rig_file);
    const auto file = [&](const char* name) { return (fs::path(out_dir) / name).string(); };
    const auto t0 = std::chrono::steady_clock::now();
    emoface::cli::ProgressBar bar("obie", quiet);
    // Every output staged in one bundle (all written or none); the video and its speech track are
    // rendered into staged paths during the run.
    emoface::core::OutputBundle bundle;
    std::unique_ptr<ob::VideoSink> video;
    if (!no_video)
      video = std::make_unique<ob::VideoSink>(bundle.stage_path(file("obie.mp4")),
                                              bundle.stage_path(file("speech.wav")));
    ob::ObieResult r = ob::run_obie(
        match, agent, face, o, [&](const ob::Progress& p) { bar.update(p.stage, p.done, p.total); },
        video.get(), match_path);
    ob::stage_outputs(bundle, out_dir, r, match, face, {weights_formats, no_video});
    bundle.commit();
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::vector<std::string> written;
    for (const char* name :
         {"obie.mp4", "speech.wav", "face.glb", "timeline.ndjson", "tracks.csv", "arkit.csv",
          "facs.csv", "livelink_face.csv", "charts.png", "key_moments.png", "summary.json"})
      if (fs::exists(file(name))) written.push_back(file(name));
    std::cout << ob::console_summary(r, match, match_path, o, total, out_dir, written);
    return 0;
  });
}
