#include "emoface/retarget/ga.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::retarget {

std::string to_string(ProjectionMode mode) {
  switch (mode) {
    case ProjectionMode::Off: return "off";
    case ProjectionMode::EvaluateOnly: return "evaluate_only";
    case ProjectionMode::Replace: return "replace";
  }
  return "off";
}

ProjectionMode projection_mode_from_string(std::string_view name) {
  for (auto m : {ProjectionMode::Off, ProjectionMode::EvaluateOnly, ProjectionMode::Replace})
    if (to_string(m) == name) return m;
  throw InvalidInput("unknown projection mode \"" + std::string(name) + "\" (expected off, evaluate_only or replace)");
}

void GaOptions::validate() const {
  auto need = [](bool ok, const char* what) {
    if (!ok) throw InvalidInput(std::string("GaOptions::") + what);
  };
  need(population >= 4 && population <= 10000, "population must be in [4, 10000]");
  need(generations >= 0 && generations <= 100000, "generations must be in [0, 100000]");
  need(bits >= 2 && bits <= 16, "bits must be in [2, 16]");
  need(cube_size > 0.0 && std::isfinite(cube_size), "cube_size must be finite and > 0");
  need(tournament >= 1 && tournament <= population, "tournament must be in [1, population]");
  need(crossover_points >= 1, "crossover_points must be >= 1");
  need(crossover_rate >= 0.0 && crossover_rate <= 1.0, "crossover_rate must be in [0, 1]");
  need(mutation_min >= 0.0 && mutation_min <= 1.0, "mutation_min must be in [0, 1]");
  need(mutation_max >= mutation_min && mutation_max <= 1.0, "mutation_max must be in [mutation_min, 1]");
  need(mutation_rate >= mutation_min && mutation_rate <= mutation_max, "mutation_rate must be in [mutation_min, mutation_max]");
  need(mutation_step >= 0.0 && mutation_step <= 1.0, "mutation_step must be in [0, 1]");
  need(stall_generations >= 1, "stall_generations must be >= 1");
  need(patience >= 0, "patience must be >= 0");
  need(tolerance >= 0.0 && std::isfinite(tolerance), "tolerance must be finite and >= 0");
}

namespace {
using Chromosome = std::vector<std::uint8_t>;

struct Codec {
  Eigen::MatrixX3d lo;  // Rmin per landmark/coordinate
  double range = 0.0;
  int bits = 0;
  double levels = 0.0;  // 2^n − 1
  std::size_t length() const { return static_cast<std::size_t>(lo.rows()) * 3 * static_cast<std::size_t>(bits); }
  // thesis §3.6.2: v = p·(Rmax − Rmin) + Rmin, p = k/(2ⁿ − 1)
  Eigen::MatrixX3d decode(const Chromosome& c) const {
    Eigen::MatrixX3d v(lo.rows(), 3);
    std::size_t pos = 0;
    for (Eigen::Index i = 0; i < lo.rows(); ++i)
      for (int k = 0; k < 3; ++k) {
        std::uint32_t value = 0;
        for (int b = 0; b < bits; ++b) value = (value << 1) | c[pos++];
        v(i, k) = lo(i, k) + range * (static_cast<double>(value) / levels);
      }
    return v;
  }
  void encode(const Eigen::MatrixX3d& v, Chromosome& c) const {
    std::size_t pos = 0;
    for (Eigen::Index i = 0; i < lo.rows(); ++i)
      for (int k = 0; k < 3; ++k) {
        const double p = std::clamp((v(i, k) - lo(i, k)) / range, 0.0, 1.0);
        const auto value = static_cast<std::uint32_t>(std::lround(p * levels));
        for (int b = bits - 1; b >= 0; --b) c[pos++] = static_cast<std::uint8_t>((value >> b) & 1u);
      }
  }
};
}  // namespace

