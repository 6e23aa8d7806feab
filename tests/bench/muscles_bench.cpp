// Issue 15 (eyes and jaw as glTF nodes, the ARKit blendshape character): split_rigid_parts on the
// default face's baked rig (41 + 52 targets) against copying the baked rig (its baseline: the split
// works on a copy in write_rig_gltf), and blend_targets (52 ARKit weights) against the dense loop.
// Muscle deformation vs a dense 35-blendshape baseline, on the default face and on a ~20k-vertex
// midpoint-subdivided copy (thesis §2.4.1 performance; issue #3 §4). Issue #13: a rig whose lips
// are driven through LipBinding (samples_in_mesh = false, every lip vertex bound, as a transferred
// rig) on the ~20k and ~80k subdivisions vs a dense 52-target blendshape evaluation on the same
// meshes.
//   cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DEMOFACE_BUILD_BENCH=ON
//   cmake --build build-bench --target muscles_bench -j2
//   build-bench/tests/bench/muscles_bench --benchmark_min_time=1s
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "emoface/facemesh/bspline.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/muscles/morph_targets.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/solver.hpp"

namespace {

namespace fm = emoface::facemesh;
namespace mu = emoface::muscles;

// Subdivides the face once and extends the rig: new vertices inherit region/material of their first
// parent, jaw/lid weights are averaged when both parents are listed. The lip B-spline still drives
// only the original lip samples (the benchmark measures cost, not looks).
fm::Face subdivided(const fm::Face& f, std::vector<std::pair<int, int>>* parents_out = nullptr) {
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
  if (parents_out) *parents_out = parents;
  return out;
}

// Subdivided `levels` times with every lip vertex (the samples and midpoints between two of them) bound
// to the lip surface through LipBinding at its own (u, v): a transferred rig's lips.
fm::Face bound_lips(int levels) {
  fm::Face f = fm::make_generic_face();
  const auto& lips = f.rig.lips;
  std::vector<Eigen::Vector2d> uv(f.mesh.vertex_count(), Eigen::Vector2d(-1.0, -1.0));
  for (int j = 0; j < lips.samples_across; ++j) {
    for (int i = 0; i < lips.samples_around; ++i) {
      uv[static_cast<std::size_t>(lips.first_vertex + j * lips.samples_around + i)] =
          Eigen::Vector2d(static_cast<double>(i) / lips.samples_around, static_cast<double>(j) / (lips.samples_across - 1));
    }
  }
  for (int l = 0; l < levels; ++l) {
    std::vector<std::pair<int, int>> parents;
    fm::Face next = subdivided(f, &parents);
    for (const auto& [a, b] : parents) {
      Eigen::Vector2d ua = uv[static_cast<std::size_t>(a)], ub = uv[static_cast<std::size_t>(b)];
      if (ua.x() < 0.0 || ub.x() < 0.0) {
        uv.emplace_back(-1.0, -1.0);
        continue;
      }
      if (std::abs(ua.x() - ub.x()) > 0.5) (ua.x() < ub.x() ? ua : ub).x() += 1.0;  // across u = 0
      Eigen::Vector2d m = 0.5 * (ua + ub);
      if (m.x() >= 1.0) m.x() -= 1.0;
      uv.push_back(m);
    }
    f = std::move(next);
  }
  f.rig.lips.samples_in_mesh = false;
  for (std::size_t v = 0; v < uv.size(); ++v) {
    if (uv[v].x() < 0.0) continue;
    fm::LipBinding b;
    b.vertex = static_cast<int>(v);
    b.u = uv[v].x();
    b.v = uv[v].y();
    b.offset = f.mesh.vertices.row(static_cast<long>(v)).transpose() - [&] {
      Eigen::Vector3d s = Eigen::Vector3d::Zero();
      for (const auto& t : fm::lip_surface_terms(b.u, b.v)) s += t.weight * f.rig.lips.control_points[static_cast<std::size_t>(t.control)];
      return s;
    }();
    f.rig.lips.bound.push_back(b);
  }
  return f;
}

const fm::Face& bound_face(int levels) {
  static const fm::Face one = bound_lips(1);
  static const fm::Face two = bound_lips(2);
  return levels == 1 ? one : two;
}

// 0: the generic face, 1: it subdivided, 2: the default face (the rigged MakeHuman head, issue 14)
const fm::Face& face(long which) {
  static const fm::Face small = fm::make_generic_face();
  static const fm::Face large = subdivided(small);
  static const fm::Face human = fm::make_default_face();
  return which == 2 ? human : which == 1 ? large : small;
}

std::vector<double> all_muscles() {
  std::vector<double> v(mu::kParameterCount, 0.0);
  for (std::size_t i = 0; i < mu::kSideParameterCount; ++i) v[i] = 1.0;  // every muscle at full contraction
  return v;
}

void BM_MuscleDeformation(benchmark::State& state) {
  const auto& f = face(state.range(0));
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
  const auto& f = face(state.range(0));
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

// Issue #13: a transferred-style rig (lips through bindings) vs 52 dense blendshape targets, same mesh.
void BM_BoundLipsDeformation(benchmark::State& state) {
  const auto& f = bound_face(static_cast<int>(state.range(0)));
  const mu::FaceSolver solver(f.mesh, f.rig);
  const auto values = all_muscles();
  mu::Deformation out;
  mu::DeformWorkspace workspace;
  for (auto _ : state) {
    solver.deform(values, out, workspace);
    benchmark::DoNotOptimize(out.vertices.data());
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["vertices"] = static_cast<double>(f.mesh.vertex_count());
  state.counters["bound"] = static_cast<double>(f.rig.lips.bound.size());
}

void BM_Blendshape52(benchmark::State& state) {
  const auto& f = bound_face(static_cast<int>(state.range(0)));
  // 52 dense targets (ARKit-sized): the 35 single-muscle deltas, then 17 of them again scaled, so
  // every target is a full #V×3 array as in a blendshape rig
  const mu::FaceSolver solver(f.mesh, f.rig);
  const long n = f.mesh.vertices.rows() * 3;
  std::vector<Eigen::VectorXd> deltas;
  for (std::size_t i = 0; i < 52; ++i) {
    std::vector<double> v(mu::kParameterCount, 0.0);
    v[i % mu::kSideParameterCount] = i < mu::kSideParameterCount ? 1.0 : 0.5;
    const auto d = solver.deform(v);
    deltas.push_back(Eigen::Map<const Eigen::VectorXd>(d.vertices.data(), n) -
                     Eigen::Map<const Eigen::VectorXd>(f.mesh.vertices.data(), n));
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
  state.SetItemsProcessed(state.iterations());
  state.counters["vertices"] = static_cast<double>(f.mesh.vertex_count());
}

const mu::BakedRig& arkit_rig() {
  static const mu::BakedRig rig = [] {
    const auto face = fm::make_default_face();
    const mu::FaceSolver solver(face.mesh, face.rig);
    const emoface::faceweights::Mapper arkit(emoface::faceweights::builtin_weight_set("arkit"),
                                             mu::parameter_names());
    return mu::bake_rig(solver, face.mesh.faces, {&arkit});
  }();
  return rig;
}

void BM_SplitRigidParts(benchmark::State& state) {
  const auto face = fm::make_default_face();
  const auto colors = fm::material_colors(face.rig, face.mesh);
  for (auto _ : state) {
    mu::BakedRig rig = arkit_rig();
    auto c = colors;
    mu::split_rigid_parts(rig, face.rig, c);
    benchmark::DoNotOptimize(rig.neutral.vertices.data());
  }
  state.counters["parts"] = 3;
}

void BM_SplitBaselineCopy(benchmark::State& state) {
  const auto face = fm::make_default_face();
  const auto colors = fm::material_colors(face.rig, face.mesh);
  for (auto _ : state) {
    mu::BakedRig rig = arkit_rig();
    auto c = colors;
    benchmark::DoNotOptimize(rig.neutral.vertices.data());
    benchmark::DoNotOptimize(c.data());
  }
}

void BM_BlendTargetsArkit(benchmark::State& state) {
  const auto& rig = arkit_rig();
  std::vector<double> set(52);
  for (std::size_t i = 0; i < set.size(); ++i) set[i] = 0.5 + 0.01 * static_cast<double>(i);
  const auto w = mu::set_target_weights(rig, set);
  for (auto _ : state) {
    auto x = mu::blend_targets(rig, w);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["vertices"] = static_cast<double>(rig.neutral.vertices.rows());
}

BENCHMARK(BM_SplitRigidParts)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SplitBaselineCopy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BlendTargetsArkit)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MuscleDeformation)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BoundLipsDeformation)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Blendshape52)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BlendshapeBaseline)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
