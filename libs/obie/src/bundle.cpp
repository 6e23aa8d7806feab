#include "emoface/obie/bundle.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>

#include "emoface/channels/io.hpp"
#include "emoface/channels/speech.hpp"
#include "emoface/core/text.hpp"
#include "emoface/faceweights/tracks.hpp"
#include "emoface/muscles/morph_targets.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/parlee/chart.hpp"

namespace emoface::obie {

namespace {

std::string fixed(double x, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << x;
  return s.str();
}

}  // namespace

void stage_outputs(core::OutputBundle& bundle, const std::string& out_dir, ObieResult& r,
                   const MatchScript& match, const facemesh::Face& face,
                   const OutputSelection& selection) {
  namespace fs = std::filesystem;
  const auto file = [&](const std::string& name) { return (fs::path(out_dir) / name).string(); };
  auto timed = [&](const char* stage, const std::function<void()>& f) {
    const auto s = std::chrono::steady_clock::now();
    f();
    r.timings.push_back(
        {stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count()});
  };
  timed("write timeline + tracks", [&] {
    bundle.add(file("timeline.ndjson"), format_timeline(r));
    bundle.add(file("tracks.csv"), channels::format_tracks(r.head.tracks, file("tracks.csv")));
    for (const auto& w : selection.weights) {
      const auto format = faceweights::track_format_from_string(w + "-csv");
      if (!format) throw InvalidInput("unknown weight format \"" + w + "\" (arkit|facs|livelink)");
      bundle.add(file(w == "livelink" ? "livelink_face.csv" : w + ".csv"),
                 faceweights::format_fixed_rate_track(*format, r.head.tracks.names,
                                                      r.head.tracks.fps, r.head.tracks.values));
    }
    if (selection.speech_wav)
      channels::write_wav(bundle.stage_path(file("speech.wav")), r.head.audio, r.head.sample_rate);
  });
  if (!r.gltf_frames.empty())
    timed("write glTF", [&] {
      // named morph targets (parameters + ARKit shapes) animated by the tracks' weights at the
      // glTF key times (docs/engines.md)
      const auto& tracks = r.head.tracks;
      std::vector<int> column;
      for (const auto& n : muscles::parameter_names()) column.push_back(tracks.column(n));
      std::vector<std::vector<double>> keys;
      for (double t : r.gltf_times) {
        const auto f = std::min<std::size_t>(static_cast<std::size_t>(std::llround(t * tracks.fps)),
                                             tracks.frames() - 1);
        std::vector<double> v(muscles::kParameterCount, 0.0);
        for (std::size_t i = 0; i < v.size(); ++i)
          if (column[i] >= 0) v[i] = tracks.at(f, static_cast<std::size_t>(column[i]));
        keys.push_back(std::move(v));
      }
      const muscles::FaceSolver solver(face.mesh, face.rig);
      muscles::RigGltfOptions gopt;
      gopt.animation_name = "match";
      muscles::write_rig_gltf(bundle.stage_path(file("face.glb")), face, solver, r.gltf_times, keys,
                              gopt);
    });
  timed("charts + key moments", [&] {
    bundle.add(file("charts.png"), core::encode_png(emotion_chart(r)));
    if (!r.key_frames.empty())
      bundle.add(file("key_moments.png"), core::encode_png(key_moment_sheet(r)));
  });
  bundle.add(file("summary.json"), format_summary(r, match));
}

std::string console_summary(const ObieResult& r, const MatchScript& match,
                            const std::string& match_path, const ObieOptions& o,
                            double total_seconds, const std::string& out_dir,
                            const std::vector<std::string>& written) {
  std::ostringstream out;
  out << "Obie (" << r.agent_name << ") watched "
      << (match.title.empty() ? match_path : match.title) << "\n";
  int f = 0, a = 0;
  for (const auto& g : r.goals) {
    out << "  goal " << fixed(g.minute, g.minute == static_cast<int>(g.minute) ? 0 : 1) << "'  "
        << g.team << "  " << g.for_score << "-" << g.against_score << "\n";
    f = g.for_score;
    a = g.against_score;
  }
  out << "  final score " << match.for_team.name << " " << f << "-" << a << " "
      << match.against_team.name << "\n";
  out << "peak emotions:";
  for (const auto& p : r.peaks)
    if (p.value > 0.005)
      out << "  " << p.emotion << " " << fixed(p.value, 2) << " @" << p.minute << "'";
  out << "\nutterances:";
  for (const auto& u : r.utterances) out << "  " << u.minute << "' \"" << u.text << "\"";
  out << "\nframes: " << r.frames << " at " << o.fps << " fps = " << fixed(r.seconds(), 1)
      << " s of animation for " << match.duration << " match minutes (" << r.frames_rendered
      << " rendered " << o.width << "x" << o.height << ")\ntime per stage:\n";
  for (const auto& s : r.timings)
    out << "  " << s.stage << std::string(s.stage.size() < 26 ? 26 - s.stage.size() : 1, ' ')
        << fixed(s.seconds, 2) << " s\n";
  out << "  total" << std::string(21, ' ') << fixed(total_seconds, 2) << " s\n";
  out << "outputs in " << out_dir << ":\n";
  for (const auto& w : written) out << "  " << w << "\n";
  return out.str();
}

KeyMoment parse_key_moment(const std::string& text) {
  const auto colon = text.find(':');
  KeyMoment k;
  const std::string minute = text.substr(0, colon);
  const std::optional<double> m = core::parse_number(minute);
  if (!m || minute.empty())
    throw InvalidInput("key moment \"" + text + "\": expected MINUTE[:LABEL]");
  k.minute = *m;
  if (colon != std::string::npos) k.label = text.substr(colon + 1);
  return k;
}

}  // namespace emoface::obie
