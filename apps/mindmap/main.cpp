// mindmap: behaviour of characters driven by mind maps (paper §6–6.1). `simulate` runs stimuli
// through the characters' mind maps and writes mood timelines, triggered actions, mood charts and,
// with a motion graph, the synthesized landmark motion. `crowd` animates and renders the characters
// side by side (issue #9 §2). Thin: parse, call mindmap/mindmotion, write.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>

#include "emoface/cli/cli.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/core/graphviz.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/version.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/mindmap/chart.hpp"
#include "emoface/mindmap/dot.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/mindmotion/crowd.hpp"
#include "emoface/mindmotion/outputs.hpp"
#include "emoface/motiongraph/io.hpp"

namespace mm = emoface::mindmap;
namespace mg = emoface::motiongraph;
namespace cli = emoface::cli;
namespace mo = emoface::mindmotion;

namespace {

struct Args {
  std::string maps, events, out, graph, rig, mood_form = "sum";
  mm::SimulationOptions sim;
  mm::ChartOptions chart;
  emoface::mindmotion::BehaviourMotionOptions motion;
  bool no_charts = false, muscles = false;
  // crowd
  std::vector<std::string> rigs;
  emoface::mindmotion::CrowdRenderOptions render;
  std::string view = "front";
  double fps = 0.0;
  bool video = false, no_vary = false;
  std::vector<std::string> weights;  // arkit, facs, livelink: also write <name>_<format>.csv
  // dot
  std::string character;
  double time = -1.0;
};

// §5.1 variation is on by default (issue 19); --no-vary switches it off.
void add_motion_options(CLI::App* cmd, Args& a) {
  cmd->add_flag("--no-vary", a.no_vary, "no motion variation (paper §5.1): the same label gives the same motion");
  cmd->add_option("--replace", a.motion.synthesis.replace_probability,
                  "variation: probability of replacing a path node by a neighbour")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--return-after", a.motion.return_after,
                  "seconds after an animation before the face returns to neutral (0 = never)")
      ->check(CLI::Range(0.0, 1e5))
      ->capture_default_str();
}

void apply_motion_options(Args& a) {
  if (a.no_vary) a.motion.synthesis = emoface::motiongraph::SynthesisOptions{};  // no §5.1 variation
}

int simulate(Args& a) {
  a.sim.mood_form = cli::parse_enum<mm::MoodForm>(a.mood_form, mm::mood_form_from_string, "--mood-form", "sum|printed");
  a.motion.seed = a.sim.seed;
  apply_motion_options(a);
  std::optional<mg::MotionGraph> graph;
  std::vector<std::string> labels;
  if (!a.graph.empty()) {
    graph = mg::read_graph(a.graph);
    labels = mo::graph_labels(*graph);
  } else {
    for (mg::Label l : mg::all_labels()) labels.push_back(mg::to_string(l));
  }
  const std::vector<mm::MindMap> maps = mm::read_mind_map_dir(a.maps, labels);
  for (const auto& m : maps) mo::character_file_stem(m.character);
  const mm::SimulationResult r = mm::simulate(maps, mm::read_events(a.events), a.sim);
  std::unique_ptr<emoface::muscles::FaceSolver> face;
  std::unique_ptr<emoface::bridge::LandmarkFitter> fitter;
  if (a.muscles) {
    if (!graph) throw cli::UsageError("--muscles needs --graph");
    auto f = a.rig.empty()          ? emoface::facemesh::make_default_face()
             : a.rig == "generic" ? emoface::facemesh::make_generic_face()
                                  : emoface::facemesh::load_face(a.rig);
    face = std::make_unique<emoface::muscles::FaceSolver>(std::move(f.mesh), std::move(f.rig));
    fitter = std::make_unique<emoface::bridge::LandmarkFitter>(*face);
  }
  // Every file staged, then all written (or none: core::OutputBundle).
  emoface::core::OutputBundle bundle;
  const std::string report = mo::stage_simulation_outputs(
      bundle, a.out, maps, r,
      {graph ? &*graph : nullptr, fitter.get(), a.motion, a.chart, !a.no_charts, a.weights});
  bundle.commit();
  std::cout << report;
  for (const auto& s : r.copied)
    std::cout << s.character << " learnt \"" << s.stimulus << "\" from " << s.from << " at " << s.time << " s\n";
  std::cout << r.actions.size() << " action(s) by " << maps.size() << " character(s) over "
            << r.duration << " s; wrote " << bundle.size() << " file(s) to " << a.out << "\n";
  return cli::kExitOk;
}

