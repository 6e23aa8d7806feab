#include "emoface/mindmotion/outputs.hpp"

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "emoface/core/errors.hpp"
#include "emoface/core/image.hpp"
#include "emoface/core/video.hpp"
#include "emoface/faceweights/tracks.hpp"
#include "emoface/mindmap/chart.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/mindmotion/muscle_tracks.hpp"
#include "emoface/motiongraph/io.hpp"

namespace emoface::mindmotion {

using emoface::InvalidInput;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}
double cpu_since(std::clock_t c0) {
  return static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
}

std::string chart_png(const mindmap::SimulationResult& r, const mindmap::MindMap& map,
                      std::size_t c, const mindmap::ChartOptions& options) {
  return core::encode_png(mindmap::mood_chart(r, map, c, options));
}

}  // namespace

std::string character_file_stem(const std::string& name) {
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') ||
        name[0] == '.')
      throw InvalidInput("character \"" + name +
                         "\": only letters, digits, '_', '-' and '.' "
                         "may be used in a character name that names output files");
  return name;
}

void stage_weight_files(core::OutputBundle& bundle, const std::string& stem,
                        const std::vector<muscles::ParameterFrame>& frames,
                        const std::vector<std::string>& formats) {
  if (frames.empty()) return;
  std::vector<double> times;
  std::vector<std::vector<double>> values;
  for (const auto& f : frames) {
    times.push_back(f.time);
    values.push_back(f.values);
  }
  const double fps = frames.size() > 1 ? std::round(1.0 / (times[1] - times[0])) : 25.0;
  for (const auto& w : formats) {
    const auto format = faceweights::track_format_from_string(w + "-csv");
    if (!format) throw InvalidInput("unknown weight format \"" + w + "\" (arkit|facs|livelink)");
    bundle.add(
        stem + "_" + w + ".csv",
        faceweights::format_weight_track(*format, muscles::parameter_names(), times, values, fps));
  }
}

std::string stage_simulation_outputs(core::OutputBundle& bundle, const std::string& dir,
                                     const std::vector<mindmap::MindMap>& maps,
                                     const mindmap::SimulationResult& r,
                                     const SimulationOutputs& o) {
  if (o.fitter && !o.graph) throw InvalidInput("muscle tracks need a motion graph");
  std::ostringstream report;
  bundle.add(dir + "/actions.ndjson", mindmap::actions_to_ndjson(r.actions));
  bundle.add(dir + "/actions.csv", mindmap::actions_to_csv(r.actions));
  for (std::size_t c = 0; c < maps.size(); ++c) {
    const std::string stem = dir + "/" + character_file_stem(maps[c].character);
    bundle.add(stem + "_mood.csv", mindmap::mood_timeline_csv(r, maps[c], c));
    if (o.charts) bundle.add(stem + "_mood.png", chart_png(r, maps[c], c, o.chart));
    if (!o.graph) continue;
    const auto motion =
        synthesize_behaviour(*o.graph, r.actions, maps[c].character, c, r.duration, o.motion);
    bundle.add(stem + "_motion.json", motiongraph::database_to_json(to_database(*o.graph, motion)));
    bundle.add(stem + "_segments.csv", segments_csv(motion));
    if (o.fitter) {
      TrackFitSummary fs;
      const auto frames = fit_muscle_tracks(*o.fitter, *o.graph, motion, &fs);
      bundle.add(stem + "_muscles.csv", muscles::format_parameter_frames_csv(frames));
      stage_weight_files(bundle, stem, frames, o.weights);
      report << maps[c].character << ": muscle fit RMS residual mean " << fs.mean_rms * 1e3
             << " mm, max " << fs.max_rms * 1e3 << " mm, " << fs.not_converged
             << " frame(s) at the iteration limit\n";
    }
    report << maps[c].character << ": " << motion.frames.size() << " frames, "
           << motion.segments.size() << " segments, " << motion.dropped_hints
           << " decay hints dropped (face busy)\n";
  }
  return report.str();
}

