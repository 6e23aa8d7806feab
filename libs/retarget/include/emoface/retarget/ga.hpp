#pragma once
// The genetic algorithm of thesis §3.6 that moves the non-detected landmarks to minimise the error
// function (§3.5). Generic over the evaluation: the caller maps candidate landmark positions to an error.
//
// Chromosome (thesis §3.6.2): per landmark and coordinate, p = (v − Rmin)/(Rmax − Rmin) ∈ [0, 1] stored
// as an n-bit integer k (p = k/(2ⁿ − 1)); the range is a cube of edge `cube_size` centred on the
// landmark's initial position. Fitness 1/E. Competitive (tournament) selection, multi-point crossover
// (the first segment is never exchanged), bit-flip mutation whose rate starts at 0.3 and adapts in
// [0.3, 0.5]: down after a generation that lowered the best error, up after `stall_generations`
// generations without improvement (thesis §3.6.2). The best solution survives (elitism).
// Projection operator (thesis §3.6.2, "Additional Operation"): the evaluation may return the projected
// positions; ProjectionMode::Replace writes them back into the chromosome, EvaluateOnly does not.
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace emoface::retarget {

enum class ProjectionMode {
  Off,           ///< no projection
  EvaluateOnly,  ///< projection used to compute the error and the final solution (thesis: slower, better)
  Replace        ///< solutions replaced by their projection (thesis: fast, stuck in local minima)
};
std::string to_string(ProjectionMode mode);
ProjectionMode projection_mode_from_string(std::string_view name);

struct GaOptions {
  int population = 32;           ///< individuals, [4, 10000]
  int generations = 40;          ///< maximum generations, [0, 100000]
  int bits = 7;                  ///< n bits per coordinate (thesis §3.6.2: 5–10 work best), [2, 16]
  double cube_size = 0.03;       ///< edge of the search cube around each initial landmark, m, > 0
  int tournament = 2;            ///< competitors per selection, [1, population]
  int crossover_points = 4;      ///< multi-point crossover cut points, >= 1
  double crossover_rate = 0.9;   ///< probability that a pair is crossed over, [0, 1]
  double mutation_rate = 0.3;    ///< initial probability that an offspring is mutated (thesis: 0.3), [min, max]
  double mutation_min = 0.3;     ///< thesis §3.6.2: 0.3, [0, 1]
  double mutation_max = 0.5;     ///< thesis §3.6.2: 0.5, [mutation_min, 1]
  double mutation_step = 0.02;   ///< change of the rate per adaptation, [0, 1]
  int stall_generations = 2;     ///< generations without improvement before the rate goes up, >= 1
  /// Stop after this many generations without improving the best error by more than `tolerance`
  /// (relative); 0 = run all generations. >= 0.
  int patience = 0;
  double tolerance = 1e-6;       ///< relative improvement that counts, >= 0
  ProjectionMode projection = ProjectionMode::EvaluateOnly;
  std::uint64_t seed = 1;        ///< same seed + inputs = same result
  void validate() const;
};

struct GaProgress {
  int generation = 0;
  double best_error = 0.0;
  double mutation_rate = 0.0;
  long evaluations = 0;
};

struct GaReport {
  std::string status;                  ///< "max_generations" or "converged"
  std::string message;
  int generations = 0;                 ///< generations run
  long evaluations = 0;                ///< error evaluations
  double initial_error = 0.0;          ///< E of the initial landmarks
  double best_error = 0.0;             ///< E of the result
  std::vector<double> error_curve;     ///< best E after generation g (index 0 = initial population)
  std::vector<double> mutation_curve;  ///< mutation rate used in generation g
  double seconds = 0.0;                ///< wall time (the only non-deterministic field)
};

/// Maps candidate positions (#K by 3) to E. It may overwrite `positions` with their projection (used as
/// the final solution; written back into the chromosome only in Replace mode).
using GaEvaluate = std::function<double(Eigen::MatrixX3d& positions)>;

struct GaResult {
  Eigen::MatrixX3d positions;  ///< best positions found (#K by 3, projected when projection is on)
  GaReport report;
};

/// Runs the GA from `initial` (#K by 3, K ≥ 1). `progress` (optional) is called after every generation.
GaResult run_ga(const Eigen::MatrixX3d& initial, const GaEvaluate& evaluate, const GaOptions& options = {},
                const std::function<void(const GaProgress&)>& progress = {});

}  // namespace emoface::retarget
