// Landmark → muscle fit per frame on the default face (issue #8 target: < 2 ms per frame).
//   build-bench/tests/bench/bridge_bench --benchmark_min_time=1
#include <cmath>

#include <benchmark/benchmark.h>

#include "emoface/bridge/landmark_fit.hpp"
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
