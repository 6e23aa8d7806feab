// mindmap: behaviour of characters driven by mind maps (paper §6–6.1). `simulate` runs stimuli
// through the characters' mind maps and writes mood timelines, triggered actions, mood charts and,
// with a motion graph, the synthesized landmark motion. `crowd` animates and renders the characters
// side by side (issue #9 §2). Thin: parse (options.cpp), call mindmap/mindmotion, write.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

#include "args.hpp"
#include "emoface/cli/cli.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/core/graphviz.hpp"
#include "emoface/core/version.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/mindmap/dot.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/mindmotion/outputs.hpp"
#include "emoface/motiongraph/io.hpp"

namespace mm = emoface::mindmap;
namespace mg = emoface::motiongraph;
namespace mo = emoface::mindmotion;
namespace cli = emoface::cli;
using emoface::mindmap_cli::Args;

namespace {

// The maps of --maps with their actions' labels checked against --graph (or every label).
std::vector<mm::MindMap> read_maps(const Args& a, const mg::MotionGraph* graph) {
  std::vector<std::string> labels;
  if (graph) labels = mo::graph_labels(*graph);
  if (!graph)
    for (mg::Label l : mg::all_labels()) labels.push_back(mg::to_string(l));
  std::vector<mm::MindMap> maps = mm::read_mind_map_dir(a.maps, labels);
  for (const auto& m : maps) mo::character_file_stem(m.character);  // names usable as file stems
  return maps;
}

// --mood-form and --no-vary (§5.1 variation is on by default, issue 19).
void apply_common_options(Args& a) {
  a.sim.mood_form = cli::parse_enum<mm::MoodForm>(a.mood_form, mm::mood_form_from_string,
                                                  "--mood-form", "sum|printed");
  if (a.no_vary) a.motion.synthesis = mg::SynthesisOptions{};
}

int simulate(Args& a) {
  apply_common_options(a);
  a.motion.seed = a.sim.seed;
  std::optional<mg::MotionGraph> graph;
  if (!a.graph.empty()) graph = mg::read_graph(a.graph);
  const std::vector<mm::MindMap> maps = read_maps(a, graph ? &*graph : nullptr);
  const mm::SimulationResult r = mm::simulate(maps, mm::read_events(a.events), a.sim);
  std::unique_ptr<emoface::muscles::FaceSolver> face;
  std::unique_ptr<emoface::bridge::LandmarkFitter> fitter;
  if (a.muscles) {
    if (!graph) throw cli::UsageError("--muscles needs --graph");
    auto f = emoface::facemesh::load_face_or_builtin(a.rig);
    face = std::make_unique<emoface::muscles::FaceSolver>(std::move(f.mesh), std::move(f.rig));
    fitter = std::make_unique<emoface::bridge::LandmarkFitter>(*face);
  }
  emoface::core::OutputBundle bundle;  // every file staged, then all written (or none)
  const std::string report = mo::stage_simulation_outputs(
      bundle, a.out, maps, r,
      {graph ? &*graph : nullptr, fitter.get(), a.motion, a.chart, !a.no_charts, a.weights});
  bundle.commit();
  std::cout << report << mo::simulation_summary(r, maps.size(), bundle.size(), a.out);
  return cli::kExitOk;
}

int crowd(Args& a) {
  apply_common_options(a);
  a.render.view = emoface::facemesh::view_from_string(a.view);  // checked by CLI11 (IsMember)
  mo::CrowdOptions co;
  co.simulation = a.sim;
  co.motion = a.motion;
  co.fps = a.fps;
  co.seed = a.sim.seed;
  try {
    co.validate();
    a.render.validate();
  } catch (const emoface::InvalidInput& e) {
    throw cli::UsageError(e.what());
  }
  const auto t0 = std::chrono::steady_clock::now();
  const mg::MotionGraph graph = a.graph.empty() ? mo::default_motion_graph() : mg::read_graph(a.graph);
  if (a.graph.empty())
    std::cout << "built the default synthetic motion graph in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
              << " s\n";
  const std::vector<mm::MindMap> maps = read_maps(a, &graph);
  // Faces: --rig FILE for everyone, --rig NAME=FILE for one character; the default face otherwise.
  const mo::CrowdFaces crowd_faces(maps, a.rigs);
  mo::CrowdTimings timings;
  const mo::Crowd crowd =
      mo::animate_crowd(maps, mm::read_events(a.events), graph, crowd_faces.rigs(), co, &timings);
  const mo::CrowdRenderer renderer(crowd, crowd_faces.rigs(), a.render);
  cli::ProgressBar bar("mindmap", false);
  emoface::core::OutputBundle bundle;  // every file and the video, or nothing
  const mo::CrowdOutputReport rendering = mo::stage_crowd_outputs(
      bundle, a.out, crowd, renderer,
      {a.chart, !a.no_charts, a.weights, a.video,
       [&](std::size_t k, std::size_t n) { bar.update("rendering", k, n); }});
  bundle.commit();
  std::cout << mo::crowd_report(crowd, renderer, timings, rendering);
  std::cout << "wrote " << bundle.size() << " file(s) to " << a.out << "\n";
  return cli::kExitOk;
}

// The mind map as a picture (issue 19, item 4), with the mood at --time after --events.
int dot(Args& a) {
  const std::vector<mm::MindMap> maps = mm::read_mind_map_dir(a.maps, {});
  if (!a.events.empty() && a.time < 0.0) throw cli::UsageError("--events needs --time (seconds)");
  std::optional<std::vector<mm::Event>> events;
  if (!a.events.empty()) events = mm::read_events(a.events);
  if (std::none_of(maps.begin(), maps.end(),
                   [&](const mm::MindMap& m) { return m.character == a.character; }))
    throw cli::UsageError("--character: no mind map of \"" + a.character + "\" in " + a.maps);
  const std::string dot =
      mm::mind_map_dot_at(maps, a.character, events ? &*events : nullptr, a.time, a.sim);
  emoface::core::write_dot(dot, a.out);
  std::cout << "wrote " << a.out << "\n";
  return cli::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Mind maps as behaviour controllers (paper §6): stimuli -> mood -> actions -> motion."};
  app.require_subcommand(1);
  app.set_version_flag("--version", emoface::kGenerator);
  app.footer("Example:\n  mindmap simulate --maps data/mindmap/characters --events data/mindmap/events.ndjson "
             "--out sim --seed 1\n  mindmap crowd --maps data/mindmap/crowd --events data/mindmap/crowd_events.ndjson "
             "--out crowd --video\n  mindmap check --maps data/mindmap/characters\n"
             "Exit codes: 0 ok, 1 usage, 2 bad input, 3 numerical, 4 internal.");
  Args a;
  const emoface::mindmap_cli::Commands cmd = emoface::mindmap_cli::add_commands(app, a);
  if (auto rc = cli::parse(app, argc, argv)) return *rc;
  return cli::run("mindmap", [&]() -> int {
    if (*cmd.simulate) return simulate(a);
    if (*cmd.crowd) return crowd(a);
    if (*cmd.dot) return dot(a);
    std::vector<std::string> labels;  // check: the actions' labels only against a given graph
    if (!a.graph.empty()) labels = mo::graph_labels(mg::read_graph(a.graph));
    for (const auto& m : mm::read_mind_map_dir(a.maps, labels)) std::cout << mm::summary(m) << "\n";
    return cli::kExitOk;
  });
}
