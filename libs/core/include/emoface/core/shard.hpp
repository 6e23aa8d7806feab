#pragma once
// Splitting a batch across processes (issue 18, docs/scale-out.md). `--shard i/N` gives process i
// of N the i-th *contiguous* block of the items, so the shard outputs, concatenated (or merged with
// merge_shard_outputs) in shard order, are the single-process output. `--shard auto` takes i and N
// from a Slurm job array (SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN, SLURM_ARRAY_TASK_COUNT).
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace emoface::core {

struct Shard {
  std::size_t index = 0;  ///< 0 <= index < count
  std::size_t count = 1;  ///< number of processes, >= 1

  /// The contiguous block [first, last) of `total` items this shard handles: first =
  /// floor(index · total / count), last = floor((index + 1) · total / count). The blocks of shards
  /// 0 … count−1 tile [0, total) in order; their sizes differ by at most one.
  std::pair<std::size_t, std::size_t> block(std::size_t total) const noexcept;
  /// True if `item` (< total) lies in block(total).
  bool owns(std::size_t item, std::size_t total) const noexcept;
  /// Interleaved ownership (item % count == index), kept for tools whose items have no known total
  /// (mgraph). Interleaved shard outputs do not concatenate back in order.
  bool owns(std::size_t item) const noexcept { return item % count == index; }
};

/// Parses "i/N" (0 <= i < N, decimal) or "auto" (from `getenv`, default std::getenv: the Slurm
/// array variables). Throws InvalidInput with a message naming what is wrong.
Shard parse_shard(std::string_view text,
                  const std::function<const char*(const char*)>& getenv = nullptr);

/// Merges shard outputs of a line-oriented stream, given in shard order, into the text one process
/// would have written: the first part whole; from every later part its leading stamp lines ('#'
/// lines and NDJSON stream-header records {"format": "emoface.…", …}) and, when the first part is
/// CSV (its first line after the stamps does not start with '{'), a header line equal to the first
/// part's. Throws InvalidInput if a later CSV part's header differs from the first part's.
std::string merge_shard_outputs(const std::vector<std::string>& parts);

}  // namespace emoface::core
