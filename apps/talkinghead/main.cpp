// talkinghead: marked-up text → parameter tracks (JSON/CSV) + speech WAV (thesis chapter 4).
#include <algorithm>
#include <iostream>
#include <memory>
#include <sstream>

#include "emoface/channels/io.hpp"
#include "emoface/channels/talking_head.hpp"
#include "emoface/channels/timing_io.hpp"
#include "emoface/cli/cli.hpp"
#include "emoface/core/io.hpp"
#include "emoface/faceweights/tracks.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "plot.hpp"

namespace ch = emoface::channels;

namespace {

std::vector<std::string> split_names(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "talkinghead: marked-up text -> facial parameter tracks and speech (thesis chapter 4).\n"
      "Example:\n  talkinghead --script data/channels/examples/oh_really.xml --fps 25 --out tracks.csv "
      "--wav speech.wav --seed 1 --plot smile.png --plot-params zygomatic_major_l,orbicularis_oris_funneler"};
  std::string script_path, out_path, wav_path, plot_path, plot_params, visemes_path, conflicts_path;
  std::string dump_visemes, dump_conflicts, weights_format, weights_path;
  ch::TalkingHeadOptions o;
  double onset = 0.5, offset = 0.5;
  bool no_blinks = false, no_gaze = false, no_head = false;
  app.add_option("--script", script_path, "marked-up script (XML, see docs/channels.md)");
  app.add_option("--fps", o.render.fps, "frames per second of the tracks")->capture_default_str();
  app.add_option("--out", out_path, "output tracks: .csv (time + one column per parameter) or .json; - = stdout JSON");
  app.add_option("--weights", weights_format,
                 "arkit|facs|livelink: also write the tracks as ARKit, FACS or Live Link Face CSV "
                 "(--weights-out)")
      ->check(CLI::IsMember({"arkit", "facs", "livelink"}));
  app.add_option("--weights-out", weights_path, "file for --weights (written atomically)");
  app.add_option("--wav", wav_path, "write the synthesized speech (16-bit mono WAV, same length as the tracks)");
  app.add_option("--seed", o.seed, "seed of blinks and gaze/head noise")->capture_default_str();
  app.add_option("--duration", o.render.duration, "seconds of output (0 = until the last movement)")->capture_default_str();
  app.add_option("--voice", o.speech.voice, "espeak-ng voice")->capture_default_str();
  app.add_option("--rate", o.speech.rate, "speech rate, words per minute")->capture_default_str();
  std::vector<std::string> timing_paths, timing_wavs;
  app.add_option("--timings", timing_paths,
                 "external phoneme/viseme timings instead of espeak-ng, one file per <PHONEME> element in "
                 "order (emoface TSV/JSON or Rhubarb Lip Sync TSV/JSON; docs/formats.md)");
  app.add_option("--timings-wav", timing_wavs,
                 "the speech audio of each --timings file, same order (16-bit PCM WAV; default: silence)");
  app.add_option("--onset", onset, "default onset of elements without one, s")->capture_default_str();
  app.add_option("--offset", offset, "default offset of elements without one, s")->capture_default_str();
  app.add_option("--dmin-plus", o.render.mix.dmin_plus, "Dmin+ of the conflict resolution, s")->capture_default_str();
  app.add_option("--dmin-minus", o.render.mix.dmin_minus, "Dmin- of the conflict resolution, s")->capture_default_str();
  app.add_flag("--no-blinks", no_blinks, "no random blinks");
  app.add_flag("--no-gaze-noise", no_gaze, "no random gaze shifts");
  app.add_flag("--no-head-noise", no_head, "no random head drift");
  app.add_option("--visemes", visemes_path, "viseme set (emoface.channels.visemes JSON); default: built-in");
  app.add_option("--conflicts", conflicts_path, "conflict table (emoface.channels.conflicts JSON); default: built-in");
  app.add_option("--plot", plot_path, "write a PNG plot of --plot-params over time");
  app.add_option("--plot-params", plot_params, "comma-separated parameter names to plot (colours: blue, red, green, "
                                               "orange, purple, brown, black, cyan)");
  app.add_option("--dump-visemes", dump_visemes, "write the built-in viseme set and exit");
  app.add_option("--dump-conflicts", dump_conflicts, "write the built-in conflict table and exit");
  if (auto code = emoface::cli::parse(app, argc, argv)) return *code;

  return emoface::cli::run("talkinghead", [&]() -> int {
    if (!dump_visemes.empty() || !dump_conflicts.empty()) {
      if (!dump_visemes.empty()) ch::write_visemes(dump_visemes, ch::default_viseme_set());
      if (!dump_conflicts.empty()) ch::write_conflicts(dump_conflicts, ch::default_conflict_table());
      return 0;
    }
    if (script_path.empty() || out_path.empty()) {
      std::cerr << "talkinghead: error: --script and --out are required (see --help)\n";
      return emoface::cli::kExitUsage;
    }
    o.timeline.blinks = !no_blinks;
    o.timeline.gaze_noise = !no_gaze;
    o.timeline.head_noise = !no_head;
    const ch::Script script = ch::read_script(script_path, ch::ScriptDefaults{onset, offset});
    const ch::VisemeSet visemes = visemes_path.empty() ? ch::default_viseme_set() : ch::read_visemes(visemes_path);
    const ch::ConflictTable conflicts =
        conflicts_path.empty() ? ch::default_conflict_table() : ch::read_conflicts(conflicts_path);
    if (!timing_paths.empty()) {
      if (timing_paths.size() != script.speech.size())
        throw emoface::cli::UsageError("--timings: " + std::to_string(timing_paths.size()) + " files for " +
                                       std::to_string(script.speech.size()) + " <PHONEME> elements");
      if (!timing_wavs.empty() && timing_wavs.size() != timing_paths.size())
        throw emoface::cli::UsageError("--timings-wav: give one WAV per --timings file");
      auto external = std::make_shared<ch::ExternalSpeech>();
      for (std::size_t i = 0; i < timing_paths.size(); ++i) {
        const ch::WavAudio wav = timing_wavs.empty() ? ch::WavAudio{} : ch::read_wav(timing_wavs[i]);
        external->add(script.speech[i].text, ch::external_utterance(ch::read_timing_file(timing_paths[i]), wav));
      }
      o.synthesizer = external;
    } else if (!timing_wavs.empty()) {
      throw emoface::cli::UsageError("--timings-wav needs --timings");
    }
    const ch::EmotionMapper mapper =
        ch::side_parameter_mapper(emoface::fuzzyexpr::side_parameter_function());
    const ch::TalkingHead th = ch::run_talking_head(script, visemes, conflicts, mapper, o);

    if (weights_format.empty() != weights_path.empty())
      throw emoface::cli::UsageError("--weights and --weights-out go together");
    emoface::cli::Output out(out_path);
    out.write(ch::format_tracks(th.tracks, out_path));
    if (!weights_path.empty())
      emoface::core::write_file_atomic(
          weights_path, emoface::faceweights::format_fixed_rate_track(
                            *emoface::faceweights::track_format_from_string(weights_format + "-csv"),
                            th.tracks.names, th.tracks.fps, th.tracks.values));
    if (!wav_path.empty()) ch::write_wav(wav_path, th.audio, th.sample_rate);
    if (!plot_path.empty()) {
      std::vector<std::vector<double>> series;
      for (const auto& n : split_names(plot_params)) series.push_back(th.tracks.series(n));
      if (series.empty()) throw emoface::InvalidInput("--plot needs --plot-params");
      emoface::talkinghead::plot_png(plot_path, series, th.tracks.fps);
    }
    out.commit();
    return 0;
  });
}
