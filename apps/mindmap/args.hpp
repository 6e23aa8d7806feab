#pragma once
// The parsed command line of mindmap (options.cpp registers it; main.cpp runs the subcommand).
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "emoface/mindmap/chart.hpp"
#include "emoface/mindmap/simulation.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/mindmotion/crowd.hpp"

namespace emoface::mindmap_cli {

struct Args {
  std::string maps, events, out, graph, rig, mood_form = "sum";
  mindmap::SimulationOptions sim;
  mindmap::ChartOptions chart;
  mindmotion::BehaviourMotionOptions motion;
  bool no_charts = false, muscles = false;
  // crowd
  std::vector<std::string> rigs;
  mindmotion::CrowdRenderOptions render;
  std::string view = "front";
  double fps = 0.0;
  bool video = false, no_vary = false;
  std::vector<std::string> weights;  // arkit, facs, livelink: also write <name>_<format>.csv
  // dot
  std::string character;
  double time = -1.0;
};

struct Commands {
  CLI::App *simulate, *crowd, *dot, *check;
};
/// Registers the four subcommands and their options on `app`, bound to `a`.
Commands add_commands(CLI::App& app, Args& a);

}  // namespace emoface::mindmap_cli
