// faceweights: the per-frame costs an engine pays. Baselines in the same run: the forward map
// (params → 52 ARKit weights) for the inverse fit, and a plain copy of the weights for the packet
// encoders. Run: build/tests/bench/faceweights_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <cmath>

#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/stream.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/muscles/parameters.hpp"

namespace fw = emoface::faceweights;
namespace {

const fw::Mapper& mapper() {
  static const fw::Mapper m(fw::builtin_weight_set("arkit"), emoface::muscles::parameter_names());
  return m;
}

// The six emotions at 0.9 as parameter vectors, then as ARKit weights.
const std::vector<std::vector<double>>& emotion_params() {
  static const auto p = [] {
    const emoface::fuzzyexpr::Engine engine;
    std::vector<std::vector<double>> out;
    for (std::size_t e = 0; e < emoface::fuzzyexpr::kEmotionCount; ++e) {
      const auto s = emoface::fuzzyexpr::expand_to_sides(engine.single(emoface::fuzzyexpr::emotion_at(e), 0.9));
      std::vector<double> v(emoface::muscles::kParameterCount, 0.0);
      for (std::size_t i = 0; i < s.size(); ++i) v[i] = s[i];
      out.push_back(v);
    }
    return out;
  }();
  return p;
}

void BM_ForwardBaseline(benchmark::State& state) {
  std::vector<double> w(52);
  std::size_t i = 0;
  for (auto _ : state) {
    mapper().forward(emotion_params()[i++ % 6].data(), w.data());
    benchmark::DoNotOptimize(w.data());
  }
}
BENCHMARK(BM_ForwardBaseline);

void BM_FromArkitCold(benchmark::State& state) {
  std::vector<std::vector<double>> w;
  for (const auto& p : emotion_params()) w.push_back(mapper().forward(p));
  std::size_t i = 0;
  int iterations = 0;
  for (auto _ : state) {
    std::vector<double> p;  // cold: zero start
    iterations += mapper().inverse(w[i++ % 6], p).sweeps;
    benchmark::DoNotOptimize(p.data());
  }
  state.counters["iterations/frame"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_FromArkitCold);

// A 60 fps track blending smoothly between emotions: warm start from the previous frame.
void BM_FromArkitWarmTrack(benchmark::State& state) {
  std::vector<std::vector<double>> w;
  for (int f = 0; f < 600; ++f) {
    const double t = f / 100.0;
    const auto& a = emotion_params()[static_cast<std::size_t>(t) % 6];
    const auto& b = emotion_params()[(static_cast<std::size_t>(t) + 1) % 6];
    const double s = t - std::floor(t);
    std::vector<double> p(a.size());
    for (std::size_t k = 0; k < p.size(); ++k) p[k] = (1 - s) * a[k] + s * b[k];
    w.push_back(mapper().forward(p));
  }
  std::vector<double> p;
  std::size_t i = 0;
  int iterations = 0;
  for (auto _ : state) {
    iterations += mapper().inverse(w[i++ % w.size()], p).sweeps;
    benchmark::DoNotOptimize(p.data());
  }
  state.counters["iterations/frame"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_FromArkitWarmTrack);

fw::StreamFrame frame() {
  fw::StreamFrame f;
  f.weights = mapper().forward(emotion_params()[1]);
  f.angles["head_yaw"] = 0.1;
  return f;
}

void BM_CopyBaseline(benchmark::State& state) {
  const auto f = frame();
  for (auto _ : state) {
    std::vector<double> copy = f.weights;
    benchmark::DoNotOptimize(copy.data());
  }
}
BENCHMARK(BM_CopyBaseline);

void BM_VmcPacket(benchmark::State& state) {
  const auto f = frame();
  for (auto _ : state) benchmark::DoNotOptimize(fw::vmc_blend_packet(f));
}
BENCHMARK(BM_VmcPacket);

void BM_LiveLinkPacket(benchmark::State& state) {
  const auto f = frame();
  for (auto _ : state) benchmark::DoNotOptimize(fw::live_link_face_packet(f, "emoface", "emoface", 1, 0.0f, 60));
}
BENCHMARK(BM_LiveLinkPacket);

}  // namespace

BENCHMARK_MAIN();
