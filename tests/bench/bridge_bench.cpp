// Landmark → muscle fit per frame on the default face (issue #8 target: < 2 ms per frame).
//   build-bench/tests/bench/bridge_bench --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "emoface/bridge/landmark_fit.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/muscles/parameters.hpp"

namespace {

void BM_BridgeFitFrame(benchmark::State& state) {
  auto face = emoface::facemesh::make_default_face();
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

void BM_MuscleModelDeform(benchmark::State& state) {  // for comparison: one full-model evaluation
  auto face = emoface::facemesh::make_default_face();
  const emoface::muscles::FaceSolver solver(std::move(face.mesh), std::move(face.rig));
  std::vector<double> v(emoface::muscles::kParameterCount, 0.0);
  v[0] = v[1] = 0.6;
  emoface::muscles::Deformation d;
  for (auto _ : state) solver.deform(v, d);
}
BENCHMARK(BM_MuscleModelDeform)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
