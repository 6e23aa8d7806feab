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
#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/core/video.hpp"
#include "emoface/motiongraph/capture.hpp"
#include "emoface/core/graphviz.hpp"
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
  if (a.on_error == "stop") return OnError::Stop;
  if (a.on_error == "skip") return OnError::Skip;
  throw cli::UsageError("--on-error: unknown value \"" + a.on_error + "\" (expected stop|skip)");
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

// Sequences (one per animation) as a database of the graph's reduced landmarks, plus pictures.
int write_animation(const Args& a, const MotionGraph& g, const std::vector<Sequence>& seqs) {
  const bool weights = is_weight_space(g.dimensions);
  if (weights && !(a.video.empty() && a.sheet.empty() && a.plot.empty() && a.frames_dir.empty()))
    throw cli::UsageError("--video, --sheet, --plot and --frames-dir draw landmarks: not for a weight graph "
                          "(use --params and faceanim)");
  if (!weights && !(a.livelink_out.empty() && a.params_out.empty()))
    throw cli::UsageError("--livelink and --params need a weight graph (mgraph generate --space arkit)");
  Database db;
  db.dimensions = g.dimensions;
  db.frame_rate = g.frame_rate;
  db.landmark_ids = g.landmark_ids();
  db.landmark_count = db.landmark_ids.size();
  db.sequences = seqs;
  std::vector<Pose> all;
  for (const Sequence& s : seqs) all.insert(all.end(), s.frames.begin(), s.frames.end());
  const std::vector<int> groups = g.landmark_regions();
  if (!a.video.empty()) {  // GIF / MP4 / MOV / MKV through ffmpeg (core/video.hpp), written atomically
    core::VideoOptions vo;
    vo.width = a.video_width;
    vo.height = a.video_height;
    vo.fps = a.fps > 0.0 ? a.fps : g.frame_rate;
    core::VideoWriter video(a.video, vo);
    const View view = fit_view(all, vo.width, vo.height);
    for (const Pose& pose : all) {
      Image img(vo.width, vo.height);
      draw_contours(img, pose, contours_for(g.landmark_ids()), view);
      draw_pose(img, pose, groups, view, std::max(1.5, vo.width / 256.0));
      video.add_frame(img.rgb);
    }
    video.finish();
  }
  if (!a.sheet.empty()) {
    std::vector<Pose> shown;
    for (std::size_t f = 0; f < all.size(); f += static_cast<std::size_t>(a.every)) shown.push_back(all[f]);
    if ((all.size() - 1) % static_cast<std::size_t>(a.every) != 0) shown.push_back(all.back());
    core::write_file_atomic(a.sheet, encode_png(contact_sheet(shown, groups, a.columns, a.cell_width,
                                                              a.cell_width * 7 / 8, contours_for(g.landmark_ids()))));
  }
  if (!a.plot.empty()) core::write_file_atomic(a.plot, encode_png(plot_trajectories(all, groups)));
  if (!a.frames_dir.empty()) {
    std::filesystem::create_directories(a.frames_dir);
    const View view = fit_view(all, 640, 490);
    for (std::size_t f = 0; f < all.size(); ++f) {
      Image img(640, 490);
      draw_pose(img, all[f], groups, view);
      char name[32];
      std::snprintf(name, sizeof name, "/frame_%05zu.png", f);
      core::write_file_atomic(a.frames_dir + name, encode_png(img));
    }
  }
  // Weight graphs: the weights as Live Link Face CSV, the face parameters through the ARKit mapping
  // (exact, no landmark fit; bridge/weight_space.hpp). Everything computed before writing.
  std::string livelink, params;
  if (!a.livelink_out.empty()) livelink = bridge::live_link_csv(bridge::weight_take(g, all, "synth"), g.frame_rate);
  if (!a.params_out.empty()) {
    bridge::WeightDriveReport rep;
    params = muscles::format_parameter_frames_csv(bridge::weight_parameters(g, all, &rep));
    std::cerr << "mgraph: " << rep.frames << " frames of face parameters, largest weight error "
              << rep.max_weight_error << "\n";
  }
  cli::Output out(a.out);
  const bool csv = a.out.size() > 4 && a.out.substr(a.out.size() - 4) == ".csv";
  out.write(csv ? database_to_csv(db) : database_to_json(db));
  if (!a.livelink_out.empty()) core::write_file_atomic(a.livelink_out, livelink);
  if (!a.params_out.empty()) core::write_file_atomic(a.params_out, params);
  out.commit();
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
    std::vector<Sequence> mine;  // sequence i depends only on (seed, i)
    for (std::size_t i = 0; i < db.sequences.size(); ++i)
      if (shard.owns(i)) mine.push_back(std::move(db.sequences[i]));
    if (mine.empty()) throw InvalidInput("--shard " + a.shard + " owns none of the sequences");
    db.sequences = std::move(mine);
    cli::Output out(a.out);
    const bool csv = a.out.size() > 4 && a.out.substr(a.out.size() - 4) == ".csv";
    out.write(csv ? database_to_csv(db) : database_to_json(db));
    out.commit();
    return cli::kExitOk;
  }
  const std::unique_ptr<LandmarkModel> model = landmark_model(a);
  // Sequence i depends only on (seed, i): shards of a batch are parts of the same database.
  Database db;
  db.dimensions = 2;
  db.landmark_count = 68;
  db.frame_rate = o.frame_rate;
  const std::size_t count = synthetic_sequence_count(o);
  for (std::size_t i = 0; i < count; ++i)
    if (shard.owns(i)) db.sequences.push_back(synthetic_sequence(*model, o, i));
  if (db.sequences.empty()) throw InvalidInput("--shard " + a.shard + " owns none of the " + std::to_string(count) + " sequences");
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
    core::write_file_atomic(a.sheet, encode_png(contact_sheet(shown, groups, a.columns, a.cell_width,
                                                              a.cell_width * 7 / 8, contours_for(all_ids))));
  }
  cli::Output out(a.out);
  const bool csv = a.out.size() > 4 && a.out.substr(a.out.size() - 4) == ".csv";
  out.write(csv ? database_to_csv(db) : database_to_json(db));
  out.commit();
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

