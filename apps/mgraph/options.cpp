// The options of mgraph build/eval sources and of eval, capture, capture-example and dot.
#include "commands.hpp"

namespace emoface::mgraph {

void add_source_options(CLI::App* c, Args& a) {
  c->add_option("--db", a.db, "landmark database (.json or .csv)");
  c->add_option("--ckplus", a.ckplus, "CK+ root directory (Landmarks/, Emotion/)");
  c->add_option("--layout", a.layout, "landmark layout JSON (default: built-in iBUG-68 layout)");
  c->add_flag("--no-align", a.no_align, "skip Procrustes alignment");
  c->add_flag("--no-clean", a.no_clean, "skip sigmoid cleaning");
  c->add_flag("--no-reverse", a.no_reverse, "do not append reversed copies");
  c->add_option("--lambda", a.lambda, "velocity influence of eq. (1)")->capture_default_str();
  c->add_option("--seed", a.seed, "random seed")->capture_default_str();
  c->add_option("--on-error", a.on_error,
                "stop|skip sequences with bad data (skip: reported on stderr)")
      ->capture_default_str();
}

AnalysisCommands add_analysis_commands(CLI::App& app, Args& a) {
  auto* eval = app.add_subcommand("eval", "paper §7 table: compression vs. length and pose error");
  add_source_options(eval, a);
  eval->add_option("--compression", a.compressions, "target compression ratios")
      ->delimiter(',')
      ->capture_default_str();
  eval->add_option("--thresholds", a.thresholds, "explicit thresholds instead")->delimiter(',');
  eval->add_option("--curve", a.curve, "also sweep this many thresholds (whole curve)")
      ->capture_default_str();
  eval->add_option("--csv", a.out, "also write the rows as CSV (with the sums that merge shards)");
  eval->add_option("--shard", a.shard,
                   "i/N: evaluate the i-th of N contiguous blocks of samples, or auto")
      ->capture_default_str();
  eval->add_flag("--raw", a.raw, "also compare with the raw (uncleaned) samples");

  auto* cap = app.add_subcommand(
      "capture",
      "tracker output (OpenFace CSV, MediaPipe NDJSON, Live Link Face CSV) -> labelled database");
  cap->add_option("--openface", a.openface,
                  "OpenFace 2.0 FeatureExtraction CSV files (one take each)");
  cap->add_option("--mediapipe", a.mediapipe,
                  "MediaPipe face-landmarker NDJSON files (one take each)");
  cap->add_option("--livelink", a.livelink,
                  "Live Link Face CSV files (ARKit weights; one take each)");
  cap->add_option("--timecode-fps", a.timecode_fps, "Live Link: frame rate of the Timecode column")
      ->capture_default_str();
  cap->add_option("--labels", a.labels_file,
                  "side file: CSV take,segment,label (segment index or *)");
  cap->add_option("--label-column", a.label_column, "OpenFace: a column with a label per frame");
  cap->add_flag("--3d", a.use_3d, "3D landmarks (OpenFace X_/Y_/Z_, MediaPipe z)");
  cap->add_option("--image-width", a.image_width, "MediaPipe: image width (px)")
      ->capture_default_str();
  cap->add_option("--image-height", a.image_height, "MediaPipe: image height (px)")
      ->capture_default_str();
  cap->add_option("--min-confidence", a.min_confidence, "drop frames below this confidence")
      ->capture_default_str();
  cap->add_option("--max-gap", a.max_gap,
                  "interpolate gaps up to this many frames; longer ones split takes")
      ->capture_default_str();
  cap->add_flag("--no-stabilise", a.no_stabilise, "keep the head motion");
  cap->add_flag("--no-trim", a.no_trim,
                "each take is one neutral-to-peak sequence (no onset detection)");
  cap->add_option("--on-error", a.on_error, "stop|skip segments without a label")
      ->capture_default_str();
  cap->add_option("--out", a.out, "output database (.json or .csv; - = JSON on stdout)")
      ->required();

  auto* ex = app.add_subcommand("capture-example", "example tracker files from emoface's own face");
  ex->add_option("--format", a.format, "openface|mediapipe|livelink")->capture_default_str();
  ex->add_option("--out", a.out, "output directory (one file per take, labels.csv)")->required();
  ex->add_option("--model", a.model, "face|parametric")->capture_default_str();
  ex->add_option("--seed", a.seed, "random seed")->capture_default_str();
  ex->add_option("--per-label", a.per_label, "sequences per label (7 labels)")
      ->capture_default_str();
  ex->add_option("--subjects", a.subjects, "distinct identities (one take each)")
      ->capture_default_str();
  ex->add_option("--noise", a.noise, "landmark noise std (pixels)")->capture_default_str();
  ex->add_option("--weight-noise", a.weight_noise, "livelink: weight noise std")
      ->capture_default_str();
  ex->add_option("--min-frames", a.min_frames, "shortest onset (frames)")->capture_default_str();
  ex->add_option("--max-frames", a.max_frames, "longest onset (frames)")->capture_default_str();
  ex->add_option("--rest", a.rest_frames, "frames at rest around expressions")
      ->capture_default_str();
  ex->add_option("--hold", a.hold_frames, "frames holding the peak")->capture_default_str();
  ex->add_option("--max-takes", a.max_takes, "write only the first N takes (0 = all)")
      ->capture_default_str();

  auto* dt = app.add_subcommand(
      "dot", "draw a region graph (Graphviz DOT; .svg/.png/.pdf rendered by dot)");
  dt->add_option("--graph", a.graph, "motion graph JSON")->required();
  dt->add_option("--region", a.region, "region name (eyes, eyebrows, nose, mouth, cheeks_jaw)")
      ->required();
  dt->add_option("--depth", a.depth, "only nodes within this many edges of the source (0 = all)")
      ->capture_default_str();
  dt->add_flag("--weights", a.edge_weights, "label edges with their eq. (1) weights");
  dt->add_option("--out", a.out, "output: .dot or - (text), .svg, .png or .pdf (needs Graphviz)")
      ->required();

  return {eval, cap, ex, dt};
}

}  // namespace emoface::mgraph
