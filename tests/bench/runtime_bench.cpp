// runtime::Character per-frame cost (issue 16 targets: 1,000 characters at 60 Hz without
// deformation ≥ 60,000 character-updates/s per core; with deformation on the default face ≥
// 2,000/s), with baselines in the same run: the offline channels::mix per frame over the same kind
// of channels, and FaceSolver::deform alone. Issue 19 item 5: the mindmotion source (a live
// mind-map character moved by a motion graph) against the mindmap source (mood → fuzzy displays),
// same map, same stimuli, same run.
//   build/tests/bench/runtime_bench --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "emoface/bridge/face_landmark_model.hpp"
#include "emoface/bridge/weight_space.hpp"
#include "emoface/channels/mixer.hpp"
#include "emoface/channels/parameters.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/motiongraph/preprocess.hpp"
#include "emoface/motiongraph/synthetic.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/runtime/character.hpp"

namespace {

namespace rt = emoface::runtime;
namespace ch = emoface::channels;

const char* const kEvents[] = {R"({"emotions": {"happiness": 0.8}, "replace": true})",
                               R"({"emotions": {"surprise": 0.9}, "replace": true})",
                               R"({"emotions": {"anger": 0.6, "disgust": 0.3}, "replace": true})",
                               R"({"emotions": {"sadness": 0.7}, "replace": true})"};

// 1,000 characters (different seeds, events every 2 s at staggered times), 60 Hz updates.
void BM_RuntimeUpdate1000(benchmark::State& state) {
  std::vector<rt::Character> crowd;
  for (int i = 0; i < 1000; ++i) {
    rt::CharacterConfig c;
    c.options.seed = static_cast<std::uint64_t>(i + 1);
    crowd.emplace_back(c);
  }
  std::size_t frame = 0;
  const auto step = [&] {
    for (std::size_t i = 0; i < crowd.size(); ++i) {
      if ((frame + i) % 120 == 0) crowd[i].push_event(kEvents[(frame / 120 + i) % 4]);
      crowd[i].update(1.0 / 60);
    }
    ++frame;
  };
  for (int f = 0; f < 120; ++f) step();  // warm up: displays, blinks and noise running
  for (auto _ : state) {
    step();
    benchmark::DoNotOptimize(crowd.back().parameters().data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 1000);
  state.counters["latency_s"] = crowd[0].latency();
}
BENCHMARK(BM_RuntimeUpdate1000)->Unit(benchmark::kMillisecond);

// One character with the default face: update + deformed vertices every frame.
void BM_RuntimeUpdateDeform(benchmark::State& state) {
  rt::CharacterConfig c;
  c.face = "default";
  rt::Character ch(c);
  std::size_t frame = 0;
  for (auto _ : state) {
    if (frame % 120 == 0) ch.push_event(kEvents[(frame / 120) % 4]);
    ch.update(1.0 / 60);
    benchmark::DoNotOptimize(ch.vertices().data());
    ++frame;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_RuntimeUpdateDeform)->Unit(benchmark::kMicrosecond);

// Mind-map characters: rex of data/mindmap/crowd, a stimulus per character every 2 s (staggered),
// 60 Hz updates; `kind` = the mindmap source (mood → fuzzy displays) or the mindmotion source with
// a weight-space ARKit graph of the default generated size (`mgraph generate --space arkit` +
// `mgraph build`: 7 labels × 10 sequences, 20 subjects) or a 2D landmark graph (the parametric
// CK+-like model, fitted on the default face).
const char* const kStimuli[] = {R"({"stimulus": "gift"})", R"({"stimulus": "insult"})",
                                R"({"stimulus": "bang"})", R"({"stimulus": "joke"})"};

std::shared_ptr<const emoface::motiongraph::MotionGraph> bench_graph(bool weights) {
  namespace mg = emoface::motiongraph;
  if (weights) {
    static const auto g = [] {
      const emoface::bridge::FaceLandmarkModel face;
      return std::make_shared<const mg::MotionGraph>(mg::build_graph(
          mg::preprocess(emoface::bridge::generate_weight_database(face, {}),
                         emoface::bridge::arkit_layout(), mg::weight_preprocess_options()),
          mg::weight_graph_options()));
    }();
    return g;
  }
  static const auto g = [] {
    return std::make_shared<const mg::MotionGraph>(mg::build_graph(mg::preprocess(
        mg::generate_synthetic_database(mg::ParametricLandmarkModel(), {}), mg::default_layout())));
  }();
  return g;
}

void mind_crowd(benchmark::State& state, rt::SourceKind kind, bool weights) {
  const int n = static_cast<int>(state.range(0));
  const auto map = emoface::mindmap::read_mind_map(std::string(EMOFACE_SOURCE_DIR) +
                                                   "/data/mindmap/crowd/rex.json");
  std::vector<rt::Character> crowd;
  for (int i = 0; i < n; ++i) {
    rt::CharacterConfig c;
    c.source = kind;
    c.map = map;
    if (kind == rt::SourceKind::MindMotion) c.motion.graph = bench_graph(weights);
    c.options.seed = static_cast<std::uint64_t>(i + 1);
    crowd.emplace_back(c);
  }
  std::size_t frame = 0;
  const auto step = [&] {
    for (std::size_t i = 0; i < crowd.size(); ++i) {
      if ((frame + i) % 120 == 0) crowd[i].push_event(kStimuli[(frame / 120 + i) % 4]);
      crowd[i].update(1.0 / 60);
    }
    ++frame;
  };
  for (int f = 0; f < 120; ++f) step();  // warm up: actions, blinks and noise running
  for (auto _ : state) {
    step();
    benchmark::DoNotOptimize(crowd.back().parameters().data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * n);
}
void BM_RuntimeMindMap(benchmark::State& state) {
  mind_crowd(state, rt::SourceKind::MindMap, false);
}
void BM_RuntimeMindMotionWeights(benchmark::State& state) {
  mind_crowd(state, rt::SourceKind::MindMotion, true);
}
void BM_RuntimeMindMotionLandmarks(benchmark::State& state) {
  mind_crowd(state, rt::SourceKind::MindMotion, false);
}
BENCHMARK(BM_RuntimeMindMap)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RuntimeMindMotionWeights)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RuntimeMindMotionLandmarks)->Arg(10)->Unit(benchmark::kMillisecond);

// Baseline: the offline mixer over 10 s at 60 fps with the channels a character has (blinks, a
// smile display, lip visemes, gaze, head), per frame.
void BM_Baseline_OfflineMixPerFrame(benchmark::State& state) {
  const double fps = 60;
  const std::size_t frames = 600;
  const auto& params = ch::default_parameter_names();
  std::vector<ch::ChannelSamples> s;
  const auto add = [&](ch::Channel c, std::vector<std::string> names, double value) {
    ch::ChannelSamples x{c, names, std::vector<double>(names.size() * frames)};
    for (std::size_t f = 0; f < frames; ++f)
      for (std::size_t p = 0; p < names.size(); ++p)
        x.values[p * frames + f] = (f / 30) % 3 == 0 ? value : 0.0;
    s.push_back(x);
  };
  add(ch::Channel::Manipulator, {"eye_blink_l", "eye_blink_r"}, 1.0);
  add(ch::Channel::Lip, {"orbicularis_oris_funneler", "orbicularis_oris_pressor", "masseter"}, 0.6);
  std::vector<std::string> sides(params.begin(), params.begin() + 35);
  add(ch::Channel::EmotionDisplay, sides, 0.5);
  add(ch::Channel::Gaze, {"eye_gaze_yaw", "eye_gaze_pitch"}, 0.02);
  add(ch::Channel::Head, {"head_yaw", "head_pitch", "head_roll"}, 0.02);
  const ch::ConflictTable conflicts = ch::default_conflict_table();
  for (auto _ : state) {
    const ch::Tracks t = ch::mix(s, params, fps, frames, conflicts, {});
    benchmark::DoNotOptimize(t.values.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * frames));
}
BENCHMARK(BM_Baseline_OfflineMixPerFrame)->Unit(benchmark::kMillisecond);

// Baseline: FaceSolver::deform alone on a smile (the floor of BM_RuntimeUpdateDeform).
void BM_Baseline_Deform(benchmark::State& state) {
  emoface::facemesh::Face face = emoface::facemesh::make_generic_face();
  const emoface::muscles::FaceSolver solver(face.mesh, face.rig);
  std::vector<double> v(emoface::muscles::kParameterCount, 0.0);
  v[0] = v[1] = 0.6;
  v[2] = v[3] = 0.3;
  emoface::muscles::Deformation d;
  emoface::muscles::DeformWorkspace ws;
  for (auto _ : state) {
    solver.deform(v, d, ws);
    benchmark::DoNotOptimize(d.vertices.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_Baseline_Deform)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
