// mindmap: behaviour of characters driven by mind maps (paper §6–6.1). `simulate` runs stimuli
// through the characters' mind maps and writes mood timelines, triggered actions, mood charts and,
// with a motion graph, the synthesized landmark motion. Thin: parse, call mindmap/mindmotion, write.
#include <filesystem>
#include <iostream>

#include "emoface/cli/cli.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/version.hpp"
#include "emoface/mindmap/chart.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/mindmotion/muscle_tracks.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/motiongraph/render.hpp"

namespace mm = emoface::mindmap;
namespace mg = emoface::motiongraph;
namespace cli = emoface::cli;

namespace {

struct Args {
  std::string maps, events, out, graph, rig, mood_form = "sum";
  mm::SimulationOptions sim;
  mm::ChartOptions chart;
  emoface::mindmotion::BehaviourMotionOptions motion;
  bool no_charts = false, muscles = false;
};

std::string file_stem(const std::string& name) {  // character names become file names: keep them portable
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') || name[0] == '.')
      throw emoface::InvalidInput("character \"" + name + "\": only letters, digits, '_', '-' and '.' "
                                  "may be used in a character name that names output files");
  return name;
}

int simulate(Args& a) {
  a.sim.mood_form = cli::parse_enum<mm::MoodForm>(a.mood_form, mm::mood_form_from_string, "--mood-form", "sum|printed");
  a.motion.seed = a.sim.seed;
  std::optional<mg::MotionGraph> graph;
  std::vector<std::string> labels;
  if (!a.graph.empty()) {
    graph = mg::read_graph(a.graph);
    labels = emoface::mindmotion::graph_labels(*graph);
  } else {
    for (mg::Label l : mg::all_labels()) labels.push_back(mg::to_string(l));
  }
  const std::vector<mm::MindMap> maps = mm::read_mind_map_dir(a.maps, labels);
  for (const auto& m : maps) file_stem(m.character);
  const mm::SimulationResult r = mm::simulate(maps, mm::read_events(a.events), a.sim);
  std::unique_ptr<emoface::muscles::FaceSolver> face;
  std::unique_ptr<emoface::bridge::LandmarkFitter> fitter;
  if (a.muscles) {
    if (!graph) throw cli::UsageError("--muscles needs --graph");
    auto f = a.rig.empty() ? emoface::facemesh::make_default_face() : emoface::facemesh::load_face(a.rig);
    face = std::make_unique<emoface::muscles::FaceSolver>(std::move(f.mesh), std::move(f.rig));
    fitter = std::make_unique<emoface::bridge::LandmarkFitter>(*face);
  }

  // Everything is computed before anything is written.
  std::vector<std::pair<std::string, std::string>> files;
  const std::string dir = a.out + "/";
  files.emplace_back(dir + "actions.ndjson", mm::actions_to_ndjson(r.actions));
  files.emplace_back(dir + "actions.csv", mm::actions_to_csv(r.actions));
  for (std::size_t c = 0; c < maps.size(); ++c) {
    const std::string stem = dir + maps[c].character;
    files.emplace_back(stem + "_mood.csv", mm::mood_timeline_csv(r, maps[c], c));
    if (!a.no_charts) {
      const mm::Raster chart = mm::mood_chart(r, maps[c], c, a.chart);
      mg::Image img(chart.width, chart.height);
      img.rgb = chart.rgb;
      files.emplace_back(stem + "_mood.png", mg::encode_png(img));
    }
    if (graph) {
      const auto motion = emoface::mindmotion::synthesize_behaviour(*graph, r.actions, maps[c].character, c,
                                                                    r.duration, a.motion);
      files.emplace_back(stem + "_motion.json", mg::database_to_json(emoface::mindmotion::to_database(*graph, motion)));
      files.emplace_back(stem + "_segments.csv", emoface::mindmotion::segments_csv(motion));
      if (fitter) {
        emoface::mindmotion::TrackFitSummary fs;
        const auto frames = emoface::mindmotion::fit_muscle_tracks(*fitter, *graph, motion, &fs);
        files.emplace_back(stem + "_muscles.csv", emoface::muscles::format_parameter_frames_csv(frames));
        std::cout << maps[c].character << ": muscle fit RMS residual mean " << fs.mean_rms * 1e3 << " mm, max "
                  << fs.max_rms * 1e3 << " mm, " << fs.not_converged << " frame(s) at the iteration limit\n";
      }
      std::cout << maps[c].character << ": " << motion.frames.size() << " frames, " << motion.segments.size()
                << " segments, " << motion.dropped_hints << " decay hints dropped (face busy)\n";
    }
  }
  std::filesystem::create_directories(a.out);
  for (const auto& [path, content] : files) emoface::core::write_file_atomic(path, content);
  for (const auto& s : r.copied)
    std::cout << s.character << " learnt \"" << s.stimulus << "\" from " << s.from << " at " << s.time << " s\n";
  std::cout << r.actions.size() << " action(s) by " << maps.size() << " character(s) over " << r.duration
            << " s; wrote " << files.size() << " file(s) to " << a.out << "\n";
  return cli::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Mind maps as behaviour controllers (paper §6): stimuli -> mood -> actions -> motion."};
  app.require_subcommand(1);
  app.set_version_flag("--version", emoface::kGenerator);
  app.footer("Example:\n  mindmap simulate --maps data/mindmap/characters --events data/mindmap/events.ndjson "
             "--out sim --seed 1\n  mindmap check --maps data/mindmap/characters\n"
             "Exit codes: 0 ok, 1 usage, 2 bad input, 3 numerical, 4 internal.");
  Args a;
  auto* sim = app.add_subcommand("simulate", "run stimuli through the characters' mind maps");
  sim->add_option("--maps", a.maps, "directory of mind maps (*.json, one character each)")->required();
  sim->add_option("--events", a.events, "stimuli (NDJSON, see docs/mindmap.md)")->required();
  sim->add_option("--out", a.out, "output directory")->required();
  sim->add_option("--graph", a.graph, "motion graph (mgraph build): also synthesize landmark motion");
  sim->add_flag("--muscles", a.muscles, "also fit muscle tracks (faceanim CSV) to the motion (needs --graph)");
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
  sim->add_option("--hint-fraction", a.motion.hint_path_fraction, "path fraction of decay hints")
      ->capture_default_str();
  sim->add_option("--chart-width", a.chart.width, "chart pixels")->capture_default_str();
  sim->add_option("--chart-height", a.chart.height, "chart pixels")->capture_default_str();
  sim->add_flag("--no-charts", a.no_charts, "do not write PNG mood charts");
  auto* check = app.add_subcommand("check", "validate mind maps (and their labels against a graph)");
  check->add_option("--maps", a.maps, "directory of mind maps")->required();
  check->add_option("--graph", a.graph, "motion graph whose labels the actions must use");
  if (auto rc = cli::parse(app, argc, argv)) return *rc;

  return cli::run("mindmap", [&]() -> int {
    if (*sim) return simulate(a);
    std::vector<std::string> labels;
    if (!a.graph.empty()) labels = emoface::mindmotion::graph_labels(mg::read_graph(a.graph));
    const auto maps = mm::read_mind_map_dir(a.maps, labels);
    for (const auto& m : maps)
      std::cout << m.character << ": " << m.emotion_count() << " emotion nodes, " << m.actions.size()
                << " actions, " << m.stimulus_edges.size() + m.response_edges.size() + m.chain_edges.size()
                << " edges\n";
    return cli::kExitOk;
  });
}
