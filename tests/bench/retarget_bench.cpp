// Retargeting costs (thesis §3.5 error function, one GA evaluation = RBF fit + deform + error, one GA
// generation, a whole fit) on the default face fitted to a warped, midpoint-subdivided copy (~20k vertices).
//   cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DEMOFACE_BUILD_BENCH=ON
//   cmake --build build-bench --target retarget_bench -j2
//   build-bench/tests/bench/retarget_bench --benchmark_min_time=1s
#include <Eigen/Geometry>
#include <benchmark/benchmark.h>

#include "emoface/facemesh/default_face.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/retarget/retarget.hpp"
#include "emoface/retarget/transfer.hpp"
#include "emoface/retarget/surface.hpp"
#include "emoface/retarget/validation.hpp"

namespace {
namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;

const fm::Face& face() {
  static const fm::Face f = fm::make_generic_face();
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

// The optional local refinement after the GA (Levenberg–Marquardt with a central-difference
// Jacobian, ceres::TinySolver; before: ceres::Solve with DENSE_QR): a 1-generation fit with refine
// on; the counters give the refinement's own time, iterations and error decrease (compare with
// BM_Fit/1).
void BM_FitRefine(benchmark::State& state) {
  rt::RetargetOptions o;
  o.ga.generations = 1;
  o.refine.enabled = true;
  o.refine.max_iterations = static_cast<int>(state.range(0));
  rt::RefineReport last;
  for (auto _ : state) last = rt::retarget_face(face(), target(), o).refine;
  state.counters["refine_s"] = last.seconds;
  state.counters["refine_iterations"] = last.iterations;
  state.counters["E_before"] = last.initial_error;
  state.counters["E_after"] = last.final_error;
}
BENCHMARK(BM_FitRefine)->Arg(15)->Unit(benchmark::kMillisecond)->Iterations(1);

// Issue 13: transfer onto a ~30k-vertex head (the warped built-in face subdivided twice and decimated,
// so its triangulation is its own) with the default options (40 GA generations), and deformation of the
// transferred rig vs a dense 52-target blendshape evaluation on the same mesh, same run.
const fm::Mesh& head30k() {
  static const fm::Mesh t = [] {
    rt::SyntheticWarp w;
    w.width = 1.05;
    w.chin = 0.004;
    w.scale = 10.0;  // decimetres
    fm::Mesh m = face().mesh;
    m.vertices = w.apply(m.vertices);
    return rt::decimate(fm::subdivide_midpoint(fm::subdivide_midpoint(m)), 0.375);
  }();
  return t;
}
const rt::TransferResult& transferred() {
  static const rt::TransferResult r = rt::transfer_rig(face(), head30k());
  return r;
}
void BM_Transfer30k(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(rt::transfer_rig(face(), head30k()).report.registration.final_rms);
  const auto& r = transferred();
  state.counters["vertices"] = static_cast<double>(head30k().vertex_count());
  state.counters["fit_s"] = r.report.fit_seconds;
  state.counters["registration_s"] = r.report.registration_seconds;
  state.counters["transfer_s"] = r.report.transfer_seconds;
}
BENCHMARK(BM_Transfer30k)->Unit(benchmark::kMillisecond)->Iterations(1);

std::vector<double> all_muscles() {
  std::vector<double> v(emoface::muscles::kParameterCount, 0.0);
  for (std::size_t i = 0; i < emoface::muscles::kSideParameterCount; ++i) v[i] = 0.6;
  return v;
}
void BM_TransferredRigDeformation30k(benchmark::State& state) {
  const auto& f = transferred().face;
  const emoface::muscles::FaceSolver solver(f.mesh, f.rig);
  const auto values = all_muscles();
  emoface::muscles::Deformation out;
  emoface::muscles::DeformWorkspace ws;
  for (auto _ : state) {
    solver.deform(values, out, ws);
    benchmark::DoNotOptimize(out.vertices.data());
  }
  state.counters["vertices"] = static_cast<double>(f.mesh.vertex_count());
  state.counters["lip_bound"] = static_cast<double>(f.rig.lips.bound.size());
}
BENCHMARK(BM_TransferredRigDeformation30k)->Unit(benchmark::kMicrosecond);

// Baseline: 52 dense targets (each a full #V×3 delta: the 35 single-muscle deformations of the same
// transferred rig, then 17 of them at half strength), weighted sum into the neutral mesh.
void BM_Blendshape52Same30k(benchmark::State& state) {
  const auto& f = transferred().face;
  const emoface::muscles::FaceSolver solver(f.mesh, f.rig);
  const long n = f.mesh.vertices.rows() * 3;
  std::vector<Eigen::VectorXd> deltas;
  for (std::size_t i = 0; i < 52; ++i) {
    std::vector<double> v(emoface::muscles::kParameterCount, 0.0);
    v[i % emoface::muscles::kSideParameterCount] = i < emoface::muscles::kSideParameterCount ? 1.0 : 0.5;
    const auto d = solver.deform(v);
    deltas.push_back(Eigen::Map<const Eigen::VectorXd>(d.vertices.data(), n) - Eigen::Map<const Eigen::VectorXd>(f.mesh.vertices.data(), n));
  }
  const Eigen::Map<const Eigen::VectorXd> neutral(f.mesh.vertices.data(), n);
  std::vector<double> weights(52);
  for (std::size_t i = 0; i < weights.size(); ++i) weights[i] = 0.5 + 0.01 * static_cast<double>(i);
  fm::Vertices out(f.mesh.vertices.rows(), 3);
  Eigen::Map<Eigen::VectorXd> x(out.data(), n);
  for (auto _ : state) {
    x = neutral;
    for (std::size_t i = 0; i < deltas.size(); ++i) x += weights[i] * deltas[i];
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["vertices"] = static_cast<double>(f.mesh.vertex_count());
}
BENCHMARK(BM_Blendshape52Same30k)->Unit(benchmark::kMicrosecond);
}  // namespace

BENCHMARK_MAIN();
