// Mind-map mood dynamics for crowds (paper §6): mood update (eqs. 2–4) and decay for 10,000
// characters per frame. Target (issue #8): ≥ 1e7 character-updates per second per core.
//   build-bench/tests/bench/mindmap_bench --benchmark_min_time=1s
#include <vector>

#include <benchmark/benchmark.h>

#include "emoface/core/rng.hpp"
#include "emoface/mindmap/mood.hpp"
#include "emoface/mindmap/simulation.hpp"

namespace mm = emoface::mindmap;

namespace {

constexpr std::size_t kCharacters = 10000;
constexpr std::size_t kEmotions = 6;

std::vector<double> random_values(std::size_t n, std::uint64_t seed) {
  emoface::core::Rng rng(seed);
  std::vector<double> v(n);
  for (double& x : v) x = rng.uniform();
  return v;
}

// Kernel: per character and frame, one stimulus (eq. 2 with affection, eq. 4 with precomputed
// PTraits of eq. 3) and the decayed mood at the frame's time. Flat arrays, 6 emotion nodes.
void BM_MoodUpdateAndDecay(benchmark::State& state) {
  const auto curve = static_cast<mm::DecayCurve>(state.range(0));
  const std::size_t n = kCharacters * kEmotions;
  std::vector<double> mood = random_values(n, 1), start = mood, emot = random_values(n, 2),
                      affect = random_values(n, 3), ptraits = random_values(n, 4),
                      personality = random_values(n, 5), stimulus(kEmotions), out(n);
  double t = 0.0;
  for (auto _ : state) {
    t += 0.04;
    const double elapsed = t - static_cast<double>(static_cast<long>(t / 5.0)) * 5.0;
    for (std::size_t c = 0; c < kCharacters; ++c) {
      const std::size_t o = c * kEmotions;
      mm::perceived_stimulus(&emot[o], &affect[o], 0.3, stimulus.data(), kEmotions);
      mm::update_mood(&mood[o], stimulus.data(), &ptraits[o], 0.6, 0.5, mm::MoodForm::Sum, kEmotions);
      mm::decayed_mood(&start[o], &personality[o], elapsed, 5.0, curve, 10.0, &out[o], kEmotions);
    }
    benchmark::DoNotOptimize(mood.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kCharacters));
  state.SetLabel("character-updates (update + decay)");
}
BENCHMARK(BM_MoodUpdateAndDecay)->Arg(0)->Arg(1)->Arg(2)->ArgNames({"curve"});

mm::MindMap crowd_member(std::size_t i) {
  mm::MindMap m;
  m.character = "c" + std::to_string(i);
  m.emotions = {"happiness", "sadness", "anger", "surprise", "fear", "bored"};
  m.actions = {{"poke", true, false, ""}, {"smile", false, true, "happiness"}};
  m.stimulus_edges = {{0, 0, 0.7}, {0, 2, 0.4}};
  m.response_edges = {{0, 1, 0.5}};
  m.traits.starting_mood = {0.5, 0.1, 0.1, 0.1, 0.1, 0.2};
  m.traits.personality = {0.4, 0.1, 0.1, 0.1, 0.1, 0.2};
  m.traits.decay_duration = 1e6;  // always decaying
  m.traits.decay_curve = mm::DecayCurve::Sigmoid;
  return m;
}

// The World: decay of 10,000 characters per advance_to (one frame at 25 fps).
void BM_WorldAdvance(benchmark::State& state) {
  std::vector<mm::MindMap> maps;
  for (std::size_t i = 0; i < kCharacters; ++i) maps.push_back(crowd_member(i));
  mm::SimulationOptions o;
  o.decay_interval = 1e9;  // no hints: pure mood dynamics
  mm::World world(std::move(maps), o);
  double t = 0.0;
  for (auto _ : state) {
    t += 0.04;
    world.advance_to(t, nullptr);
    benchmark::DoNotOptimize(world.mood(0).data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kCharacters));
}
BENCHMARK(BM_WorldAdvance);

// The World: one stimulus to every character per frame (eqs. 2–4, action choice) plus decay.
void BM_WorldStimulusEveryFrame(benchmark::State& state) {
  std::vector<mm::MindMap> maps;
  for (std::size_t i = 0; i < kCharacters; ++i) maps.push_back(crowd_member(i));
  mm::World world(std::move(maps));
  std::vector<mm::TriggeredAction> actions;
  mm::Event e;
  e.target = "*";
  e.stimulus = "poke";
  for (auto _ : state) {
    e.time += 0.04;
    actions.clear();
    world.apply(e, &actions);
    benchmark::DoNotOptimize(actions.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kCharacters));
}
BENCHMARK(BM_WorldStimulusEveryFrame);

}  // namespace

BENCHMARK_MAIN();
