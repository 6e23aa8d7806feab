// Landmark → muscle fit per frame on the default face (issue #8 target: < 2 ms per frame), and
// weight-space synthesis (issue 19: < 1 ms per transition).
//   build-bench/tests/bench/bridge_bench --benchmark_min_time=1
#include <cmath>

#include <benchmark/benchmark.h>

#include "emoface/bridge/landmark_fit.hpp"
#include "emoface/bridge/weight_space.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/muscles/parameters.hpp"

namespace {

void BM_BridgeFitFrame(benchmark::State& state) {
  auto face = emoface::facemesh::make_generic_face();
  const emoface::muscles::FaceSolver solver(std::move(face.mesh), std::move(face.rig));
  const emoface::bridge::LandmarkFitter fitter(solver);
  std::vector<double> truth(emoface::muscles::kSideParameterCount, 0.0);
  truth[emoface::muscles::parameter_index("zygomatic_major_l")] = 0.6;
  truth[emoface::muscles::parameter_index("zygomatic_major_r")] = 0.6;
  truth[emoface::muscles::parameter_index("masseter")] = 0.3;
  const Eigen::MatrixXd target = fitter.model_displacements(truth);
  for (auto _ : state) {
    std::vector<double> side(truth.size(), 0.0);  // cold start: the worst case
    benchmark::DoNotOptimize(fitter.fit(target, side));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_BridgeFitFrame)->Unit(benchmark::kMillisecond);

// A track: 60 frames ramping three muscles up and down, each frame warm-started from the previous fit
// (how mindmap simulate --muscles runs). One item = one frame.
void BM_BridgeFitTrack(benchmark::State& state) {
  auto face = emoface::facemesh::make_generic_face();
  const emoface::muscles::FaceSolver solver(std::move(face.mesh), std::move(face.rig));
  const emoface::bridge::LandmarkFitter fitter(solver);
  std::vector<Eigen::MatrixXd> targets;
  for (int k = 0; k < 60; ++k) {
    const double a = 0.5 * (1.0 - std::cos(k * 2.0 * 3.141592653589793 / 60.0));
    std::vector<double> v(emoface::muscles::kSideParameterCount, 0.0);
    v[emoface::muscles::parameter_index("zygomatic_major_l")] = 0.7 * a;
    v[emoface::muscles::parameter_index("zygomatic_major_r")] = 0.7 * a;
    v[emoface::muscles::parameter_index("masseter")] = 0.4 * a;
    targets.push_back(fitter.model_displacements(v));
  }
  for (auto _ : state) benchmark::DoNotOptimize(fitter.fit_track(targets));
  state.SetItemsProcessed(state.iterations() * 60);
}
BENCHMARK(BM_BridgeFitTrack)->Unit(benchmark::kMillisecond);

void BM_MuscleModelDeform(benchmark::State& state) {  // for comparison: one full-model evaluation
  auto face = emoface::facemesh::make_generic_face();
  const emoface::muscles::FaceSolver solver(std::move(face.mesh), std::move(face.rig));
  std::vector<double> v(emoface::muscles::kParameterCount, 0.0);
  v[0] = v[1] = 0.6;
  emoface::muscles::Deformation d;
  for (auto _ : state) solver.deform(v, d);
}
BENCHMARK(BM_MuscleModelDeform)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

// Issue 19 item 2: one synthesized transition in weight space (ARKit-52 graph of the face-driven
// weight database, 5 regions, §5 steps 1–4 with the sigmoid smoothing) against the baseline of the
// same run: one transition of the landmark graph of the face-driven landmark database (same
// sequences); then the weight frames → face parameters through the ARKit mapping (per transition).
//   build-bench/tests/bench/bridge_bench --benchmark_filter='Transition|WeightDrive'
namespace {
namespace mg = emoface::motiongraph;
namespace br = emoface::bridge;

const br::FaceLandmarkModel& face_model() {
  static const br::FaceLandmarkModel m;
  return m;
}
const mg::MotionGraph& weight_graph() {
  static const mg::MotionGraph g = mg::build_graph(
      mg::preprocess(br::generate_weight_database(face_model()), br::arkit_layout(),
                     mg::weight_preprocess_options()),
      mg::weight_graph_options());
  return g;
}
const mg::MotionGraph& landmark_graph() {
  static const mg::MotionGraph g = mg::build_graph(
      mg::preprocess(mg::generate_synthetic_database(face_model()), mg::default_layout()));
  return g;
}
const mg::Label kLabels[] = {mg::Label::Happiness, mg::Label::Fear, mg::Label::Surprise, mg::Label::Anger};

void BM_LandmarkTransitionBaseline(benchmark::State& state) {
  mg::SynthesisState s = mg::initial_state(landmark_graph());
  std::size_t i = 0, frames = 0;
  for (auto _ : state) frames += mg::synthesize(landmark_graph(), s, kLabels[i++ % 4]).size();
  state.counters["frames/transition"] = static_cast<double>(frames) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_LandmarkTransitionBaseline)->Unit(benchmark::kMicrosecond);

void BM_WeightTransition(benchmark::State& state) {
  const mg::SynthesisOptions o = mg::weight_synthesis_options();
  mg::SynthesisState s = mg::initial_state(weight_graph());
  std::size_t i = 0, frames = 0;
  for (auto _ : state) frames += mg::synthesize(weight_graph(), s, kLabels[i++ % 4], o).size();
  state.counters["frames/transition"] = static_cast<double>(frames) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_WeightTransition)->Unit(benchmark::kMicrosecond);

void BM_WeightDriveTransition(benchmark::State& state) {
  mg::SynthesisState s = mg::initial_state(weight_graph());
  const auto frames = mg::synthesize(weight_graph(), s, mg::Label::Surprise, mg::weight_synthesis_options());
  for (auto _ : state) benchmark::DoNotOptimize(br::weight_parameters(weight_graph(), frames));
  state.counters["frames"] = static_cast<double>(frames.size());
}
BENCHMARK(BM_WeightDriveTransition)->Unit(benchmark::kMicrosecond);
}  // namespace
