// fuzzyexpr throughput: ESV → FMCV conversions per second per core, for single, blend and auto modes,
// and fuzzylite (test-only oracle) evaluating the same engine (exported FLL, centroid resolution 1000,
// the resolution the agreement test uses) on the same inputs in the same run; the ratio is printed.
//
//   build-bench/tests/bench/fuzzyexpr_bench                      # all benchmarks + ratios
//   build-bench/tests/bench/fuzzyexpr_bench --write-csv F N      # N-row ESV CSV for the CLI benchmark
#include <benchmark/benchmark.h>
#include <fl/Headers.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "emoface/core/io.hpp"
#include "emoface/core/rng.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/io.hpp"

namespace fx = emoface::fuzzyexpr;

namespace {

// Mixed inputs: half uniform random ESVs, half one or two active emotions (the common case for an
// agent), seeded.
const std::vector<fx::Esv>& inputs() {
  static const std::vector<fx::Esv> v = [] {
    emoface::core::Rng rng(2026);
    std::vector<fx::Esv> out(4096);
    for (std::size_t i = 0; i < out.size(); ++i) {
      fx::Esv e{};
      if (i % 2 == 0) {
        for (double& x : e) x = rng.uniform();
      } else {
        e[rng.uniform_int(6)] = rng.uniform();
        e[rng.uniform_int(6)] = rng.uniform();
      }
      out[i] = e;
    }
    return out;
  }();
  return v;
}

void run_emoface(benchmark::State& state, fx::ExpressionMode mode) {
  fx::ExpressionOptions o;
  o.mode = mode;
  const fx::Engine engine(fx::default_rule_base(), o);
  const auto& in = inputs();
  std::size_t i = 0;
  for (auto _ : state) {
    fx::Fmcv f = engine.convert(in[i]);
    benchmark::DoNotOptimize(f);
    i = (i + 1) & (in.size() - 1);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void run_fuzzylite(benchmark::State& state, fx::ExpressionMode mode) {
  fx::ExpressionOptions o;
  o.mode = mode;
  const fx::Engine ours(fx::default_rule_base(), o);
  fx::FllOptions fll;
  fll.centroid_resolution = 1000;
  std::unique_ptr<fl::Engine> engine(fl::FllImporter().fromString(fx::to_fll(fx::default_rule_base(), fll)));
  const auto& in = inputs();
  // Block per input, chosen by emoface's (cheap, crisp) mode selection outside the timed loop.
  std::vector<fl::RuleBlock*> blocks;
  for (const auto& esv : in) {
    const fx::Selection s = ours.select(esv);
    std::string name = "single_" + std::string(fx::to_string(s.first));
    if (s.mode == fx::ExpressionMode::Blend && s.pair_has_rules)
      for (const auto& b : ours.rules().blend)
        if ((b.first == s.first && b.second == s.second) || (b.first == s.second && b.second == s.first))
          name = "blend_" + std::string(fx::to_string(b.first)) + "_" + std::string(fx::to_string(b.second));
    blocks.push_back(engine->getRuleBlock(name));
  }
  std::vector<fl::InputVariable*> vars;
  for (std::size_t e = 0; e < fx::kEmotionCount; ++e)
    vars.push_back(engine->getInputVariable(std::string(fx::to_string(fx::emotion_at(e)))));
  std::size_t i = 0;
  fl::RuleBlock* enabled = nullptr;
  for (auto _ : state) {
    if (blocks[i] != enabled) {
      if (enabled) enabled->setEnabled(false);
      blocks[i]->setEnabled(true);
      enabled = blocks[i];
    }
    for (std::size_t e = 0; e < fx::kEmotionCount; ++e) vars[e]->setValue(in[i][e]);
    engine->process();
    double sum = 0.0;
    for (std::size_t m = 0; m < engine->numberOfOutputVariables(); ++m)
      sum += engine->getOutputVariable(m)->getValue();
    benchmark::DoNotOptimize(sum);
    i = (i + 1) & (in.size() - 1);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

BENCHMARK_CAPTURE(run_emoface, single, fx::ExpressionMode::Single)->Name("emoface/single");
BENCHMARK_CAPTURE(run_emoface, blend, fx::ExpressionMode::Blend)->Name("emoface/blend");
BENCHMARK_CAPTURE(run_emoface, auto, fx::ExpressionMode::Auto)->Name("emoface/auto");
BENCHMARK_CAPTURE(run_fuzzylite, single, fx::ExpressionMode::Single)->Name("fuzzylite/single");
BENCHMARK_CAPTURE(run_fuzzylite, blend, fx::ExpressionMode::Blend)->Name("fuzzylite/blend");
BENCHMARK_CAPTURE(run_fuzzylite, auto, fx::ExpressionMode::Auto)->Name("fuzzylite/auto");

// Console output plus a record of items/s per benchmark, for the ratio table.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, double> rate;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& r : runs) {
      auto it = r.counters.find("items_per_second");
      if (it != r.counters.end()) rate[r.benchmark_name()] = it->second;
    }
    ConsoleReporter::ReportRuns(runs);
  }
};

int write_csv(const char* path, long rows) {
  emoface::core::Rng rng(7);
  std::string out = "id,sadness,happiness,anger,fear,disgust,surprise\n";
  char buf[160];
  for (long r = 0; r < rows; ++r) {
    double e[6];
    for (double& x : e) x = rng.uniform() < 0.5 ? 0.0 : rng.uniform();
    std::snprintf(buf, sizeof buf, "%ld,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", r, e[0], e[1], e[2], e[3], e[4], e[5]);
    out += buf;
  }
  emoface::core::write_file_atomic(path, out);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 4 && std::strcmp(argv[1], "--write-csv") == 0) return write_csv(argv[2], std::atol(argv[3]));
  benchmark::Initialize(&argc, argv);
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\n%-8s %16s %16s %10s\n", "mode", "emoface ESV/s", "fuzzylite ESV/s", "ratio");
  for (const char* mode : {"single", "blend", "auto"}) {
    const double a = reporter.rate["emoface/" + std::string(mode)];
    const double b = reporter.rate["fuzzylite/" + std::string(mode)];
    if (a > 0 && b > 0) std::printf("%-8s %16.0f %16.0f %9.0fx\n", mode, a, b, a / b);
  }
  benchmark::Shutdown();
  return 0;
}
