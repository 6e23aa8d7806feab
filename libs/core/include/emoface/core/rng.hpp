#pragma once
// Seeded, portable random numbers. Every random choice in emoface takes an Rng built from a user seed,
// so the same inputs and seed give byte-identical output on every platform: the generator
// (xoshiro256**, seeded through SplitMix64) and the distributions below are implemented here rather
// than taken from <random>, whose distributions differ between standard libraries.
#include <cstdint>

namespace emoface::core {

/// SplitMix64 step: advances `state` and returns a well-mixed 64-bit value.
std::uint64_t splitmix64(std::uint64_t& state) noexcept;

/// Mixes a seed and a stream id (e.g. a row index or character id) into one independent seed, so
/// work split across processes (--shard) draws the same numbers as an unsplit run.
std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) noexcept;

class Rng {
 public:
  /// A generator for (seed, stream); different streams of one seed are independent.
  explicit Rng(std::uint64_t seed = 0, std::uint64_t stream = 0) noexcept;

  std::uint64_t next_u64() noexcept;
  /// Uniform in [0, 1), 53 random bits.
  double uniform() noexcept;
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) noexcept { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n), unbiased (Lemire's method). n must be > 0.
  std::uint64_t uniform_int(std::uint64_t n) noexcept;
  /// Standard normal (Box–Muller, both values used).
  double normal() noexcept;
  double normal(double mean, double stddev) noexcept { return mean + stddev * normal(); }
  /// Exponential with the given rate (> 0).
  double exponential(double rate) noexcept;

 private:
  std::uint64_t s_[4];
  double spare_normal_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace emoface::core
