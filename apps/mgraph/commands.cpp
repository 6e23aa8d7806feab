#include "commands.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "emoface/bridge/face_landmark_model.hpp"
#include "emoface/bridge/weight_space.hpp"
#include "emoface/cli/cli.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/graphviz.hpp"
#include "emoface/core/io.hpp"
#include "emoface/motiongraph/batch.hpp"
#include "emoface/motiongraph/capture.hpp"
#include "emoface/motiongraph/dot.hpp"
#include "emoface/motiongraph/evaluate.hpp"
#include "emoface/motiongraph/io.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "emoface/motiongraph/render.hpp"
#include "emoface/motiongraph/synthesis.hpp"
#include "emoface/motiongraph/synthetic.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "emoface/muscles/io.hpp"

namespace emoface::mgraph {

using namespace motiongraph;

namespace {

OnError on_error(const Args& a) {
  return cli::parse_enum<OnError>(a.on_error, core::on_error_from_string, "--on-error",
                                  "stop|skip");
}

// A database to --out: CSV for a .csv name, else JSON ("-": JSON on stdout).
void stage_database(core::OutputBundle& bundle, const std::string& out, const Database& db) {
  const bool csv = out.size() > 4 && out.substr(out.size() - 4) == ".csv";
  bundle.add(out, csv ? database_to_csv(db) : database_to_json(db));
}

void print_skipped(const ReadReport& report) {
  for (const std::string& m : report.skipped) std::cerr << "mgraph: skipped: " << m << "\n";
  if (!report.skipped.empty()) std::cerr << "mgraph: " << report.skipped.size() << " record(s) skipped\n";
}

Database load_database(const Args& a) {
  if (a.db.empty() == a.ckplus.empty()) throw InvalidInput("give exactly one of --db and --ckplus");
  ReadReport report;
  CkPlusOptions ck;
  ck.on_error = on_error(a);
  Database db = a.db.empty() ? read_ck_plus(a.ckplus, ck, &report) : read_database(a.db, 30.0, ck.on_error, &report);
  print_skipped(report);
  return db;
}

// `clean` = false gives the raw samples (eval --raw).
PreparedDatabase prepare(const Args& a, const Database& db, bool clean, bool quiet = false) {
  const bool weights = is_weight_space(db.dimensions);
  // Weight databases: the ARKit regions for 52 channels (bridge::arkit_layout), else one region.
  LandmarkLayout layout = !a.layout.empty()           ? read_layout(a.layout)
                          : db.landmark_count == 68 && !weights ? default_layout()
                          : db.landmark_count == 52 && weights  ? bridge::arkit_layout()
                                                                : single_region_layout(db.landmark_count);
  PreprocessOptions o = weights ? weight_preprocess_options() : PreprocessOptions{};
  o.align = !a.no_align;
  o.clean = clean && !a.no_clean;
  o.append_reversed = !a.no_reverse;
  o.skip_bad_samples = on_error(a) == OnError::Skip;  // a sample that does not start neutral
  PreprocessReport pr;
  PreparedDatabase data = preprocess(db, layout, o, &pr);
  if (!quiet)
    for (const auto& s : pr.skipped) std::cerr << "mgraph: skipped: " << s << "\n";
  return data;
}

PreparedDatabase load_prepared(const Args& a) { return prepare(a, load_database(a), true); }

GraphOptions graph_options(const Args& a, int dimensions) {
  GraphOptions g = is_weight_space(dimensions) ? weight_graph_options() : GraphOptions{};
  g.similarity.lambda = a.lambda;
  g.seed = a.seed;
  if (a.sample_threshold >= 0.0) g.sample_threshold = a.sample_threshold;
  if (a.merge_threshold >= 0.0) g.merge_threshold = a.merge_threshold;
  return g;
}

// Sequences (one per animation) as a database of the graph's reduced landmarks, plus pictures and
// the weight outputs: every output computed and staged, then all committed (core::OutputBundle).
int write_animation(const Args& a, const MotionGraph& g, const std::vector<Sequence>& seqs) {
  const bool weights = is_weight_space(g.dimensions);
  AnimationPictures pics{a.sheet, a.plot,       a.frames_dir,  a.video,        a.columns,
                         a.every, a.cell_width, a.video_width, a.video_height, a.fps};
  if (weights && pics.any())
    throw cli::UsageError("--video, --sheet, --plot and --frames-dir draw landmarks: not for a weight graph "
                          "(use --params and faceanim)");
  if (!weights && !(a.livelink_out.empty() && a.params_out.empty()))
    throw cli::UsageError("--livelink and --params need a weight graph (mgraph generate --space arkit)");
  const Database db = animation_database(g, seqs);
  std::vector<Pose> all;
  for (const Sequence& s : seqs) all.insert(all.end(), s.frames.begin(), s.frames.end());
  core::OutputBundle bundle;
  // Weight graphs: the weights as Live Link Face CSV, the face parameters through the ARKit mapping
  // (exact, no landmark fit; bridge/weight_space.hpp).
  if (!a.livelink_out.empty())
    bundle.add(a.livelink_out,
               bridge::live_link_csv(bridge::weight_take(g, all, "synth"), g.frame_rate));
  if (!a.params_out.empty()) {
    bridge::WeightDriveReport rep;
    bundle.add(a.params_out,
               muscles::format_parameter_frames_csv(bridge::weight_parameters(g, all, &rep)));
    std::cerr << "mgraph: " << rep.frames << " frames of face parameters, largest weight error "
              << rep.max_weight_error << "\n";
  }
  stage_database(bundle, a.out, db);
  stage_animation_pictures(bundle, g, all, pics);
  bundle.commit();
  return cli::kExitOk;
}

std::unique_ptr<LandmarkModel> landmark_model(const Args& a) {
  std::unique_ptr<LandmarkModel> model;
  if (a.model == "parametric") {
    model = std::make_unique<ParametricLandmarkModel>();
  } else if (a.model == "face") {
    bridge::FaceLandmarkModelOptions fo;
    fo.projection = cli::parse_enum<bridge::Projection>(a.projection, bridge::projection_from_string,
                                                        "--projection", "perspective|orthographic");
    fo.camera_distance = a.camera_distance;
    model = std::make_unique<bridge::FaceLandmarkModel>(fo);
  } else {
    throw cli::UsageError("--model: unknown value \"" + a.model + "\" (expected face|parametric)");
  }
  return model;
}

}  // namespace

int generate(const Args& a) {
  SyntheticOptions o;
  o.seed = a.seed;
  o.sequences_per_label = a.per_label;
  o.subjects = a.subjects;
  o.noise_std = a.noise;
  const cli::Shard shard = cli::parse_shard(a.shard);
  if (a.space != "landmarks" && a.space != "arkit")
    throw cli::UsageError("--space: unknown value \"" + a.space + "\" (expected landmarks|arkit)");
  if (a.space == "arkit") {  // weight space (issue 19 item 2): ARKit-52 weights of the face model
    if (a.model != "face") throw cli::UsageError("--space arkit needs --model face");
    if (!a.sheet.empty()) throw cli::UsageError("--sheet draws landmarks: not with --space arkit");
    bridge::WeightDatabaseOptions wo;
    wo.database = o;
    wo.noise_std = a.weight_noise;
    try {
      wo.validate();
    } catch (const InvalidInput& e) {
      throw cli::UsageError(e.what());
    }
    Database db = bridge::generate_weight_database(bridge::FaceLandmarkModel(), wo);
    // Sequence i depends only on (seed, i); the shard keeps its contiguous block.
    const auto [first, last] = shard.block(db.sequences.size());
    if (first == last) throw InvalidInput("--shard " + a.shard + " owns none of the sequences");
    db.sequences = std::vector<Sequence>(db.sequences.begin() + static_cast<std::ptrdiff_t>(first),
                                         db.sequences.begin() + static_cast<std::ptrdiff_t>(last));
    core::OutputBundle bundle;
    stage_database(bundle, a.out, db);
    bundle.commit();
    return cli::kExitOk;
  }
  const std::unique_ptr<LandmarkModel> model = landmark_model(a);
  // Sequence i depends only on (seed, i): a shard computes its contiguous block of the database.
  Database db;
  db.dimensions = 2;
  db.landmark_count = 68;
  db.frame_rate = o.frame_rate;
  const std::size_t count = synthetic_sequence_count(o);
  const auto [first, last] = shard.block(count);
  for (std::size_t i = first; i < last; ++i)
    db.sequences.push_back(synthetic_sequence(*model, o, i));
  if (db.sequences.empty()) throw InvalidInput("--shard " + a.shard + " owns none of the " + std::to_string(count) + " sequences");
  core::OutputBundle bundle;
  if (!a.sheet.empty()) {
    // First frame of the first sequence, then the peak frame of the first sequence of each label;
    // colours = regions of the built-in layout (grey: landmarks outside the reduced set).
    std::vector<int> groups(68, 8);
    const LandmarkLayout layout = default_layout();
    for (std::size_t r = 0; r < layout.regions.size(); ++r)
      for (int i : layout.regions[r].landmarks) groups[static_cast<std::size_t>(i)] = static_cast<int>(r);
    std::vector<Pose> shown{db.sequences.front().frames.front()};
    std::vector<Label> seen;
    for (const Sequence& s : db.sequences)
      if (std::find(seen.begin(), seen.end(), s.label) == seen.end()) {
        seen.push_back(s.label);
        shown.push_back(s.frames.back());
      }
    std::vector<int> all_ids(68);
    for (int i = 0; i < 68; ++i) all_ids[static_cast<std::size_t>(i)] = i;
    bundle.add(a.sheet, encode_png(contact_sheet(shown, groups, a.columns, a.cell_width,
                                                 a.cell_width * 7 / 8, contours_for(all_ids))));
  }
  stage_database(bundle, a.out, db);
  bundle.commit();
  return cli::kExitOk;
}

int build(const Args& a) {
  const PreparedDatabase data = load_prepared(a);
  GraphOptions g = graph_options(a, data.dimensions);
  if (a.target_compression >= 0.0)
    g.sample_threshold = g.merge_threshold = threshold_for_compression(data, a.target_compression, g);
  const MotionGraph graph = build_graph(data, g);
  write_graph(a.out, graph);
  std::cerr << "mgraph: " << graph.regions.size() << " regions, " << graph.node_count() << " nodes from "
            << graph.source_frames << " frames per region, compression " << graph.compression_ratio() * 100
            << " %, threshold " << g.sample_threshold << "\n";
  return cli::kExitOk;
}

int synth(const Args& a) {
  const MotionGraph g = read_graph(a.graph);
  if (!a.requests.empty() && !a.labels.empty()) throw cli::UsageError("give --labels or --requests, not both");
  if (a.requests.empty() && a.labels.empty()) throw cli::UsageError("give --labels or --requests");
  ChainOptions o = chain_options_for(g);
  o.synthesis.vary_duration = a.vary;
  o.synthesis.replace_probability = a.replace;
  o.synthesis.path_fraction = a.hint;
  o.synthesis.smoothing.sigmoid = !a.no_sigmoid;
  o.idle_after = a.idle_after;
  if (a.requests.empty())
    return write_animation(a, g, synthesize_chain(g, a.labels, a.seed, "", o));
  // Batch (motiongraph/batch.hpp): request r uses the seed stream r, and a shard takes its
  // contiguous block of the requests (bad ones count), so shard outputs concatenate to one run.
  const cli::Shard shard = cli::parse_shard(a.shard);
  const std::vector<RequestRecord> records = read_requests_csv(a.requests);
  ReadReport report;
  const std::vector<Sequence> seqs =
      synthesize_requests(g, records, shard.block(records.size()), a.seed, o, on_error(a), &report);
  for (const std::string& m : report.skipped) std::cerr << "mgraph: skipped: " << m << "\n";
  if (!report.skipped.empty())
    std::cerr << "mgraph: " << report.skipped.size() << " request(s) skipped\n";
  if (seqs.empty()) throw InvalidInput("no request produced an animation (shard " + a.shard + ")");
  return write_animation(a, g, seqs);
}

int idle(const Args& a) {
  const MotionGraph g = read_graph(a.graph);
  const Label label = label_from_string(a.idle_label);
  SynthesisState state = initial_state(g);
  const bool weights = is_weight_space(g.dimensions);
  SynthesisOptions so = weights ? weight_synthesis_options() : SynthesisOptions{};
  so.seed = a.seed;
  std::vector<Sequence> seqs;
  if (label != Label::Neutral) seqs.push_back({"onset_" + a.idle_label, "", label, synthesize(g, state, label, so)});
  IdleOptions o = weights ? weight_idle_options() : IdleOptions{};
  o.duration = a.duration;
  o.hop_interval = a.hop_interval;
  o.dwell = a.dwell;
  o.seed = a.seed;
  seqs.push_back({"idle_" + a.idle_label, "", label, motiongraph::idle(g, state, label, o)});
  return write_animation(a, g, seqs);
}

int eval(const Args& a) {
  const Database db = load_database(a);
  const PreparedDatabase data = prepare(a, db, true);
  // --raw: the same samples without sigmoid cleaning (issue 19: compare with what the tracker gave).
  std::optional<PreparedDatabase> raw;
  if (a.raw) raw = prepare(a, db, false, true);
  const bool weights = is_weight_space(data.dimensions);
  const GraphOptions g = graph_options(a, data.dimensions);
  std::vector<double> thresholds = a.thresholds;
  if (thresholds.empty())
    for (double c : a.compressions) thresholds.push_back(threshold_for_compression(data, c, g));
  for (std::size_t i = 1; i <= a.curve; ++i) thresholds.push_back(0.25 * static_cast<double>(i));
  EvaluationOptions eo = weights ? weight_evaluation_options() : EvaluationOptions{};
  eo.graph = g;
  const cli::Shard shard = cli::parse_shard(a.shard);
  eo.shard_index = shard.index;
  eo.shard_count = shard.count;
  if (shard.count > 1) {
    const auto [first, last] = shard.block(data.samples.size());
    std::printf("shard %zu/%zu: samples [%zu, %zu) of %zu (graphs from the whole database)\n",
                shard.index, shard.count, first, last, data.samples.size());
  }
  const char* unit = weights ? "(weight)" : "(px)";
  std::printf("%10s %14s %7s %22s %22s%s\n", "threshold", "compression %", "nodes", "length diff (frames)",
              (std::string("pose diff ") + unit).c_str(),
              raw ? (std::string("   vs raw samples ") + unit).c_str() : "");
  std::vector<EvaluationRow> rows;
  for (double t : thresholds) {
    const EvaluationRow& r = rows.emplace_back(evaluate(data, t, eo, raw ? &*raw : nullptr));
    std::printf("%10.4f %14.2f %7zu %10.3f +- %-8.3f %10.4f +- %-8.4f", t, 100 * r.compression, r.nodes,
                r.length_mean, r.length_std, r.pose_mean, r.pose_std);
    if (raw) std::printf(" %10.4f +- %-8.4f", r.raw_pose_mean, r.raw_pose_std);
    std::printf("\n");
  }
  std::printf("paper (CK+, 70 sequences): 90%% -> 0.98 +- 1.84 frames, 2.86 +- 2.3 px; 78%% -> 0.071 +- 0.39, "
              "2.12 +- 1.81; 57.53%% -> 0 +- 0, 1.52 +- 1.51\n");
  // The sums let rows of shards be merged exactly (read_evaluation_csv + merge_rows).
  if (a.out != "-") core::write_file_atomic(a.out, evaluation_csv(rows));
  return cli::kExitOk;
}

// Capture files (issue 19): OpenFace CSV / MediaPipe NDJSON takes → cleaned, stabilised, trimmed,
// labelled landmark database.
int capture(const Args& a) {
  if ((a.openface.empty() ? 0 : 1) + (a.mediapipe.empty() ? 0 : 1) + (a.livelink.empty() ? 0 : 1) != 1)
    throw cli::UsageError("give --openface, --mediapipe or --livelink files (one kind)");
  if (!a.livelink.empty() && !a.label_column.empty())
    throw cli::UsageError("--label-column: Live Link Face files have no label column (use --labels)");
  CaptureOptions co;
  co.on_error = on_error(a);
  co.filter.min_confidence = a.min_confidence;
  co.filter.max_gap = a.max_gap;
  co.stabilise = !a.no_stabilise;
  co.trim = !a.no_trim;
  try {
    co.validate();
  } catch (const InvalidInput& e) {
    throw cli::UsageError(e.what());
  }
  std::vector<TrackedFrames> takes;
  OpenFaceReadOptions oo;
  oo.use_3d = a.use_3d;
  oo.label_column = a.label_column;
  MediaPipeReadOptions mo;
  mo.image_width = a.image_width;
  mo.image_height = a.image_height;
  mo.use_z = a.use_3d;
  for (const auto& f : a.openface) takes.push_back(read_openface_csv(f, oo));
  for (const auto& f : a.mediapipe) takes.push_back(read_mediapipe_ndjson(f, mo));
  if (!(a.timecode_fps > 0.0 && a.timecode_fps <= 1000.0))
    throw cli::UsageError("--timecode-fps must be in (0, 1000]");
  for (const auto& f : a.livelink) takes.push_back(bridge::read_live_link_take(f, a.timecode_fps));
  std::optional<LabelTable> labels;
  if (!a.labels_file.empty()) labels = read_label_table(a.labels_file);
  ReadReport report;
  const Database db = capture_database(takes, co, labels ? &*labels : nullptr, &report);
  print_skipped(report);
  core::OutputBundle bundle;
  stage_database(bundle, a.out, db);
  bundle.commit();
  std::size_t frames = 0;
  for (const auto& s : db.sequences) frames += s.frames.size();
  std::cerr << "mgraph: " << takes.size() << " take(s) → " << db.sequences.size() << " labelled neutral-to-peak "
            << "sequence(s), " << frames << " frames at " << db.frame_rate << " fps\n";
  return cli::kExitOk;
}

// Example capture files from emoface's own face: one file per take and the labels side file.
int capture_example(const Args& a) {
  if (a.format != "openface" && a.format != "mediapipe" && a.format != "livelink")
    throw cli::UsageError("--format: unknown value \"" + a.format + "\" (expected openface|mediapipe|livelink)");
  if (a.format == "livelink") {  // ARKit weights of the face model (issue 19 item 2)
    bridge::WeightTakeOptions wo;
    wo.database.database.seed = a.seed;
    wo.database.database.sequences_per_label = a.per_label;
    wo.database.database.subjects = a.subjects;
    wo.database.database.min_frames = a.min_frames;
    wo.database.database.max_frames = a.max_frames;
    wo.database.noise_std = a.weight_noise;
    wo.rest_frames = a.rest_frames;
    wo.hold_frames = a.hold_frames;
    try {
      wo.validate();
    } catch (const InvalidInput& e) {
      throw cli::UsageError(e.what());
    }
    std::vector<TrackedFrames> takes = bridge::generate_weight_takes(bridge::FaceLandmarkModel(), wo);
    if (a.max_takes > 0 && takes.size() > a.max_takes) takes.resize(a.max_takes);
    std::vector<std::pair<std::string, std::string>> files;
    for (const TrackedFrames& t : takes)
      files.emplace_back(a.out + "/" + t.id + ".csv", bridge::live_link_csv(t, wo.database.database.frame_rate));
    files.emplace_back(a.out + "/labels.csv", label_table_csv(bridge::weight_take_labels(takes)));
    core::OutputBundle bundle;  // all takes and labels.csv, or nothing
    for (const auto& [path, content] : files) bundle.add(path, content);
    bundle.commit();
    std::cerr << "mgraph: wrote " << takes.size() << " livelink take(s) and labels.csv to " << a.out << "\n";
    return cli::kExitOk;
  }
  CaptureExampleOptions o;
  o.database.seed = a.seed;
  o.database.sequences_per_label = a.per_label;
  o.database.subjects = a.subjects;
  o.database.noise_std = a.noise;
  o.database.min_frames = a.min_frames;
  o.database.max_frames = a.max_frames;
  o.rest_frames = a.rest_frames;
  o.hold_frames = a.hold_frames;
  try {
    o.validate();
  } catch (const InvalidInput& e) {
    throw cli::UsageError(e.what());
  }
  const std::unique_ptr<LandmarkModel> model = landmark_model(a);
  std::vector<TrackedFrames> takes = generate_capture_takes(*model, o);
  if (a.max_takes > 0 && takes.size() > a.max_takes) takes.resize(a.max_takes);
  // Everything is computed before anything is written.
  std::vector<std::pair<std::string, std::string>> files;
  LabelTable side;
  for (const TrackedFrames& t : takes) {
    // The side file labels every segment the default capture options find, from the take's column.
    std::size_t k = 0;
    for (const TrackedFrames& part : clean_frames(t)) {
      TrackedFrames p = part;
      stabilise_head(p);
      for (const TakeSegment& seg : find_segments(p)) {
        const Label l = label_from_string(p.labels[seg.peak]);
        if (l != Label::Neutral) side.entries[{t.id, std::to_string(k)}] = l;
        ++k;
      }
    }
    if (a.format == "openface") {
      files.emplace_back(a.out + "/" + t.id + ".csv", openface_csv(t));
    } else {
      std::vector<Eigen::MatrixXd> points;
      for (std::size_t i = 0; i < t.size(); ++i)
        points.push_back(t.success[i] ? mediapipe_points_from_ibug68(t.frames[i]) : Eigen::MatrixXd());
      files.emplace_back(a.out + "/" + t.id + ".ndjson", mediapipe_ndjson(t.times, points, t.labels));
    }
  }
  files.emplace_back(a.out + "/labels.csv", label_table_csv(side));
  core::OutputBundle bundle;  // all takes and labels.csv, or nothing
  for (const auto& [path, content] : files) bundle.add(path, content);
  bundle.commit();
  std::cerr << "mgraph: wrote " << takes.size() << " " << a.format << " take(s) and labels.csv to " << a.out << "\n";
  return cli::kExitOk;
}

// A region motion graph as a picture (issue 19, item 4).
int dot(const Args& a) {
  const MotionGraph g = read_graph(a.graph);
  const RegionGraph* region = nullptr;
  std::string names;
  for (const auto& r : g.regions) {
    if (r.name == a.region) region = &r;
    names += (names.empty() ? "" : ", ") + r.name;
  }
  if (!region) throw cli::UsageError("--region: no region \"" + a.region + "\" (the graph has " + names + ")");
  GraphDotOptions o;
  o.depth = a.depth;
  o.edge_weights = a.edge_weights;
  core::write_dot(region_graph_dot(*region, o), a.out);
  return cli::kExitOk;
}

}  // namespace emoface::mgraph
