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

  auto add_source = [&](CLI::App* c) {
    c->add_option("--db", a.db, "landmark database (.json or .csv)");
    c->add_option("--ckplus", a.ckplus, "CK+ root directory (Landmarks/, Emotion/)");
    c->add_option("--layout", a.layout, "landmark layout JSON (default: built-in iBUG-68 layout)");
    c->add_flag("--no-align", a.no_align, "skip Procrustes alignment");
    c->add_flag("--no-clean", a.no_clean, "skip sigmoid cleaning");
    c->add_flag("--no-reverse", a.no_reverse, "do not append reversed copies");
    c->add_option("--lambda", a.lambda, "velocity influence of eq. (1)")->capture_default_str();
    c->add_option("--seed", a.seed, "random seed")->capture_default_str();
    c->add_option("--on-error", a.on_error, "stop|skip sequences with bad data (skip: reported on stderr)")
        ->capture_default_str();
  };
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
  add_source(build);
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

  auto* eval = app.add_subcommand("eval", "paper §7 table: compression vs. length and pose error");
  add_source(eval);
  eval->add_option("--compression", a.compressions, "target compression ratios")->delimiter(',')
      ->capture_default_str();
  eval->add_option("--thresholds", a.thresholds, "explicit thresholds instead")->delimiter(',');
  eval->add_option("--curve", a.curve, "also sweep this many thresholds (whole curve)")->capture_default_str();
  eval->add_option("--csv", a.out, "also write the rows as CSV (with the sums that merge shards)");
  eval->add_option("--shard", a.shard,
                   "i/N: evaluate the i-th of N contiguous blocks of samples, or auto")
      ->capture_default_str();
  eval->add_flag("--raw", a.raw, "also compare with the raw (uncleaned) samples");

  auto* cap = app.add_subcommand("capture",
                                 "tracker output (OpenFace CSV, MediaPipe NDJSON, Live Link Face CSV) -> labelled database");
  cap->add_option("--openface", a.openface, "OpenFace 2.0 FeatureExtraction CSV files (one take each)");
  cap->add_option("--mediapipe", a.mediapipe, "MediaPipe face-landmarker NDJSON files (one take each)");
  cap->add_option("--livelink", a.livelink, "Live Link Face CSV files (ARKit weights; one take each)");
  cap->add_option("--timecode-fps", a.timecode_fps, "Live Link: frame rate of the Timecode column")
      ->capture_default_str();
  cap->add_option("--labels", a.labels_file, "side file: CSV take,segment,label (segment index or *)");
  cap->add_option("--label-column", a.label_column, "OpenFace: a column with a label per frame");
  cap->add_flag("--3d", a.use_3d, "3D landmarks (OpenFace X_/Y_/Z_, MediaPipe z)");
  cap->add_option("--image-width", a.image_width, "MediaPipe: image width (px)")->capture_default_str();
  cap->add_option("--image-height", a.image_height, "MediaPipe: image height (px)")->capture_default_str();
  cap->add_option("--min-confidence", a.min_confidence, "drop frames below this confidence")->capture_default_str();
  cap->add_option("--max-gap", a.max_gap, "interpolate gaps up to this many frames; longer ones split takes")
      ->capture_default_str();
  cap->add_flag("--no-stabilise", a.no_stabilise, "keep the head motion");
  cap->add_flag("--no-trim", a.no_trim, "each take is one neutral-to-peak sequence (no onset detection)");
  cap->add_option("--on-error", a.on_error, "stop|skip segments without a label")->capture_default_str();
  cap->add_option("--out", a.out, "output database (.json or .csv; - = JSON on stdout)")->required();

  auto* ex = app.add_subcommand("capture-example", "example tracker files from emoface's own face");
  ex->add_option("--format", a.format, "openface|mediapipe|livelink")->capture_default_str();
  ex->add_option("--out", a.out, "output directory (one file per take, labels.csv)")->required();
  ex->add_option("--model", a.model, "face|parametric")->capture_default_str();
  ex->add_option("--seed", a.seed, "random seed")->capture_default_str();
  ex->add_option("--per-label", a.per_label, "sequences per label (7 labels)")->capture_default_str();
  ex->add_option("--subjects", a.subjects, "distinct identities (one take each)")->capture_default_str();
  ex->add_option("--noise", a.noise, "landmark noise std (pixels)")->capture_default_str();
  ex->add_option("--weight-noise", a.weight_noise, "livelink: weight noise std")->capture_default_str();
  ex->add_option("--min-frames", a.min_frames, "shortest onset (frames)")->capture_default_str();
  ex->add_option("--max-frames", a.max_frames, "longest onset (frames)")->capture_default_str();
  ex->add_option("--rest", a.rest_frames, "frames at rest around expressions")->capture_default_str();
  ex->add_option("--hold", a.hold_frames, "frames holding the peak")->capture_default_str();
  ex->add_option("--max-takes", a.max_takes, "write only the first N takes (0 = all)")->capture_default_str();

  auto* dt = app.add_subcommand("dot", "draw a region graph (Graphviz DOT; .svg/.png/.pdf rendered by dot)");
  dt->add_option("--graph", a.graph, "motion graph JSON")->required();
  dt->add_option("--region", a.region, "region name (eyes, eyebrows, nose, mouth, cheeks_jaw)")->required();
  dt->add_option("--depth", a.depth, "only nodes within this many edges of the source (0 = all)")
      ->capture_default_str();
  dt->add_flag("--weights", a.edge_weights, "label edges with their eq. (1) weights");
  dt->add_option("--out", a.out, "output: .dot or - (text), .svg, .png or .pdf (needs Graphviz)")->required();

  if (auto code = cli::parse(app, argc, argv)) return *code;
  return cli::run("mgraph", [&] {
    if (*gen) return mgraph::generate(a);
    if (*build) return mgraph::build(a);
    if (*synth) return mgraph::synth(a);
    if (*idle) return mgraph::idle(a);
    if (*cap) return mgraph::capture(a);
    if (*ex) return mgraph::capture_example(a);
    if (*dt) return mgraph::dot(a);
    return mgraph::eval(a);
  });
}
