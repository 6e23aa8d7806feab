// Muscle deformation vs a dense 35-blendshape baseline, on the default face and on a ~20k-vertex
// midpoint-subdivided copy (thesis §2.4.1 performance; issue #3 §4).
//   cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DEMOFACE_BUILD_BENCH=ON
//   cmake --build build-bench --target muscles_bench -j2
//   build-bench/tests/bench/muscles_bench --benchmark_min_time=1s
#include <benchmark/benchmark.h>

#include <vector>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/muscles/solver.hpp"

namespace {

namespace fm = emoface::facemesh;
namespace mu = emoface::muscles;

// Subdivides the face once and extends the rig: new vertices inherit region/material of their first
// parent, jaw/lid weights are averaged when both parents are listed. The lip B-spline still drives
// only the original lip samples (the benchmark measures cost, not looks).
fm::Face subdivided(const fm::Face& f) {
  std::vector<std::pair<int, int>> parents;
  fm::Face out;
  out.mesh = fm::subdivide_midpoint(f.mesh, &parents);
  out.rig = f.rig;
  const int n0 = static_cast<int>(f.mesh.vertex_count());
  out.rig.vertex_count = out.mesh.vertex_count();
  auto extend = [&](std::vector<int>& ids, std::vector<double>* weights) {
    std::vector<double> w0(static_cast<std::size_t>(n0), -1.0);
    for (std::size_t k = 0; k < ids.size(); ++k) w0[static_cast<std::size_t>(ids[k])] = weights ? (*weights)[k] : 1.0;
    for (std::size_t i = 0; i < parents.size(); ++i) {
      const double a = w0[static_cast<std::size_t>(parents[i].first)], b = w0[static_cast<std::size_t>(parents[i].second)];
      if (a >= 0.0 && b >= 0.0) {
        ids.push_back(n0 + static_cast<int>(i));
        if (weights) weights->push_back(0.5 * (a + b));
      }
    }
  };
  for (const auto& p : parents) {
    out.rig.regions.push_back(f.rig.regions[static_cast<std::size_t>(p.first)]);
    out.rig.materials.push_back(f.rig.materials[static_cast<std::size_t>(p.first)]);
  }
  extend(out.rig.jaw.vertices, &out.rig.jaw.weights);
  for (auto& eye : out.rig.eyes) {
    extend(eye.eyeball_vertices, nullptr);
    extend(eye.upper_lid, &eye.upper_lid_weights);
    extend(eye.lower_lid, &eye.lower_lid_weights);
  }
  return out;
}

const fm::Face& face(bool big) {
  static const fm::Face small = fm::make_default_face();
  static const fm::Face large = subdivided(small);
  return big ? large : small;
}

std::vector<double> all_muscles() {
  std::vector<double> v(mu::kParameterCount, 0.0);
  for (std::size_t i = 0; i < mu::kSideParameterCount; ++i) v[i] = 1.0;  // every muscle at full contraction
  return v;
}

void BM_MuscleDeformation(benchmark::State& state) {
  const auto& f = face(state.range(0) != 0);
  const mu::FaceSolver solver(f.mesh, f.rig);  // δc = 0.2 (5 steps at full contraction)
  const auto values = all_muscles();
  mu::Deformation out;
  mu::DeformWorkspace workspace;  // one per thread; no allocation after the first call
  for (auto _ : state) {
    solver.deform(values, out, workspace);
    benchmark::DoNotOptimize(out.vertices.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["vertices"] = static_cast<double>(f.mesh.vertex_count());
  state.counters["steps"] = out.steps;
}

void BM_BlendshapeBaseline(benchmark::State& state) {
  const auto& f = face(state.range(0) != 0);
  // 35 dense per-parameter deltas (each muscle alone at full contraction minus neutral)
  const mu::FaceSolver solver(f.mesh, f.rig);
  const long n = f.mesh.vertices.rows() * 3;
  std::vector<Eigen::VectorXd> deltas;
  for (std::size_t i = 0; i < mu::kSideParameterCount; ++i) {
    std::vector<double> v(mu::kParameterCount, 0.0);
    v[i] = 1.0;
    const auto d = solver.deform(v);
    deltas.push_back(Eigen::Map<const Eigen::VectorXd>(d.vertices.data(), n) -
                     Eigen::Map<const Eigen::VectorXd>(f.mesh.vertices.data(), n));
  }
  const Eigen::Map<const Eigen::VectorXd> neutral(f.mesh.vertices.data(), n);
  const auto weights = all_muscles();
  fm::Vertices out(f.mesh.vertices.rows(), 3);
  Eigen::Map<Eigen::VectorXd> x(out.data(), n);
  for (auto _ : state) {
    x = neutral;
    for (std::size_t i = 0; i < deltas.size(); ++i) x += weights[i] * deltas[i];
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["vertices"] = static_cast<double>(f.mesh.vertex_count());
}

BENCHMARK(BM_MuscleDeformation)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlendshapeBaseline)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