namespace {
// One chained animation from neutral: a transition per label (each sink the next source), idle after
// each when asked. Sequence ids start with `prefix`.
void synthesize_chain(const Args& a, const MotionGraph& g, const std::vector<std::string>& labels,
                      std::uint64_t seed, const std::string& prefix, std::vector<Sequence>& seqs) {
  const bool weights = is_weight_space(g.dimensions);
  SynthesisOptions o = weights ? weight_synthesis_options() : SynthesisOptions{};
  o.seed = seed;
  o.vary_duration = a.vary;
  o.replace_probability = a.replace;
  o.path_fraction = a.hint;
  o.smoothing.sigmoid = !a.no_sigmoid;
  std::vector<Label> parsed;
  for (const std::string& name : labels) parsed.push_back(label_from_string(name));  // all checked first
  if (parsed.empty()) throw InvalidInput("no labels");
  SynthesisState state = initial_state(g);
  std::vector<Sequence> out;
  for (std::size_t k = 0; k < parsed.size(); ++k) {
    const std::string& name = labels[k];
    out.push_back({prefix + "synth_" + std::to_string(out.size()) + "_" + name, "", parsed[k],
                   synthesize(g, state, parsed[k], o)});
    if (a.idle_after > 0.0) {
      IdleOptions io = weights ? weight_idle_options() : IdleOptions{};
      io.duration = a.idle_after;
      io.seed = seed;
      out.push_back({prefix + "idle_" + std::to_string(out.size()) + "_" + name, "", parsed[k],
                     idle(g, state, parsed[k], io)});
    }
  }
  seqs.insert(seqs.end(), out.begin(), out.end());
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t pos = 0;
  while (true) {
    const std::size_t e = s.find(sep, pos);
    parts.push_back(s.substr(pos, e == std::string::npos ? std::string::npos : e - pos));
    if (e == std::string::npos) return parts;
    pos = e + 1;
  }
}
}  // namespace

