// mgraph generate and build, and the glue the subcommands share.
#include "commands.hpp"

#include <iostream>

#include "emoface/bridge/face_landmark_model.hpp"
#include "emoface/bridge/weight_space.hpp"
#include "emoface/cli/cli.hpp"
#include "emoface/core/bundle.hpp"
#include "emoface/motiongraph/batch.hpp"
#include "emoface/motiongraph/layout.hpp"
#include "emoface/motiongraph/weights.hpp"

namespace emoface::mgraph {

using namespace motiongraph;

OnError on_error(const Args& a) {
  return cli::parse_enum<OnError>(a.on_error, core::on_error_from_string, "--on-error",
                                  "stop|skip");
}

void print_skipped(const ReadReport& report, const char* what) {
  for (const std::string& m : report.skipped) std::cerr << "mgraph: skipped: " << m << "\n";
  if (!report.skipped.empty())
    std::cerr << "mgraph: " << report.skipped.size() << " " << what << " skipped\n";
}

Database load_database(const Args& a) {
  if (a.db.empty() == a.ckplus.empty()) throw InvalidInput("give exactly one of --db and --ckplus");
  ReadReport report;
  CkPlusOptions ck;
  ck.on_error = on_error(a);
  Database db = a.db.empty() ? read_ck_plus(a.ckplus, ck, &report)
                             : read_database(a.db, 30.0, ck.on_error, &report);
  print_skipped(report);
  return db;
}

PreparedDatabase prepare(const Args& a, const Database& db, bool clean, bool quiet) {
  const bool weights = is_weight_space(db.dimensions);
  // Weight databases: the ARKit regions for 52 channels (bridge::arkit_layout), else one region.
  const LandmarkLayout layout = !a.layout.empty()                     ? read_layout(a.layout)
                                : db.landmark_count == 68 && !weights ? default_layout()
                                : db.landmark_count == 52 && weights
                                    ? bridge::arkit_layout()
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

GraphOptions graph_options(const Args& a, int dimensions) {
  GraphOptions g = is_weight_space(dimensions) ? weight_graph_options() : GraphOptions{};
  g.similarity.lambda = a.lambda;
  g.seed = a.seed;
  if (a.sample_threshold >= 0.0) g.sample_threshold = a.sample_threshold;
  if (a.merge_threshold >= 0.0) g.merge_threshold = a.merge_threshold;
  return g;
}

std::unique_ptr<LandmarkModel> landmark_model(const Args& a) {
  if (a.model == "parametric") return std::make_unique<ParametricLandmarkModel>();
  if (a.model != "face")
    throw cli::UsageError("--model: unknown value \"" + a.model + "\" (expected face|parametric)");
  bridge::FaceLandmarkModelOptions fo;
  fo.projection = cli::parse_enum<bridge::Projection>(a.projection, bridge::projection_from_string,
                                                      "--projection", "perspective|orthographic");
  fo.camera_distance = a.camera_distance;
  return std::make_unique<bridge::FaceLandmarkModel>(fo);
}

int generate(const Args& a) {
  SyntheticOptions o;
  o.seed = a.seed;
  o.sequences_per_label = a.per_label;
  o.subjects = a.subjects;
  o.noise_std = a.noise;
  const cli::Shard shard = cli::parse_shard(a.shard);
  if (a.space != "landmarks" && a.space != "arkit")
    throw cli::UsageError("--space: unknown value \"" + a.space + "\" (expected landmarks|arkit)");
  bridge::WeightDatabaseOptions wo;  // weight space (issue 19 item 2): ARKit-52 weights of the face
  if (a.space == "arkit") {
    if (a.model != "face") throw cli::UsageError("--space arkit needs --model face");
    if (!a.sheet.empty()) throw cli::UsageError("--sheet draws landmarks: not with --space arkit");
    wo.database = o;
    wo.noise_std = a.weight_noise;
    try {
      wo.validate();
    } catch (const InvalidInput& e) {
      throw cli::UsageError(e.what());
    }
  }
  // Sequence i depends only on (seed, i): a shard keeps its contiguous block.
  const std::size_t count = synthetic_sequence_count(o);
  const auto block = shard.block(count);
  if (block.first == block.second)
    throw InvalidInput("--shard " + a.shard + " owns none of the " + std::to_string(count) +
                       " sequences");
  const Database db =
      a.space == "arkit"
          ? database_block(bridge::generate_weight_database(bridge::FaceLandmarkModel(), wo), block)
          : generate_synthetic_database(*landmark_model(a), o, block);
  core::OutputBundle bundle;
  if (!a.sheet.empty()) stage_peaks_sheet(bundle, a.sheet, db, a.columns, a.cell_width);
  stage_database(bundle, a.out, db);
  bundle.commit();
  return cli::kExitOk;
}

int build(const Args& a) {
  const PreparedDatabase data = prepare(a, load_database(a), true);
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

}  // namespace emoface::mgraph
