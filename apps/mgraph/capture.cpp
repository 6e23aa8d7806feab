// mgraph capture and capture-example (issue 19), dot (a region graph as a picture).
#include "emoface/motiongraph/capture.hpp"

#include <iostream>
#include <optional>

#include "commands.hpp"
#include "emoface/bridge/face_landmark_model.hpp"
#include "emoface/bridge/weight_space.hpp"
#include "emoface/cli/cli.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/core/graphviz.hpp"
#include "emoface/motiongraph/batch.hpp"
#include "emoface/motiongraph/dot.hpp"

namespace emoface::mgraph {

using namespace motiongraph;

namespace {

template <class Options>
void validate_usage(const Options& o) {
  try {
    o.validate();
  } catch (const InvalidInput& e) {
    throw cli::UsageError(e.what());
  }
}

// Every take file and labels.csv under `dir`, or nothing.
void commit_takes(const std::string& dir,
                  const std::vector<std::pair<std::string, std::string>>& files,
                  const LabelTable& labels) {
  core::OutputBundle bundle;
  for (const auto& [name, content] : files) bundle.add(dir + "/" + name, content);
  bundle.add(dir + "/labels.csv", label_table_csv(labels));
  bundle.commit();
}

}  // namespace

// Tracker files (OpenFace CSV, MediaPipe NDJSON, Live Link Face CSV; one take each) → cleaned,
// stabilised, trimmed, labelled database.
int capture(const Args& a) {
  if ((a.openface.empty() ? 0 : 1) + (a.mediapipe.empty() ? 0 : 1) + (a.livelink.empty() ? 0 : 1) !=
      1)
    throw cli::UsageError("give --openface, --mediapipe or --livelink files (one kind)");
  if (!a.livelink.empty() && !a.label_column.empty())
    throw cli::UsageError(
        "--label-column: Live Link Face files have no label column (use --labels)");
  if (!(a.timecode_fps > 0.0 && a.timecode_fps <= 1000.0))
    throw cli::UsageError("--timecode-fps must be in (0, 1000]");
  CaptureOptions co;
  co.on_error = on_error(a);
  co.filter.min_confidence = a.min_confidence;
  co.filter.max_gap = a.max_gap;
  co.stabilise = !a.no_stabilise;
  co.trim = !a.no_trim;
  validate_usage(co);
  OpenFaceReadOptions oo;
  oo.use_3d = a.use_3d;
  oo.label_column = a.label_column;
  MediaPipeReadOptions mo;
  mo.image_width = a.image_width;
  mo.image_height = a.image_height;
  mo.use_z = a.use_3d;
  std::vector<TrackedFrames> takes;
  for (const auto& f : a.openface) takes.push_back(read_openface_csv(f, oo));
  for (const auto& f : a.mediapipe) takes.push_back(read_mediapipe_ndjson(f, mo));
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
  std::cerr << "mgraph: " << takes.size() << " take(s) → " << db.sequences.size()
            << " labelled neutral-to-peak "
            << "sequence(s), " << frames << " frames at " << db.frame_rate << " fps\n";
  return cli::kExitOk;
}

// Example tracker files from emoface's own face: one file per take and the labels side file.
int capture_example(const Args& a) {
  if (a.format != "openface" && a.format != "mediapipe" && a.format != "livelink")
    throw cli::UsageError("--format: unknown value \"" + a.format +
                          "\" (expected openface|mediapipe|livelink)");
  SyntheticOptions so;
  so.seed = a.seed;
  so.sequences_per_label = a.per_label;
  so.subjects = a.subjects;
  so.min_frames = a.min_frames;
  so.max_frames = a.max_frames;
  std::vector<TrackedFrames> takes;
  std::vector<std::pair<std::string, std::string>> files;  // everything computed before writing
  if (a.format == "livelink") {  // ARKit weights of the face model (issue 19 item 2)
    bridge::WeightTakeOptions wo;
    wo.database.database = so;
    wo.database.noise_std = a.weight_noise;
    wo.rest_frames = a.rest_frames;
    wo.hold_frames = a.hold_frames;
    validate_usage(wo);
    takes = bridge::generate_weight_takes(bridge::FaceLandmarkModel(), wo);
    if (a.max_takes > 0 && takes.size() > a.max_takes) takes.resize(a.max_takes);
    for (const TrackedFrames& t : takes)
      files.emplace_back(t.id + ".csv", bridge::live_link_csv(t, so.frame_rate));
    commit_takes(a.out, files, bridge::weight_take_labels(takes));
  } else {
    CaptureExampleOptions o;
    o.database = so;
    o.database.noise_std = a.noise;
    o.rest_frames = a.rest_frames;
    o.hold_frames = a.hold_frames;
    validate_usage(o);
    takes = generate_capture_takes(*landmark_model(a), o);
    if (a.max_takes > 0 && takes.size() > a.max_takes) takes.resize(a.max_takes);
    for (const TrackedFrames& t : takes)
      files.emplace_back(a.format == "openface" ? t.id + ".csv" : t.id + ".ndjson",
                         a.format == "openface" ? openface_csv(t) : mediapipe_ndjson(t));
    commit_takes(a.out, files, segment_label_table(takes));
  }
  std::cerr << "mgraph: wrote " << takes.size() << " " << a.format << " take(s) and labels.csv to "
            << a.out << "\n";
  return cli::kExitOk;
}

// A region motion graph as a picture (issue 19, item 4).
int dot(const Args& a) {
  const MotionGraph g = read_graph(a.graph);
  GraphDotOptions o;
  o.depth = a.depth;
  o.edge_weights = a.edge_weights;
  const RegionGraph* region = nullptr;
  try {
    region = &g.region(a.region);
  } catch (const InvalidInput& e) {
    throw cli::UsageError(std::string("--region: ") + e.what());
  }
  core::write_dot(region_graph_dot(*region, o), a.out);
  return cli::kExitOk;
}

}  // namespace emoface::mgraph
