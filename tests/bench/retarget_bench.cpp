// Retargeting costs (thesis §3.5 error function, one GA evaluation = RBF fit + deform + error, one GA
// generation, a whole fit) on the default face fitted to a warped, midpoint-subdivided copy (~20k vertices).
//   cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DEMOFACE_BUILD_BENCH=ON
//   cmake --build build-bench --target retarget_bench -j2
//   build-bench/tests/bench/retarget_bench --benchmark_min_time=1s
#include <Eigen/Geometry>
#include <benchmark/benchmark.h>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/retarget/retarget.hpp"
#include "emoface/retarget/surface.hpp"
#include "emoface/retarget/validation.hpp"

namespace {
namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;

const fm::Face& face() {
  static const fm::Face f = fm::make_default_face();
  return f;
}

const fm::Mesh& target() {
  static const fm::Mesh t = [] {
    rt::SyntheticWarp w;
    w.width = 1.08;
    w.nose = 0.005;
    fm::Mesh m = face().mesh;
    m.vertices = w.apply(m.vertices);
    return fm::subdivide_midpoint(m);
  }();
  return t;
}

Eigen::MatrixX3d landmarks(const fm::Face& f, const fm::Mesh& m) {
  Eigen::MatrixX3d l(static_cast<Eigen::Index>(f.rig.retarget_landmarks.size()), 3);
  for (std::size_t i = 0; i < f.rig.retarget_landmarks.size(); ++i)
    l.row(static_cast<Eigen::Index>(i)) = m.vertices.row(f.rig.retarget_landmarks[i].vertex);
  return l;
}

void BM_ErrorFunction(benchmark::State& state) {
  rt::ErrorOptions o;
  o.bottom_y = rt::landmark_position(face(), "chin").y();
  const rt::ErrorFunction error(target(), rt::top_vertex(target().vertices), face().mesh.faces, face().mesh.vertex_count(), o);
  const int top = face().rig.retarget_landmarks[0].vertex;
  for (auto _ : state) benchmark::DoNotOptimize(error.evaluate(face().mesh.vertices, top));
  state.counters["evaluations/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ErrorFunction)->Unit(benchmark::kMicrosecond);

void BM_RbfFitAndDeform(benchmark::State& state) {
  const Eigen::MatrixX3d src = landmarks(face(), face().mesh);
  const Eigen::MatrixX3d dst = src * 1.05;
  fm::Vertices out;
  for (auto _ : state) {
    const auto net = rt::fit_rbf(src, dst);
    net.evaluate(face().mesh.vertices, out);
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_RbfFitAndDeform)->Unit(benchmark::kMicrosecond);

// Automatic alignment (symmetry plane + matching the source) of the 20k-vertex target, randomly rotated.
void BM_Align(benchmark::State& state) {
  fm::Mesh rotated = target();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.4, -0.8, 0.45).normalized()).toRotationMatrix();
  rotated.vertices = (target().vertices * r.transpose()).eval();
  const Eigen::Vector3d top = rt::landmark_position(face(), "top_of_head"), nose = rt::landmark_position(face(), "nose_tip");
  for (auto _ : state) benchmark::DoNotOptimize(rt::align_to_frame(rotated, face().mesh, top, nose).scale);
}
BENCHMARK(BM_Align)->Unit(benchmark::kMillisecond);

// One GA generation = what a fit with G generations costs beyond a fit with G − 1: measured here as a
// whole fit with 1 generation (setup + initial population + 1 generation) and with 40 (the default).
void BM_Fit(benchmark::State& state) {
  rt::RetargetOptions o;
  o.ga.generations = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(rt::retarget_face(face(), target(), o).ga.best_error);
  state.counters["target_vertices"] = static_cast<double>(target().vertex_count());
}
BENCHMARK(BM_Fit)->Arg(1)->Arg(40)->Unit(benchmark::kMillisecond)->Iterations(1);
}  // namespace

BENCHMARK_MAIN();
