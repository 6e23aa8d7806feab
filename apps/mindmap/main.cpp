// mindmap: behaviour of characters driven by mind maps (paper §6–6.1). `simulate` runs stimuli
// through the characters' mind maps and writes mood timelines, triggered actions, mood charts and,
// with a motion graph, the synthesized landmark motion. `crowd` animates and renders the characters
// side by side (issue #9 §2). Thin: parse, call mindmap/mindmotion, write.
#include <cmath>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "emoface/cli/cli.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/version.hpp"
#include "emoface/core/video.hpp"
#include "emoface/core/graphviz.hpp"
#include "emoface/mindmap/chart.hpp"
#include "emoface/mindmap/dot.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/mindmotion/behaviour.hpp"
#include "emoface/mindmotion/crowd.hpp"
#include "emoface/mindmotion/muscle_tracks.hpp"
#include "emoface/faceweights/tracks.hpp"
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

// The muscle tracks as ARKit / FACS / Live Link Face CSV (faceweights' shared writer).
void add_weight_files(std::vector<std::pair<std::string, std::string>>& files, const std::string& stem,
                      const std::vector<emoface::muscles::ParameterFrame>& frames,
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
    files.emplace_back(stem + "_" + w + ".csv",
                       emoface::faceweights::format_weight_track(
                           *emoface::faceweights::track_format_from_string(w + "-csv"),
                           emoface::muscles::parameter_names(), times, values, fps));
  }
}


// Writes DOT text, or renders it with Graphviz by the extension (.svg, .png, .pdf).
void write_dot(const std::string& dot, const std::string& out) {
  const auto ext = std::filesystem::path(out).extension().string();
  if (ext == ".svg" || ext == ".png" || ext == ".pdf") {
    emoface::core::render_dot(dot, out);
  } else {
    emoface::core::write_file_atomic(out, dot);
  }
}

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
  apply_motion_options(a);
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
    auto f = a.rig.empty()          ? emoface::facemesh::make_default_face()
             : a.rig == "generic" ? emoface::facemesh::make_generic_face()
                                  : emoface::facemesh::load_face(a.rig);
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
        add_weight_files(files, stem, frames, a.weights);
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


using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
double cpu_since(std::clock_t c0) { return static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC; }

std::string png(const emoface::facemesh::Image& image) { return emoface::facemesh::encode_png(image); }