int crowd(Args& a) {
  a.sim.mood_form = cli::parse_enum<mm::MoodForm>(a.mood_form, mm::mood_form_from_string, "--mood-form", "sum|printed");
  a.render.view =
      emoface::facemesh::view_from_string(a.view);  // checked by CLI11 (IsMember) when parsing
  apply_motion_options(a);
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
  const std::vector<mm::MindMap> maps = mm::read_mind_map_dir(a.maps, mo::graph_labels(graph));
  for (const auto& m : maps) mo::character_file_stem(m.character);
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
  std::size_t c = maps.size();
  for (std::size_t i = 0; i < maps.size(); ++i)
    if (maps[i].character == a.character) c = i;
  if (c == maps.size()) throw cli::UsageError("--character: no mind map of \"" + a.character + "\" in " + a.maps);
  mm::MindMapDotOptions o;
  mm::MindMap shown = maps[c];
  if (!a.events.empty()) {
    if (a.time < 0.0) throw cli::UsageError("--events needs --time (seconds)");
    a.sim.duration = a.time;
    const std::vector<mm::Event> events = mm::read_events(a.events);
    o.mood = mm::mood_at(mm::simulate(maps, events, a.sim), c, a.time);
    shown = mm::map_at(maps, events, c, a.time, a.sim);  // context/affection changed by then
  } else if (a.time >= 0.0) {
    o.mood = maps[c].traits.starting_mood;  // no stimuli: the starting mood
  }
  emoface::core::write_dot(mm::mind_map_dot(shown, o), a.out);
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
  auto* sim = app.add_subcommand("simulate", "run stimuli through the characters' mind maps");
  sim->add_option("--maps", a.maps, "directory of mind maps (*.json, one character each)")->required();
  sim->add_option("--events", a.events, "stimuli (NDJSON, see docs/mindmap.md)")->required();
  sim->add_option("--out", a.out, "output directory")->required();
  sim->add_option("--graph", a.graph, "motion graph (mgraph build): also synthesize landmark motion");
  sim->add_flag("--muscles", a.muscles, "also fit muscle tracks (faceanim CSV) to the motion (needs --graph)");
  sim->add_option("--weights", a.weights,
                  "arkit,facs,livelink: with --muscles, also write <name>_arkit.csv, _facs.csv, "
                  "_livelink.csv")
      ->delimiter(',')
      ->check(CLI::IsMember({"arkit", "facs", "livelink"}));
  sim->add_option("--rig", a.rig, "rig for --muscles (default: the built-in default face)");
  sim->add_option("--seed", a.sim.seed, "random seed (near-tie choices, motion variation)")->capture_default_str();
  sim->add_option("--mood-form", a.mood_form, "sum|printed reading of eq. 4")->capture_default_str();
  sim->add_option("--frame-rate", a.sim.frame_rate, "mood samples per second")->capture_default_str();
  sim->add_option("--duration", a.sim.duration, "seconds (0 = until the last decay ends)")->capture_default_str();
  sim->add_option("--tie-tolerance", a.sim.tie_tolerance, "near-equal edge tolerance")->capture_default_str();
  sim->add_option("--chain-delay", a.sim.chain_delay, "seconds between chained actions")->capture_default_str();
  sim->add_option("--decay-interval", a.sim.decay_interval, "seconds between decay hints")->capture_default_str();
  sim->add_option("--propagate", a.sim.propagation_depth, "hops a performed stimulus travels to the others (0 = off)")
      ->capture_default_str();
  sim->add_flag("--to-addressee", a.sim.propagate_to_addressee,
                "with --propagate: an action aimed at a character reaches only that character");
  sim->add_option("--hint-fraction", a.motion.hint_path_fraction, "path fraction of decay hints")
      ->capture_default_str();
  add_motion_options(sim, a);
  sim->add_option("--chart-width", a.chart.width, "chart pixels")->capture_default_str();
  sim->add_option("--chart-height", a.chart.height, "chart pixels")->capture_default_str();
  sim->add_flag("--no-charts", a.no_charts, "do not write PNG mood charts");
  auto* cr = app.add_subcommand("crowd", "animate several characters reacting to the same stimuli, side by side");
  cr->add_option("--maps", a.maps, "directory of mind maps (*.json, 2 to 16 characters)")->required();
  cr->add_option("--events", a.events, "shared stimuli (NDJSON, see docs/mindmap.md)")->required();
  cr->add_option("--out", a.out, "output directory")->required();
  cr->add_option("--graph", a.graph, "motion graph (mgraph build); default: mgraph generate + build defaults (~3 s)");
  cr->add_option("--rig", a.rigs, "rig for everyone (FILE) or for one character (NAME=FILE); default: the built-in face");
  cr->add_option("--weights", a.weights,
                 "arkit,facs,livelink: also write <name>_arkit.csv, _facs.csv, _livelink.csv")
      ->delimiter(',')
      ->check(CLI::IsMember({"arkit", "facs", "livelink"}));
  cr->add_option("--seed", a.sim.seed, "random seed (near-tie choices, motion variation)")->capture_default_str();
  cr->add_option("--fps", a.fps, "frames per second of tracks, mood rows and video (0 = the graph's)")->capture_default_str();
  cr->add_option("--width", a.render.face_width, "pixels per face (height = 7/6 of it)")->capture_default_str();
  cr->add_option("--strip-height", a.render.strip_height, "pixels of the mood strip under each face")->capture_default_str();
  cr->add_option("--columns", a.render.columns, "grid columns (0 = one row up to 4 characters)")->capture_default_str();
  cr->add_option("--view", a.view, "front|threequarter")
      ->check(CLI::IsMember({"front", "threequarter"}))
      ->capture_default_str();
  cr->add_flag("--video", a.video, "also write crowd.mp4 (needs the ffmpeg binary)");
  cr->add_option("--mood-form", a.mood_form, "sum|printed reading of eq. 4")->capture_default_str();
  cr->add_option("--duration", a.sim.duration, "seconds (0 = until the last decay ends)")->capture_default_str();
  cr->add_option("--propagate", a.sim.propagation_depth, "hops a performed stimulus travels to the others (0 = off)")
      ->capture_default_str();
  cr->add_flag("--no-charts", a.no_charts, "do not write PNG mood charts");
  add_motion_options(cr, a);
  auto* dt = app.add_subcommand("dot", "draw a mind map (Graphviz DOT; .svg/.png/.pdf rendered by dot)");
  dt->add_option("--maps", a.maps, "directory of mind maps")->required();
  dt->add_option("--character", a.character, "whose mind map")->required();
  dt->add_option("--events", a.events, "stimuli to run first (NDJSON), for the mood at --time");
  dt->add_option("--time", a.time, "seconds: show the mood at this time (starting mood without --events)");
  dt->add_option("--seed", a.sim.seed, "random seed of the simulation")->capture_default_str();
  dt->add_option("--out", a.out, "output: .dot (text), .svg, .png or .pdf (needs Graphviz)")->required();
  auto* check = app.add_subcommand("check", "validate mind maps (and their labels against a graph)");
  check->add_option("--maps", a.maps, "directory of mind maps")->required();
  check->add_option("--graph", a.graph, "motion graph whose labels the actions must use");
  if (auto rc = cli::parse(app, argc, argv)) return *rc;

  return cli::run("mindmap", [&]() -> int {
    if (*sim) return simulate(a);
    if (*cr) return crowd(a);
    if (*dt) return dot(a);
    std::vector<std::string> labels;
    if (!a.graph.empty()) labels = mo::graph_labels(mg::read_graph(a.graph));
    const auto maps = mm::read_mind_map_dir(a.maps, labels);
    for (const auto& m : maps)
      std::cout << m.character << ": " << m.emotion_count() << " emotion nodes, " << m.actions.size()
                << " actions, " << m.stimulus_edges.size() + m.response_edges.size() + m.chain_edges.size()
                << " edges\n";
    return cli::kExitOk;
  });
}
