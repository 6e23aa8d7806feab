// mgraph eval: the paper's §7 table, compression against length and pose error.
#include <cstdio>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "emoface/cli/cli.hpp"
#include "emoface/core/io.hpp"
#include "emoface/motiongraph/batch.hpp"
#include "emoface/motiongraph/weights.hpp"

namespace emoface::mgraph {

using namespace motiongraph;

int eval(const Args& a) {
  const Database db = load_database(a);
  const PreparedDatabase data = prepare(a, db, true);
  // --raw: the same samples without sigmoid cleaning (issue 19: compare with what the tracker
  // gave).
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
  std::vector<EvaluationRow> rows;
  for (double t : thresholds) rows.push_back(evaluate(data, t, eo, raw ? &*raw : nullptr));
  std::cout << evaluation_table(rows, weights ? "weight" : "px");
  // The sums let rows of shards be merged exactly (read_evaluation_csv + merge_rows).
  if (a.out != "-") core::write_file_atomic(a.out, evaluation_csv(rows));
  return cli::kExitOk;
}

}  // namespace emoface::mgraph
