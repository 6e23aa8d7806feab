#pragma once
// The files of `mindmap simulate` and `mindmap crowd` as library calls (issue 18, item 4): every
// output of a run staged into one core::OutputBundle (all written or none), and the console
// reports. docs/mindmap.md, "CLI".
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "emoface/bridge/landmark_fit.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/mindmap/chart.hpp"
#include "emoface/mindmap/mind_map.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/mindmotion/crowd.hpp"
#include "emoface/motiongraph/graph.hpp"
#include "emoface/muscles/parameters.hpp"

namespace emoface::mindmotion {

/// A character name used as a file-name stem: letters, digits, '_', '-' and '.' (not leading);
/// InvalidInput naming the character otherwise.
std::string character_file_stem(const std::string& name);

/// The muscle tracks as "<stem>_<format>.csv" for each of `formats` (arkit, facs, livelink:
/// faceweights' shared writer; the frame rate from the first two frames).
void stage_weight_files(core::OutputBundle& bundle, const std::string& stem,
                        const std::vector<muscles::ParameterFrame>& frames,
                        const std::vector<std::string>& formats);

struct SimulationOutputs {
  const motiongraph::MotionGraph* graph = nullptr;  ///< also synthesize the landmark motion
  const bridge::LandmarkFitter* fitter = nullptr;   ///< also fit muscle tracks (needs graph)
  BehaviourMotionOptions motion;
  mindmap::ChartOptions chart;
  bool charts = true;                ///< <name>_mood.png
  std::vector<std::string> weights;  ///< with fitter: <name>_<format>.csv
};

/// Stages `mindmap simulate`'s files in `dir`: actions.ndjson, actions.csv, and per character
/// <name>_mood.csv, _mood.png, with a graph _motion.json and _segments.csv, with a fitter
/// _muscles.csv and the weight CSVs. Returns the per-character report lines.
std::string stage_simulation_outputs(core::OutputBundle& bundle, const std::string& dir,
                                     const std::vector<mindmap::MindMap>& maps,
                                     const mindmap::SimulationResult& result,
                                     const SimulationOutputs& options);

/// The end of `mindmap simulate`'s console report: one line per stimulus a character learnt
/// ("<who> learnt \"<stimulus>\" from <whom> at <t> s"), then "<n> action(s) by <m> character(s)
/// over <d> s; wrote <files> file(s) to <dir>".
std::string simulation_summary(const mindmap::SimulationResult& result, std::size_t characters,
                               std::size_t files, const std::string& dir);

struct CrowdOutputs {
  mindmap::ChartOptions chart;
  bool charts = true;
  std::vector<std::string> weights;
  bool video = false;  ///< crowd.mp4 (ffmpeg), rendered into a staged path of the bundle
  /// Called while the video is rendered (frames done, total).
  std::function<void(std::size_t, std::size_t)> progress;
};

struct CrowdOutputReport {
  std::size_t rendered = 0;                       ///< faces rendered (key moments + video)
  double render_seconds = 0.0, render_cpu = 0.0;  ///< wall / this process's CPU
};

/// Stages `mindmap crowd`'s files in `dir`: actions, per character muscles, weights, mood CSV,
/// segments and mood chart, key_moments.csv and .png, and crowd.mp4 when asked.
CrowdOutputReport stage_crowd_outputs(core::OutputBundle& bundle, const std::string& dir,
                                      const Crowd& crowd, const CrowdRenderer& renderer,
                                      const CrowdOutputs& options);

/// The crowd's console report: per character actions, segments and fit; learnt stimuli; face
/// distances; size, frames and timings.
std::string crowd_report(const Crowd& crowd, const CrowdRenderer& renderer,
                         const CrowdTimings& timings, const CrowdOutputReport& rendering);

}  // namespace emoface::mindmotion