GaResult run_ga(const Eigen::MatrixX3d& initial, const GaEvaluate& evaluate, const GaOptions& options,
                const std::function<void(const GaProgress&)>& progress) {
  options.validate();
  if (initial.rows() < 1 || !initial.allFinite()) throw InvalidInput("run_ga: need at least one finite landmark");
  if (!evaluate) throw InvalidInput("run_ga: no evaluation function");
  const auto start = std::chrono::steady_clock::now();
  Codec codec;
  codec.bits = options.bits;
  codec.levels = std::ldexp(1.0, options.bits) - 1.0;
  codec.range = options.cube_size;
  // Cube around the initial landmark (thesis Fig. 3.5), shifted by half a step so that the initial
  // landmark itself is representable (k = 2ⁿ⁻¹).
  codec.lo = initial.array() - (std::ldexp(1.0, options.bits - 1) / codec.levels) * options.cube_size;
  const std::size_t length = codec.length();
  core::Rng rng(options.seed, 0x6761);
  const auto pop_size = static_cast<std::size_t>(options.population);

  GaResult result;
  GaReport& report = result.report;
  std::vector<Chromosome> pop(pop_size, Chromosome(length));
  std::vector<double> error(pop_size);
  std::vector<Eigen::MatrixX3d> shown(pop_size);  // evaluated (possibly projected) positions
  codec.encode(initial, pop[0]);  // individual 0: the initial landmarks
  for (std::size_t i = 1; i < pop_size; ++i)
    for (auto& bit : pop[i]) bit = static_cast<std::uint8_t>(rng.uniform_int(2));
  auto evaluate_one = [&](std::size_t i) {
    Eigen::MatrixX3d positions = codec.decode(pop[i]);
    const double e = evaluate(positions);
    ++report.evaluations;
    error[i] = std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
    if (options.projection == ProjectionMode::Replace) codec.encode(positions, pop[i]);
    shown[i] = std::move(positions);
  };
  {  // the exact initial landmarks, for the report
    Eigen::MatrixX3d positions = initial;
    report.initial_error = evaluate(positions);
    ++report.evaluations;
  }
  for (std::size_t i = 0; i < pop_size; ++i) evaluate_one(i);
  auto best_index = [&]() { return static_cast<std::size_t>(std::min_element(error.begin(), error.end()) - error.begin()); };
  double best = error[best_index()];
  double rate = options.mutation_rate;
  report.error_curve.push_back(best);
  report.mutation_curve.push_back(rate);
  int stall = 0, quiet = 0;
  report.status = "max_generations";
  auto select = [&]() {  // competitive (tournament) selection: lower E = higher fitness 1/E
    std::size_t winner = static_cast<std::size_t>(rng.uniform_int(pop_size));
    for (int t = 1; t < options.tournament; ++t) {
      const auto c = static_cast<std::size_t>(rng.uniform_int(pop_size));
      if (error[c] < error[winner]) winner = c;
    }
    return winner;
  };
  std::vector<std::size_t> cuts;
  for (int g = 1; g <= options.generations; ++g) {
    std::vector<Chromosome> next;
    next.reserve(pop_size);
    next.push_back(pop[best_index()]);  // elitism
    while (next.size() < pop_size) {
      Chromosome a = pop[select()], b = pop[select()];
      if (rng.uniform() < options.crossover_rate) {
        // Multi-point crossover (thesis §3.6.2, Fig. 3.6): distinct sorted cut points; segments after
        // odd-numbered cuts are exchanged, the segment before the first cut never is.
        const auto points = std::min<std::size_t>(static_cast<std::size_t>(options.crossover_points), length - 1);
        cuts.clear();
        while (cuts.size() < points) {
          const auto c = 1 + static_cast<std::size_t>(rng.uniform_int(length - 1));
          if (std::find(cuts.begin(), cuts.end(), c) == cuts.end()) cuts.push_back(c);
        }
        std::sort(cuts.begin(), cuts.end());
        cuts.push_back(length);
        for (std::size_t s = 0; s + 1 < cuts.size(); s += 2)
          for (std::size_t k = cuts[s]; k < cuts[s + 1]; ++k) std::swap(a[k], b[k]);
      }
      for (Chromosome* child : {&a, &b}) {
        if (next.size() >= pop_size) break;
        if (rng.uniform() < rate) {  // bit-flip mutation: one random bit, then each bit with p = 1/L
          (*child)[static_cast<std::size_t>(rng.uniform_int(length))] ^= 1u;
          for (auto& bit : *child)
            if (rng.uniform() * static_cast<double>(length) < 1.0) bit ^= 1u;
        }
        next.push_back(std::move(*child));
      }
    }
    // The elite keeps its evaluation.
    const std::size_t elite = best_index();
    const double elite_error = error[elite];
    Eigen::MatrixX3d elite_shown = shown[elite];
    pop = std::move(next);
    error[0] = elite_error;
    shown[0] = std::move(elite_shown);
    for (std::size_t i = 1; i < pop_size; ++i) evaluate_one(i);
    const double now = error[best_index()];
    // Adaptive mutation rate in [0.3, 0.5] (thesis §3.6.2).
    const bool improved = now < best * (1.0 - options.tolerance);
    if (now < best) {
      rate = std::max(options.mutation_min, rate - options.mutation_step);
      stall = 0;
    } else if (++stall >= options.stall_generations) {
      rate = std::min(options.mutation_max, rate + options.mutation_step);
      stall = 0;
    }
    quiet = improved ? 0 : quiet + 1;
    best = std::min(best, now);
    report.generations = g;
    report.error_curve.push_back(best);
    report.mutation_curve.push_back(rate);
    if (progress) progress({g, best, rate, report.evaluations});
    if (options.patience > 0 && quiet >= options.patience) {
      report.status = "converged";
      break;
    }
  }
  const std::size_t b = best_index();
  result.positions = shown[b];
  report.best_error = error[b];
  if (report.initial_error <= report.best_error) {  // never return worse than the start
    result.positions = initial;
    Eigen::MatrixX3d positions = initial;
    report.best_error = evaluate(positions);
    ++report.evaluations;
    result.positions = positions;
  }
  report.message = "best E " + std::to_string(report.best_error) + " after " + std::to_string(report.generations) + " generations";
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace emoface::retarget