int synth(const Args& a) {
  const MotionGraph g = read_graph(a.graph);
  std::vector<Sequence> seqs;
  if (!a.requests.empty() && !a.labels.empty()) throw cli::UsageError("give --labels or --requests, not both");
  if (a.requests.empty()) {
    if (a.labels.empty()) throw cli::UsageError("give --labels or --requests");
    synthesize_chain(a, g, a.labels, a.seed, "", seqs);
    return write_animation(a, g, seqs);
  }
  // Batch: CSV with header "id,labels", labels separated by ';'. Request r uses the seed stream r,
  // so --shard runs produce the same animations as one run.
  const cli::Shard shard = cli::parse_shard(a.shard);
  const OnError policy = on_error(a);
  const std::string text = core::read_file(a.requests);
  std::vector<std::string> fields;
  std::size_t line_no = 0, pos = 0, record = 0, skipped = 0;
  bool header = true;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::string err;
    const std::size_t col = core::split_csv_line(line, fields, &err);
    if (header) {
      if (col != 0 || fields.size() != 2 || fields[0] != "id" || fields[1] != "labels")
        throw FormatError({a.requests, "", line_no, 1}, "header must be \"id,labels\"");
      header = false;
      continue;
    }
    const std::size_t index = record++;
    if (!shard.owns(index)) continue;
    try {
      if (col != 0) throw FormatError({a.requests, "", line_no, col}, err);
      if (fields.size() != 2)
        throw FormatError({a.requests, "", line_no, 1}, "expected 2 fields (id,labels), got " + std::to_string(fields.size()));
      if (fields[0].empty()) throw FormatError({a.requests, "", line_no, 1}, "empty request id");
      std::vector<Sequence> mine;
      try {
        synthesize_chain(a, g, split(fields[1], ';'), core::derive_seed(a.seed, index), fields[0] + "/", mine);
      } catch (const InvalidInput& e) {
        throw FormatError({a.requests, "", line_no, 2}, e.what());
      }
      seqs.insert(seqs.end(), mine.begin(), mine.end());
    } catch (const FormatError& e) {
      if (policy == OnError::Stop) throw;
      std::cerr << "mgraph: skipped: " << e.what() << "\n";
      ++skipped;
    }
  }
  if (header) throw FormatError({a.requests, "", 1, 1}, "empty requests file (no header)");
  if (skipped) std::cerr << "mgraph: " << skipped << " request(s) skipped\n";
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
  if (shard.count > 1)
    std::printf("shard %zu/%zu: samples with index %% %zu == %zu (graphs from the whole database)\n", shard.index,
                shard.count, shard.count, shard.index);
  // The sums let rows of shards be merged exactly (motiongraph::merge_rows; docs/motiongraph.md).
  std::string csv = core::csv_stamp() + "threshold,compression_percent,nodes,length_diff_mean,length_diff_std,pose_diff_mean,"
                    "pose_diff_std,samples,distances,length_sum,length_sum2,pose_sum,pose_sum2" +
                    std::string(raw ? ",raw_pose_diff_mean,raw_pose_diff_std,raw_pose_sum,raw_pose_sum2" : "") +
                    "\n";
  const char* unit = weights ? "(weight)" : "(px)";
  std::printf("%10s %14s %7s %22s %22s%s\n", "threshold", "compression %", "nodes", "length diff (frames)",
              (std::string("pose diff ") + unit).c_str(),
              raw ? (std::string("   vs raw samples ") + unit).c_str() : "");
  for (double t : thresholds) {
    const EvaluationRow r = evaluate(data, t, eo, raw ? &*raw : nullptr);
    std::printf("%10.4f %14.2f %7zu %10.3f +- %-8.3f %10.4f +- %-8.4f", t, 100 * r.compression, r.nodes,
                r.length_mean, r.length_std, r.pose_mean, r.pose_std);
    if (raw) std::printf(" %10.4f +- %-8.4f", r.raw_pose_mean, r.raw_pose_std);
    std::printf("\n");
    char line[640];
    std::snprintf(line, sizeof line, "%.6g,%.4f,%zu,%.6g,%.6g,%.6g,%.6g,%zu,%zu,%.17g,%.17g,%.17g,%.17g", t,
                  100 * r.compression, r.nodes, r.length_mean, r.length_std, r.pose_mean, r.pose_std, r.samples,
                  r.distances, r.length_sum, r.length_sum2, r.pose_sum, r.pose_sum2);
    csv += line;
    if (raw) {
      std::snprintf(line, sizeof line, ",%.6g,%.6g,%.17g,%.17g", r.raw_pose_mean, r.raw_pose_std, r.raw_pose_sum,
                    r.raw_pose_sum2);
      csv += line;
    }
    csv += "\n";
  }
  std::printf("paper (CK+, 70 sequences): 90%% -> 0.98 +- 1.84 frames, 2.86 +- 2.3 px; 78%% -> 0.071 +- 0.39, "
              "2.12 +- 1.81; 57.53%% -> 0 +- 0, 1.52 +- 1.51\n");
  if (a.out != "-") core::write_file_atomic(a.out, csv);
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
  cli::Output out(a.out);
  const bool csv = a.out.size() > 4 && a.out.substr(a.out.size() - 4) == ".csv";
  out.write(csv ? database_to_csv(db) : database_to_json(db));
  out.commit();
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
    std::filesystem::create_directories(a.out);
    for (const auto& [path, content] : files) core::write_file_atomic(path, content);
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
  std::filesystem::create_directories(a.out);
  for (const auto& [path, content] : files) core::write_file_atomic(path, content);
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
  const std::string text = region_graph_dot(*region, o);
  const auto ext = std::filesystem::path(a.out).extension().string();
  if (ext == ".svg" || ext == ".png" || ext == ".pdf") {
    core::render_dot(text, a.out);
  } else {
    cli::Output out(a.out);
    out.write(text);
    out.commit();
  }
  return cli::kExitOk;
}

}  // namespace emoface::mgraph
