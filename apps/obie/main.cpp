// obie: the whole chain on a football match (thesis chapter 7): events → emotions → expressions and
// utterances → channels → muscles → animated, rendered face (MP4 with speech), charts, key moments.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "emoface/channels/io.hpp"
#include "emoface/cli/cli.hpp"
#include "emoface/faceweights/tracks.hpp"
#include "emoface/facemesh/gltf_morph.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/muscles/morph_targets.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/core/version.hpp"
#include "emoface/core/video.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/gltf.hpp"
#include "emoface/obie/pipeline.hpp"
#include "emoface/parlee/io.hpp"

namespace ob = emoface::obie;
namespace fs = std::filesystem;

namespace {

// Progress on stderr: a bar redrawn in place on a terminal, a plain line per 10 % otherwise.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool quiet) : quiet_(quiet), tty_(::isatty(2) == 1) {}
  void operator()(const ob::Progress& p) {
    if (quiet_ || p.total == 0) return;
    const int pct = static_cast<int>(100 * p.done / p.total);
    if (tty_) {
      if (pct == last_pct_ && std::string(p.stage) == stage_) return;
      const int width = 30, filled = width * pct / 100;
      std::fprintf(stderr, "\r%-10.10s [%s%s] %3d%% %zu/%zu", std::string(p.stage).c_str(),
                   std::string(static_cast<std::size_t>(filled), '#').c_str(),
                   std::string(static_cast<std::size_t>(width - filled), '.').c_str(), pct, p.done, p.total);
      if (p.done == p.total) std::fputc('\n', stderr);
      std::fflush(stderr);
    } else if (pct / 10 != last_pct_ / 10 || std::string(p.stage) != stage_ || p.done == p.total) {
      if (!(p.done == p.total && pct == last_pct_ && std::string(p.stage) == stage_))
        std::fprintf(stderr, "obie: %s %d%% (%zu/%zu)\n", std::string(p.stage).c_str(), pct, p.done, p.total);
    }
    last_pct_ = pct;
    stage_ = std::string(p.stage);
  }

 private:
  bool quiet_, tty_;
  int last_pct_ = -1;
  std::string stage_;
};

// "12:the against team scores" → key moment.
ob::KeyMoment parse_key_moment(const std::string& text) {
  const auto colon = text.find(':');
  ob::KeyMoment k;
  try {
    std::size_t used = 0;
    k.minute = std::stod(text.substr(0, colon), &used);
    if (used != text.substr(0, colon).size()) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw emoface::cli::UsageError("--key-moment \"" + text + "\": expected MINUTE[:LABEL]");
  }
  if (colon != std::string::npos) k.label = text.substr(colon + 1);
  return k;
}

