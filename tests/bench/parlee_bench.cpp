// parlee benchmarks (docs/parlee.md, "Performance"). Build in a Release dir with
//   cmake -S . -B build-bench -DEMOFACE_BUILD_BENCH=ON && cmake --build build-bench --target parlee_bench -j2
// and run  build-bench/tests/bench/parlee_bench --benchmark_min_time=2s
#include <benchmark/benchmark.h>

#include <vector>

#include "emoface/core/rng.hpp"
#include "emoface/parlee/agent.hpp"
#include "emoface/parlee/io.hpp"

using namespace emoface::parlee;

namespace {
const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/";
}

// The full 90-minute Obie match: 91 events, Obie's own turns, planning at depth 3 for both goals
// before/after every action, models of the other agent, appraisal, update. A fresh agent (empty
// planner memo) per iteration.
static void BM_ObieMatch(benchmark::State& state) {
  const Domain domain(read_domain_files({kData + "football.domain"}));
  const auto events = read_events_file(kData + "match.ndjson");
  AgentConfig config = read_agent_file(kData + "agents/neutral.json");
  config.planning.horizon = static_cast<int>(state.range(0));
  for (auto _ : state) {
    Agent agent(domain, config);
    for (const auto& e : events) benchmark::DoNotOptimize(agent.step(e));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<long>(events.size()));
}
BENCHMARK(BM_ObieMatch)->Arg(3)->Arg(5)->Unit(benchmark::kMillisecond);

// Rocket planning from scratch (exhaustive top-down DP with memoisation, Fig. 5.6).
static void BM_RocketPlan(benchmark::State& state) {
  const Domain domain(read_domain_files({kData + "rocket.domain"}));
  for (auto _ : state) {
    Planner planner(domain);
    benchmark::DoNotOptimize(planner.goal_probability(0, domain.initial_state(), static_cast<int>(state.range(0))));
  }
}
BENCHMARK(BM_RocketPlan)->Arg(5)->Arg(9)->Unit(benchmark::kMicrosecond);

namespace {
struct Crowd {
  EmotionParams params = EmotionParams::defaults();
  std::vector<EmotionVector> emotions, impulses, decay;
  EmotionVector alpha{};
  explicit Crowd(std::size_t n) : emotions(n), impulses(n), decay(n) {
    emoface::core::Rng rng(5, 0);
    alpha = motivated_alpha(params, MotivationalState{});
    for (std::size_t k = 0; k < n; ++k) {
      Personality p;
      for (auto& v : p.values) v = rng.uniform();
      decay[k] = decay_multipliers(params, p);
      for (std::size_t i = 0; i < kEmotionCount; ++i) {
        emotions[k][i] = rng.uniform(0.0, 0.5);
        impulses[k][i] = rng.uniform() < 0.3 ? rng.uniform(0.0, 0.5) : 0.0;
      }
    }
  }
};
}  // namespace

// Emotion update + decay (§5.6.3–5.6.4) for 10,000 agents per step, no planning.
static void BM_EmotionUpdate10k(benchmark::State& state) {
  Crowd crowd(10000);
  for (auto _ : state) {
    for (std::size_t k = 0; k < crowd.emotions.size(); ++k)
      update_emotions(crowd.emotions[k], crowd.impulses[k], crowd.params, crowd.alpha, crowd.decay[k]);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 10000);
}
BENCHMARK(BM_EmotionUpdate10k)->Unit(benchmark::kMicrosecond);

// Issue 17 item 3: the same update with ParleE's per-second decay over 30 s (half a thesis step):
// decayed() (exp/expm1 per emotion, slower at low intensity, r = 1/2) + update_decayed_emotions.
// Baseline: BM_EmotionUpdate10k above (per-step multiply) in the same run.
static void BM_DecayedUpdate10k(benchmark::State& state) {
  Crowd crowd(10000);
  for (auto _ : state) {
    for (std::size_t k = 0; k < crowd.emotions.size(); ++k) {
      const EmotionVector psi = decayed(crowd.emotions[k], crowd.params, crowd.decay[k], 30.0);
      update_decayed_emotions(crowd.emotions[k], psi, crowd.impulses[k], crowd.params, crowd.alpha);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 10000);
}
BENCHMARK(BM_DecayedUpdate10k)->Unit(benchmark::kMicrosecond);

// Appraisal (§5.6.2 with personality) + update for 10,000 agents, two goals each, no planning:
// comparable to an "appraisal" of GAMYGDALA.
static void BM_AppraiseAndUpdate10k(benchmark::State& state) {
  Crowd crowd(10000);
  std::vector<AppraisalInput> inputs(10000);
  std::vector<Personality> people(10000);
  emoface::core::Rng rng(6, 0);
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    for (auto& v : people[k].values) v = rng.uniform();
    GoalAppraisal a, b;
    a.p_before = rng.uniform();
    a.p_after = rng.uniform();
    b.p_before = rng.uniform();
    b.p_after = rng.uniform();
    b.importance = 0.5;
    inputs[k].goals = {a, b};
    inputs[k].p_event = rng.uniform();
    inputs[k].actor = Actor::Other;
  }
  for (auto _ : state) {
    for (std::size_t k = 0; k < inputs.size(); ++k) {
      const AppraisalResult r = appraise(inputs[k], people[k]);
      update_emotions(crowd.emotions[k], r.impulse, crowd.params, crowd.alpha, crowd.decay[k]);
    }
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * 10000);
}
BENCHMARK(BM_AppraiseAndUpdate10k)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
