// mgraph: facial motion graphs (paper §4–5, §7) — generate a synthetic database, build region
// graphs, synthesize labelled animations and idle motion, evaluate compression against error.
#include <cstdio>
#include <iostream>

#include "commands.hpp"
#include "emoface/cli/cli.hpp"

using namespace emoface;

int main(int argc, char** argv) {
  CLI::App app{"Facial motion graphs: labelled landmark sequences -> region graphs -> new motion.\n"
               "Example:\n"
               "  mgraph generate --out db.json            (face-driven: default face + fuzzyexpr + muscles)\n"
               "  mgraph build --db db.json --out graph.json\n"
               "  mgraph synth --graph graph.json --labels fear,surprise --out anim.json --sheet anim.png --video anim.gif\n"
               "  mgraph idle --graph graph.json --label happiness --duration 4 --out idle.csv\n"
               "  mgraph eval --db db.json --compression 0.5753,0.78,0.90\n"
               "  mgraph capture --openface take1.csv take2.csv --label-column label --out db.json"};
  app.require_subcommand(1);
  mgraph::Args a;

  auto add_output = [&](CLI::App* c) {
    c->add_option("--out", a.out, "output landmark sequences (.json or .csv; - = JSON on stdout)")
        ->capture_default_str();
    c->add_option("--sheet", a.sheet, "contact sheet PNG of the frames");
    c->add_option("--plot", a.plot, "trajectory plot PNG (y of the most moving landmark per region)");
    c->add_option("--frames-dir", a.frames_dir, "write one PNG per frame into this directory");
    c->add_option("--columns", a.columns, "contact sheet columns")->capture_default_str();
    c->add_option("--every", a.every, "contact sheet: every n-th frame")->capture_default_str()->check(CLI::PositiveNumber);
    c->add_option("--cell-width", a.cell_width, "contact sheet cell width (px)")->capture_default_str();
    c->add_option("--video", a.video, "animation of the landmarks: .gif, .mp4, .mov or .mkv (needs ffmpeg)");
    c->add_option("--video-width", a.video_width, "video frame width (px)")->capture_default_str();
    c->add_option("--video-height", a.video_height, "video frame height (px)")->capture_default_str();
    c->add_option("--fps", a.fps, "video frame rate (default: the graph's)");
  };

  auto* gen = app.add_subcommand("generate", "synthetic CK+-like database (68 landmarks, 640x490 px)");
  gen->add_option("--out", a.out, "output database (.json or .csv; - = JSON on stdout)")->required();
  gen->add_option("--model", a.model, "face (default face + fuzzyexpr + muscles, projected) | parametric")
      ->capture_default_str();
  gen->add_option("--projection", a.projection, "face model: perspective|orthographic")->capture_default_str();
  gen->add_option("--camera-distance", a.camera_distance, "face model: camera distance (m)")->capture_default_str();
  gen->add_option("--shard", a.shard,
                  "i/N: the i-th of N contiguous blocks of sequences, or auto (Slurm)")
      ->capture_default_str();
  gen->add_option("--sheet", a.sheet, "contact sheet PNG: a neutral frame, then one peak per label");
  gen->add_option("--columns", a.columns, "contact sheet columns")->capture_default_str();
  gen->add_option("--cell-width", a.cell_width, "contact sheet cell width (px)")->capture_default_str();
  gen->add_option("--seed", a.seed, "random seed")->capture_default_str();
  gen->add_option("--per-label", a.per_label, "sequences per label (7 labels)")->capture_default_str();
  gen->add_option("--subjects", a.subjects, "distinct identities")->capture_default_str();
  gen->add_option("--noise", a.noise, "landmark noise std (pixels)")->capture_default_str();
  gen->add_option("--space", a.space,
                  "landmarks | arkit (ARKit-52 weights of the face model: faceweights mapping)")
      ->capture_default_str();
  gen->add_option("--weight-noise", a.weight_noise, "arkit: weight noise std")->capture_default_str();

  auto* build = app.add_subcommand("build", "build the region motion graphs");
  mgraph::add_source_options(build, a);
  build->add_option("--sample-threshold", a.sample_threshold,
                    "sample-graph threshold (default 0.4 px per landmark; 0.012 per weight channel)");
  build->add_option("--merge-threshold", a.merge_threshold,
                    "final-graph threshold (default 0.4 px per landmark; 0.012 per weight channel)");
  build->add_option("--compression", a.target_compression, "pick both thresholds for this ratio (0..1)");
  build->add_option("--out", a.out, "output graph JSON")->required();

  auto* synth = app.add_subcommand("synth", "synthesize transitions to peaks of the given labels");
  synth->add_option("--graph", a.graph, "motion graph JSON")->required();
  synth->add_option("--labels", a.labels, "comma-separated labels, chained")->delimiter(',');
  synth->add_option("--requests", a.requests, "batch: CSV \"id,labels\" (labels separated by ';'), one chain each");
  synth
      ->add_option("--shard", a.shard,
                   "i/N: the i-th of N contiguous blocks of requests, or auto (Slurm)")
      ->capture_default_str();
  synth->add_option("--on-error", a.on_error, "stop|skip bad requests (skip: reported on stderr)")->capture_default_str();
  synth->add_option("--seed", a.seed, "random seed")->capture_default_str();
  synth->add_flag("--vary", a.vary, "sample durations from the peak nodes' distributions (§5.1)");
  synth->add_option("--replace", a.replace, "probability of replacing a path node by a neighbour")
      ->capture_default_str();
  synth->add_option("--hint", a.hint, "mood-decay hint: use only this leading path fraction (0,1]")
      ->capture_default_str();
  synth->add_option("--idle", a.idle_after, "seconds of idle motion after each transition")
      ->capture_default_str();
  synth->add_flag("--no-sigmoid", a.no_sigmoid, "Savitzky-Golay smoothing only");
  synth->add_option("--livelink", a.livelink_out, "weight graph: also write the weights as Live Link Face CSV");
  synth->add_option("--params", a.params_out,
                    "weight graph: also write face parameters (muscles CSV) through the ARKit mapping");
  add_output(synth);

  auto* idle = app.add_subcommand("idle", "idle movements around a label's peak (§5)");
  idle->add_option("--graph", a.graph, "motion graph JSON")->required();
  idle->add_option("--label", a.idle_label, "label (the animation first reaches its peak)")->required();
  idle->add_option("--duration", a.duration, "seconds")->capture_default_str();
  idle->add_option("--hop-interval", a.hop_interval, "seconds between hops")->capture_default_str();
  idle->add_option("--dwell", a.dwell, "seconds at each hop target")->capture_default_str();
  idle->add_option("--seed", a.seed, "random seed")->capture_default_str();
  add_output(idle);

  const mgraph::AnalysisCommands more = mgraph::add_analysis_commands(app, a);

  if (auto code = cli::parse(app, argc, argv)) return *code;
  return cli::run("mgraph", [&] {
    if (*gen) return mgraph::generate(a);
    if (*build) return mgraph::build(a);
    if (*synth) return mgraph::synth(a);
    if (*idle) return mgraph::idle(a);
    if (*more.capture) return mgraph::capture(a);
    if (*more.example) return mgraph::capture_example(a);
    if (*more.dot) return mgraph::dot(a);
    return mgraph::eval(a);
  });
}