std::string fixed(double x, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << x;
  return s.str();
}

}  // namespace

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
      for (const auto& k : key_moments) m.key_moments.push_back(parse_key_moment(k));
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
    fs::create_directories(out_dir);
    const auto file = [&](const char* name) { return (fs::path(out_dir) / name).string(); };

    const auto t0 = std::chrono::steady_clock::now();
    ProgressPrinter printer(quiet);
    std::unique_ptr<ob::VideoSink> video;
    if (!no_video) video = std::make_unique<ob::VideoSink>(file("obie.mp4"), file("speech.wav"));
    ob::ObieResult r = ob::run_obie(match, agent, face, o, std::ref(printer), video.get(), match_path);

    auto timed = [&](const char* stage, const std::function<void()>& f) {
      const auto s = std::chrono::steady_clock::now();
      f();
      r.timings.push_back({stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count()});
    };
    timed("write timeline + tracks", [&] {
      emoface::core::write_file_atomic(file("timeline.ndjson"), ob::format_timeline(r));
      emoface::channels::write_tracks(file("tracks.csv"), r.head.tracks);
      for (const auto& w : weights_formats) {
        const std::string name = w == "livelink" ? "livelink_face.csv" : w + ".csv";
        emoface::core::write_file_atomic(
            file(name.c_str()),
            emoface::faceweights::format_fixed_rate_track(
                *emoface::faceweights::track_format_from_string(w + "-csv"), r.head.tracks.names,
                r.head.tracks.fps, r.head.tracks.values));
      }
      if (no_video) emoface::channels::write_wav(file("speech.wav"), r.head.audio, r.head.sample_rate);
    });
    if (!r.gltf_frames.empty())
      timed("write glTF", [&] {
        // named morph targets (parameters + ARKit shapes) animated by the tracks' weights at the
        // glTF key times (docs/engines.md)
        namespace mu = emoface::muscles;
        const auto& tracks = r.head.tracks;
        std::vector<int> column;
        for (const auto& n : mu::parameter_names()) column.push_back(tracks.column(n));
        std::vector<std::vector<double>> keys;
        for (double t : r.gltf_times) {
          const auto f = std::min<std::size_t>(static_cast<std::size_t>(std::llround(t * tracks.fps)),
                                               tracks.frames() - 1);
          std::vector<double> v(mu::kParameterCount, 0.0);
          for (std::size_t i = 0; i < v.size(); ++i)
            if (column[i] >= 0) v[i] = tracks.at(f, static_cast<std::size_t>(column[i]));
          keys.push_back(std::move(v));
        }
        const mu::FaceSolver solver(face.mesh, face.rig);
        mu::RigGltfOptions gopt;
        gopt.animation_name = "match";
        mu::write_rig_gltf(file("face.glb"), face, solver, r.gltf_times, keys, gopt);
      });
    timed("charts + key moments", [&] {
      emoface::core::write_file_atomic(file("charts.png"), emoface::parlee::encode_png(ob::emotion_chart(r)));
      if (!r.key_frames.empty())
        emoface::core::write_file_atomic(file("key_moments.png"), emoface::parlee::encode_png(ob::key_moment_sheet(r)));
    });
    emoface::core::write_file_atomic(file("summary.json"), ob::format_summary(r, match));
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // one-screen summary
    std::ostream& out = std::cout;
    out << "Obie (" << r.agent_name << ") watched " << (match.title.empty() ? match_path : match.title) << "\n";
    int f = 0, a = 0;
    for (const auto& g : r.goals) {
      out << "  goal " << fixed(g.minute, g.minute == static_cast<int>(g.minute) ? 0 : 1) << "'  " << g.team << "  "
          << g.for_score << "-" << g.against_score << "\n";
      f = g.for_score;
      a = g.against_score;
    }
    out << "  final score " << match.for_team.name << " " << f << "-" << a << " " << match.against_team.name << "\n";
    out << "peak emotions:";
    for (const auto& p : r.peaks)
      if (p.value > 0.005) out << "  " << p.emotion << " " << fixed(p.value, 2) << " @" << p.minute << "'";
    out << "\nutterances:";
    for (const auto& u : r.utterances) out << "  " << u.minute << "' \"" << u.text << "\"";
    out << "\nframes: " << r.frames << " at " << o.fps << " fps = " << fixed(r.seconds(), 1) << " s of animation for "
        << match.duration << " match minutes (" << r.frames_rendered << " rendered " << o.width << "x" << o.height
        << ")\ntime per stage:\n";
    for (const auto& s : r.timings) out << "  " << s.stage << std::string(s.stage.size() < 26 ? 26 - s.stage.size() : 1, ' ') << fixed(s.seconds, 2) << " s\n";
    out << "  total" << std::string(21, ' ') << fixed(total, 2) << " s\n";
    out << "outputs in " << out_dir << ":\n";
    for (const char* name : {"obie.mp4", "speech.wav", "face.glb", "timeline.ndjson", "tracks.csv", "arkit.csv",
                             "facs.csv", "livelink_face.csv", "charts.png",
                             "key_moments.png", "summary.json"})
      if (fs::exists(file(name))) out << "  " << file(name) << "\n";
    return 0;
  });
}