int crowd(Args& a) {
  namespace mo = emoface::mindmotion;
  namespace fm = emoface::facemesh;
  a.sim.mood_form = cli::parse_enum<mm::MoodForm>(a.mood_form, mm::mood_form_from_string, "--mood-form", "sum|printed");
  a.render.view = fm::view_from_string(a.view);  // checked by CLI11 (IsMember) when parsing
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
  auto t0 = Clock::now();
  const mg::MotionGraph graph = a.graph.empty() ? mo::default_motion_graph() : mg::read_graph(a.graph);
  if (a.graph.empty()) std::cout << "built the default synthetic motion graph in " << since(t0) << " s\n";
  const std::vector<mm::MindMap> maps = mm::read_mind_map_dir(a.maps, mo::graph_labels(graph));
  for (const auto& m : maps) file_stem(m.character);
  const std::vector<mm::Event> events = mm::read_events(a.events);

  // Faces: --rig FILE for everyone, --rig NAME=FILE for one character; the default face otherwise.
  const mo::CrowdFaces crowd_faces(maps, a.rigs);
  const std::vector<mo::CrowdRig>& rigs = crowd_faces.rigs();

  mo::CrowdTimings timings;
  const mo::Crowd crowd = mo::animate_crowd(maps, events, graph, rigs, co, &timings);
  const mo::CrowdRenderer renderer(crowd, rigs, a.render);

  // Everything but the video is computed before anything is written; the video is written first
  // (atomically, by VideoWriter), so a failing run leaves no output file.
  std::vector<std::pair<std::string, std::string>> files;
  const std::string dir = a.out + "/";
  files.emplace_back(dir + "actions.ndjson", mm::actions_to_ndjson(crowd.simulation.actions));
  files.emplace_back(dir + "actions.csv", mm::actions_to_csv(crowd.simulation.actions));
  for (std::size_t c = 0; c < maps.size(); ++c) {
    const auto& ch = crowd.characters[c];
    const std::string stem = dir + ch.name;
    files.emplace_back(stem + "_muscles.csv", emoface::muscles::format_parameter_frames_csv(ch.tracks));
    add_weight_files(files, stem, ch.tracks, a.weights);
    files.emplace_back(stem + "_mood.csv", mm::mood_timeline_csv(crowd.simulation, crowd.maps[c], c));
    files.emplace_back(stem + "_segments.csv", mo::segments_csv(ch.motion));
    if (!a.no_charts) {
      const mm::Raster chart = mm::mood_chart(crowd.simulation, crowd.maps[c], c, a.chart);
      mg::Image img(chart.width, chart.height);
      img.rgb = chart.rgb;
      files.emplace_back(stem + "_mood.png", mg::encode_png(img));
    }
  }
  files.emplace_back(dir + "key_moments.csv", mo::key_moments_csv(crowd));
  t0 = Clock::now();
  std::clock_t c0 = std::clock();
  const fm::Image sheet = renderer.key_moment_sheet();
  std::size_t rendered = 0;
  for (const auto& km : crowd.key_moments) rendered += km.frames.size();
  files.emplace_back(dir + "key_moments.png", png(sheet));
  double render_seconds = since(t0), render_cpu = cpu_since(c0);

  std::filesystem::create_directories(a.out);
  if (a.video) {
    emoface::core::VideoOptions vo;
    vo.width = renderer.width();
    vo.height = renderer.height();
    vo.fps = crowd.fps;
    t0 = Clock::now();
    c0 = std::clock();
    emoface::core::VideoWriter writer(dir + "crowd.mp4", vo);
    for (std::size_t k = 0; k < crowd.frame_count(); ++k) {
      writer.add_frame(renderer.frame(k).rgb);
      if (k % 30 == 0 || k + 1 == crowd.frame_count()) {
        std::fprintf(stderr, "\rrendering %zu/%zu frames", k + 1, crowd.frame_count());
        std::fflush(stderr);
      }
    }
    writer.finish();
    std::fprintf(stderr, "\n");
    render_seconds += since(t0);
    render_cpu += cpu_since(c0);  // this process only (ffmpeg's encoding is not counted)
    rendered += crowd.frame_count() * maps.size();
  }
  for (const auto& [path, content] : files) emoface::core::write_file_atomic(path, content);

  for (const auto& ch : crowd.characters) {
    std::size_t actions = 0;
    for (const auto& x : crowd.simulation.actions) actions += x.character == ch.name ? 1 : 0;
    std::cout << ch.name << ": " << actions << " action(s), " << ch.motion.segments.size() << " segments, fit RMS mean "
              << ch.fit.mean_rms * 1e3 << " mm (max " << ch.fit.max_rms * 1e3 << " mm)\n";
  }
  for (const auto& s : crowd.simulation.copied)
    std::cout << s.character << " learnt \"" << s.stimulus << "\" from " << s.from << " at " << s.time << " s\n";
  const auto distance = mo::face_distances(crowd);  // issue 19: how different the faces are
  std::cout << "face distance (mean per-frame parameter distance):";
  for (std::size_t i = 0; i < distance.size(); ++i)
    for (std::size_t j = i + 1; j < distance.size(); ++j)
      std::printf(" %s-%s %.3f", crowd.characters[i].name.c_str(), crowd.characters[j].name.c_str(), distance[i][j]);
  std::cout << "\n";
  const double frames = static_cast<double>(crowd.frame_count());
  std::printf("%zu characters, %zu frames at %g fps (%g s), %zu key moments, frame %dx%d\n", maps.size(),
              crowd.frame_count(), crowd.fps, crowd.simulation.duration, crowd.key_moments.size(), renderer.width(),
              renderer.height());
  const double faces = frames * static_cast<double>(maps.size());
  std::printf("time (wall / CPU): simulation %.3f / %.3f s; synthesis %.3f / %.3f s (%.3f ms CPU per frame and "
              "character); fitting %.3f / %.3f s (%.3f ms CPU per frame and character); deformation+render %.3f / "
              "%.3f s for %zu faces (%.2f ms CPU per face)\n",
              timings.simulation.wall, timings.simulation.cpu, timings.synthesis.wall, timings.synthesis.cpu,
              1e3 * timings.synthesis.cpu / faces, timings.fitting.wall, timings.fitting.cpu,
              1e3 * timings.fitting.cpu / faces, render_seconds, render_cpu, rendered,
              rendered ? 1e3 * render_cpu / static_cast<double>(rendered) : 0.0);
  std::cout << "wrote " << files.size() + (a.video ? 1 : 0) << " file(s) to " << a.out << "\n";
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
  write_dot(mm::mind_map_dot(shown, o), a.out);
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
    if (!a.graph.empty()) labels = emoface::mindmotion::graph_labels(mg::read_graph(a.graph));
    const auto maps = mm::read_mind_map_dir(a.maps, labels);
    for (const auto& m : maps)
      std::cout << m.character << ": " << m.emotion_count() << " emotion nodes, " << m.actions.size()
                << " actions, " << m.stimulus_edges.size() + m.response_edges.size() + m.chain_edges.size()
                << " edges\n";
    return cli::kExitOk;
  });
}
