// The subcommands and options of mindmap (the command line only; main.cpp runs them).
#include "args.hpp"

namespace emoface::mindmap_cli {

namespace {

// §5.1 variation is on by default (issue 19); --no-vary switches it off.
void add_motion_options(CLI::App* cmd, Args& a) {
  cmd->add_flag("--no-vary", a.no_vary,
                "no motion variation (paper §5.1): the same label gives the same motion");
  cmd->add_option("--replace", a.motion.synthesis.replace_probability,
                  "variation: probability of replacing a path node by a neighbour")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--return-after", a.motion.return_after,
                  "seconds after an animation before the face returns to neutral (0 = never)")
      ->check(CLI::Range(0.0, 1e5))
      ->capture_default_str();
}

}  // namespace

Commands add_commands(CLI::App& app, Args& a) {
  auto* sim = app.add_subcommand("simulate", "run stimuli through the characters' mind maps");
  sim->add_option("--maps", a.maps, "directory of mind maps (*.json, one character each)")
      ->required();
  sim->add_option("--events", a.events, "stimuli (NDJSON, see docs/mindmap.md)")->required();
  sim->add_option("--out", a.out, "output directory")->required();
  sim->add_option("--graph", a.graph,
                  "motion graph (mgraph build): also synthesize landmark motion");
  sim->add_flag("--muscles", a.muscles,
                "also fit muscle tracks (faceanim CSV) to the motion (needs --graph)");
  sim->add_option("--weights", a.weights,
                  "arkit,facs,livelink: with --muscles, also write <name>_arkit.csv, _facs.csv, "
                  "_livelink.csv")
      ->delimiter(',')
      ->check(CLI::IsMember({"arkit", "facs", "livelink"}));
  sim->add_option("--rig", a.rig, "rig for --muscles (default: the built-in default face)");
  sim->add_option("--seed", a.sim.seed, "random seed (near-tie choices, motion variation)")
      ->capture_default_str();
  sim->add_option("--mood-form", a.mood_form, "sum|printed reading of eq. 4")
      ->capture_default_str();
  sim->add_option("--frame-rate", a.sim.frame_rate, "mood samples per second")
      ->capture_default_str();
  sim->add_option("--duration", a.sim.duration, "seconds (0 = until the last decay ends)")
      ->capture_default_str();
  sim->add_option("--tie-tolerance", a.sim.tie_tolerance, "near-equal edge tolerance")
      ->capture_default_str();
  sim->add_option("--chain-delay", a.sim.chain_delay, "seconds between chained actions")
      ->capture_default_str();
  sim->add_option("--decay-interval", a.sim.decay_interval, "seconds between decay hints")
      ->capture_default_str();
  sim->add_option("--propagate", a.sim.propagation_depth,
                  "hops a performed stimulus travels to the others (0 = off)")
      ->capture_default_str();
  sim->add_flag("--to-addressee", a.sim.propagate_to_addressee,
                "with --propagate: an action aimed at a character reaches only that character");
  sim->add_option("--hint-fraction", a.motion.hint_path_fraction, "path fraction of decay hints")
      ->capture_default_str();
  add_motion_options(sim, a);
  sim->add_option("--chart-width", a.chart.width, "chart pixels")->capture_default_str();
  sim->add_option("--chart-height", a.chart.height, "chart pixels")->capture_default_str();
  sim->add_flag("--no-charts", a.no_charts, "do not write PNG mood charts");
  auto* cr = app.add_subcommand(
      "crowd", "animate several characters reacting to the same stimuli, side by side");
  cr->add_option("--maps", a.maps, "directory of mind maps (*.json, 2 to 16 characters)")
      ->required();
  cr->add_option("--events", a.events, "shared stimuli (NDJSON, see docs/mindmap.md)")->required();
  cr->add_option("--out", a.out, "output directory")->required();
  cr->add_option("--graph", a.graph,
                 "motion graph (mgraph build); default: mgraph generate + build defaults (~3 s)");
  cr->add_option(
      "--rig", a.rigs,
      "rig for everyone (FILE) or for one character (NAME=FILE); default: the built-in face");
  cr->add_option("--weights", a.weights,
                 "arkit,facs,livelink: also write <name>_arkit.csv, _facs.csv, _livelink.csv")
      ->delimiter(',')
      ->check(CLI::IsMember({"arkit", "facs", "livelink"}));
  cr->add_option("--seed", a.sim.seed, "random seed (near-tie choices, motion variation)")
      ->capture_default_str();
  cr->add_option("--fps", a.fps,
                 "frames per second of tracks, mood rows and video (0 = the graph's)")
      ->capture_default_str();
  cr->add_option("--width", a.render.face_width, "pixels per face (height = 7/6 of it)")
      ->capture_default_str();
  cr->add_option("--strip-height", a.render.strip_height,
                 "pixels of the mood strip under each face")
      ->capture_default_str();
  cr->add_option("--columns", a.render.columns, "grid columns (0 = one row up to 4 characters)")
      ->capture_default_str();
  cr->add_option("--view", a.view, "front|threequarter")
      ->check(CLI::IsMember({"front", "threequarter"}))
      ->capture_default_str();
  cr->add_flag("--video", a.video, "also write crowd.mp4 (needs the ffmpeg binary)");
  cr->add_option("--mood-form", a.mood_form, "sum|printed reading of eq. 4")->capture_default_str();
  cr->add_option("--duration", a.sim.duration, "seconds (0 = until the last decay ends)")
      ->capture_default_str();
  cr->add_option("--propagate", a.sim.propagation_depth,
                 "hops a performed stimulus travels to the others (0 = off)")
      ->capture_default_str();
  cr->add_flag("--no-charts", a.no_charts, "do not write PNG mood charts");
  add_motion_options(cr, a);
  auto* dt =
      app.add_subcommand("dot", "draw a mind map (Graphviz DOT; .svg/.png/.pdf rendered by dot)");
  dt->add_option("--maps", a.maps, "directory of mind maps")->required();
  dt->add_option("--character", a.character, "whose mind map")->required();
  dt->add_option("--events", a.events, "stimuli to run first (NDJSON), for the mood at --time");
  dt->add_option("--time", a.time,
                 "seconds: show the mood at this time (starting mood without --events)");
  dt->add_option("--seed", a.sim.seed, "random seed of the simulation")->capture_default_str();
  dt->add_option("--out", a.out, "output: .dot (text), .svg, .png or .pdf (needs Graphviz)")
      ->required();
  auto* check =
      app.add_subcommand("check", "validate mind maps (and their labels against a graph)");
  check->add_option("--maps", a.maps, "directory of mind maps")->required();
  check->add_option("--graph", a.graph, "motion graph whose labels the actions must use");
  return {sim, cr, dt, check};
}

}  // namespace emoface::mindmap_cli