CrowdOutputReport stage_crowd_outputs(core::OutputBundle& bundle, const std::string& dir,
                                      const Crowd& crowd, const CrowdRenderer& renderer,
                                      const CrowdOutputs& o) {
  CrowdOutputReport rep;
  bundle.add(dir + "/actions.ndjson", mindmap::actions_to_ndjson(crowd.simulation.actions));
  bundle.add(dir + "/actions.csv", mindmap::actions_to_csv(crowd.simulation.actions));
  for (std::size_t c = 0; c < crowd.characters.size(); ++c) {
    const auto& ch = crowd.characters[c];
    const std::string stem = dir + "/" + character_file_stem(ch.name);
    bundle.add(stem + "_muscles.csv", muscles::format_parameter_frames_csv(ch.tracks));
    stage_weight_files(bundle, stem, ch.tracks, o.weights);
    bundle.add(stem + "_mood.csv", mindmap::mood_timeline_csv(crowd.simulation, crowd.maps[c], c));
    bundle.add(stem + "_segments.csv", segments_csv(ch.motion));
    if (o.charts)
      bundle.add(stem + "_mood.png", chart_png(crowd.simulation, crowd.maps[c], c, o.chart));
  }
  bundle.add(dir + "/key_moments.csv", key_moments_csv(crowd));
  auto t0 = Clock::now();
  std::clock_t c0 = std::clock();
  const core::Image sheet = renderer.key_moment_sheet();
  for (const auto& km : crowd.key_moments) rep.rendered += km.frames.size();
  bundle.add(dir + "/key_moments.png", core::encode_png(sheet));
  rep.render_seconds = since(t0);
  rep.render_cpu = cpu_since(c0);
  if (o.video) {
    core::VideoOptions vo;
    vo.width = renderer.width();
    vo.height = renderer.height();
    vo.fps = crowd.fps;
    t0 = Clock::now();
    c0 = std::clock();
    core::VideoWriter writer(bundle.stage_path(dir + "/crowd.mp4"), vo);
    for (std::size_t k = 0; k < crowd.frame_count(); ++k) {
      writer.add_frame(renderer.frame(k));
      if (o.progress) o.progress(k + 1, crowd.frame_count());
    }
    writer.finish();
    rep.render_seconds += since(t0);
    rep.render_cpu += cpu_since(c0);  // this process only (ffmpeg's encoding is not counted)
    rep.rendered += crowd.frame_count() * crowd.characters.size();
  }
  return rep;
}

std::string simulation_summary(const mindmap::SimulationResult& result, std::size_t characters,
                               std::size_t files, const std::string& dir) {
  std::ostringstream out;  // default stream formatting of doubles (6 significant digits)
  for (const auto& s : result.copied)
    out << s.character << " learnt \"" << s.stimulus << "\" from " << s.from << " at " << s.time
        << " s\n";
  out << result.actions.size() << " action(s) by " << characters << " character(s) over "
      << result.duration << " s; wrote " << files << " file(s) to " << dir << "\n";
  return out.str();
}

std::string crowd_report(const Crowd& crowd, const CrowdRenderer& renderer,
                         const CrowdTimings& timings, const CrowdOutputReport& rep) {
  std::ostringstream out;
  for (const auto& ch : crowd.characters) {
    std::size_t actions = 0;
    for (const auto& x : crowd.simulation.actions) actions += x.character == ch.name ? 1 : 0;
    out << ch.name << ": " << actions << " action(s), " << ch.motion.segments.size()
        << " segments, fit RMS mean " << ch.fit.mean_rms * 1e3 << " mm (max "
        << ch.fit.max_rms * 1e3 << " mm)\n";
  }
  for (const auto& s : crowd.simulation.copied)
    out << s.character << " learnt \"" << s.stimulus << "\" from " << s.from << " at " << s.time
        << " s\n";
  const auto distance = face_distances(crowd);  // issue 19: how different the faces are
  out << "face distance (mean per-frame parameter distance):";
  char buf[1024];
  for (std::size_t i = 0; i < distance.size(); ++i)
    for (std::size_t j = i + 1; j < distance.size(); ++j) {
      std::snprintf(buf, sizeof buf, " %s-%s %.3f", crowd.characters[i].name.c_str(),
                    crowd.characters[j].name.c_str(), distance[i][j]);
      out << buf;
    }
  out << "\n";
  const std::size_t n = crowd.characters.size();
  const double frames = static_cast<double>(crowd.frame_count());
  std::snprintf(buf, sizeof buf,
                "%zu characters, %zu frames at %g fps (%g s), %zu key moments, frame %dx%d\n", n,
                crowd.frame_count(), crowd.fps, crowd.simulation.duration, crowd.key_moments.size(),
                renderer.width(), renderer.height());
  out << buf;
  const double faces = frames * static_cast<double>(n);
  std::snprintf(
      buf, sizeof buf,
      "time (wall / CPU): simulation %.3f / %.3f s; synthesis %.3f / %.3f s (%.3f ms CPU per "
      "frame and character); fitting %.3f / %.3f s (%.3f ms CPU per frame and character); "
      "deformation+render %.3f / %.3f s for %zu faces (%.2f ms CPU per face)\n",
      timings.simulation.wall, timings.simulation.cpu, timings.synthesis.wall,
      timings.synthesis.cpu, 1e3 * timings.synthesis.cpu / faces, timings.fitting.wall,
      timings.fitting.cpu, 1e3 * timings.fitting.cpu / faces, rep.render_seconds, rep.render_cpu,
      rep.rendered, rep.rendered ? 1e3 * rep.render_cpu / static_cast<double>(rep.rendered) : 0.0);
  out << buf;
  return out.str();
}

}  // namespace emoface::mindmotion
