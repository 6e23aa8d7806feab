#pragma once
// Shared by transfer_test.cpp and transfer_slow_test.cpp: options, a brute-force closest point, the
// comparison against the built-in deformation, and the fixtures made once per test program.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/bspline.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/retarget/io.hpp"
#include "emoface/retarget/registration.hpp"
#include "emoface/retarget/transfer.hpp"
#include "emoface/retarget/validation.hpp"
#include "test_shapes.hpp"

namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;
namespace ms = emoface::muscles;

namespace {

rt::TransferOptions quick_options() {
  rt::TransferOptions o;
  o.fit.ga.generations = 6;
  o.fit.ga.population = 12;
  return o;
}

// Closest point of p on the triangles of `m` (brute force: an independent check of the library's
// index).
struct Closest {
  int face = -1;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
};
Closest brute_closest(const fm::Mesh& m, const Eigen::Vector3d& p) {
  Closest best;
  double bd = 1e300;
  for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
    const Eigen::Vector3d a = m.vertices.row(m.faces(f, 0)), b = m.vertices.row(m.faces(f, 1)),
                          c = m.vertices.row(m.faces(f, 2));
    const Eigen::Vector3d q = rt::closest_point_on_triangle(p, a, b, c);
    const double d = (q - p).squaredNorm();
    if (d < bd) {
      bd = d;
      best.face = static_cast<int>(f);
      // barycentrics by areas
      const double area = (b - a).cross(c - a).norm();
      best.bary = Eigen::Vector3d((b - q).cross(c - q).norm(), (c - q).cross(a - q).norm(),
                                  (a - q).cross(b - q).norm()) /
                  area;
    }
  }
  return best;
}

// Per parameter: the largest displacement of the built-in face and the errors of the transferred
// rig against the built-in deformation at each target vertex's own point of the built-in surface
// (known: the target is made from the built-in face). Displacements compared in the input frame.
struct ParameterError {
  std::string name;
  double largest = 0.0;  // largest displacement of the built-in face, m
  double worst = 0.0;    // largest error, m
  std::size_t over = 0;  // vertices with error > 3 % of `largest`
};
std::vector<ParameterError> compare(const fm::Face& source, const fm::Mesh& target_in_source_frame,
                                    const rt::TransferResult& r,
                                    const Eigen::Matrix3d& input_rotation, double input_scale) {
  std::vector<Closest> gt(static_cast<std::size_t>(target_in_source_frame.vertices.rows()));
  for (Eigen::Index v = 0; v < target_in_source_frame.vertices.rows(); ++v)
    gt[static_cast<std::size_t>(v)] =
        brute_closest(source.mesh, target_in_source_frame.vertices.row(v).transpose());
  const ms::FaceSolver s(source.mesh, source.rig), t(r.face.mesh, r.face.rig);
  const std::vector<double> zero(ms::kParameterCount, 0.0);
  const auto s0 = s.deform(zero), t0 = t.deform(zero);
  std::vector<ParameterError> out;
  for (std::size_t p = 0; p < ms::kSideParameterCount; ++p) {
    std::vector<double> values = zero;
    values[p] = 1.0;
    const auto ds = s.deform(values), dt = t.deform(values);
    ParameterError e;
    e.name = ms::parameter_names()[p];
    for (Eigen::Index v = 0; v < ds.vertices.rows(); ++v)
      e.largest = std::max(e.largest, (ds.vertices.row(v) - s0.vertices.row(v)).norm());
    for (std::size_t v = 0; v < gt.size(); ++v) {
      Eigen::Vector3d truth = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k) {
        const int g = source.mesh.faces(gt[v].face, k);
        truth += gt[v].bary(k) * (ds.vertices.row(g) - s0.vertices.row(g)).transpose();
      }
      // transferred displacement: rig frame → input frame → (known) source frame
      const Eigen::Vector3d d_rig = (dt.vertices.row(static_cast<Eigen::Index>(v)) -
                                     t0.vertices.row(static_cast<Eigen::Index>(v)))
                                        .transpose();
      const Eigen::Vector3d d_input =
          r.face.rig.frame.rotation.transpose() * d_rig / r.face.rig.frame.scale;
      const Eigen::Vector3d d_source = input_rotation.transpose() * d_input / input_scale;
      const double err = (d_source - truth).norm();
      e.worst = std::max(e.worst, err);
      if (err > 0.03 * e.largest) ++e.over;
    }
    out.push_back(e);
  }
  return out;
}

// Shared fixtures: the built-in face and transfers made once per suite.
// The transfers are made on first use (gtest_discover_tests runs every test in its own process, so
// a test pays only for the transfers it uses).
struct Fixtures {
  fm::Face source = fm::make_generic_face();
  fm::Mesh remeshed;  // half-edge-collapse decimation: a different triangulation, vertices on the
                      // built-in surface
  Fixtures() { remeshed = rt::decimate(source.mesh, 0.6, true); }
  const rt::TransferResult& self_transfer() const {
    static const rt::TransferResult r = rt::transfer_rig(source, source.mesh, {}, quick_options());
    return r;
  }
  const rt::TransferResult& remesh_transfer() const {
    static const rt::TransferResult r = rt::transfer_rig(source, remeshed, {}, quick_options());
    return r;
  }
};
const Fixtures& fixtures() {
  static const Fixtures f;
  return f;
}

}  // namespace

namespace {

// Eyelid checks of a transferred rig (issue 13): blink closes each eye's lid margin (the one the
// transfer found, report.lid_margin_*) without the upper margin passing below the lower one, AU7
// (orbicularis oculi palpebralis) narrows the opening but leaves it open, and no triangle of the
// eye region turns over (normal against its neutral normal) under blink and the six emotions of
// the thesis ch. 6 rules at 0.9 (`emotions`: the 35 side parameters per emotion, from fuzzyexpr).
struct LidCheck {
  std::array<double, 2> open{}, closed{}, narrowed{};  // mean margin gap, % of the head height
  std::array<double, 2> worst_closed{};    // largest partner distance after the blink, %
  std::array<double, 2> worst_crossing{};  // deepest upper-below-lower (y), % (0 = none)
  std::array<double, 2> narrowed_min{};    // smallest gap of the central half under AU7, %
  int flipped = 0;                         // eye-region triangles turned over, all cases
  std::string worst_case;
};
// The six emotions at 0.9 through the thesis ch. 6 rules (fuzzyexpr), as named side parameters.
std::vector<std::map<std::string, double>> six_emotions() {
  namespace fx = emoface::fuzzyexpr;
  const fx::Engine engine;
  std::vector<std::map<std::string, double>> out;
  for (std::size_t e = 0; e < fx::kEmotionCount; ++e) {
    fx::Esv esv{};
    esv[e] = 0.9;
    const auto sides = fx::expand_to_sides(engine.convert(esv));
    std::map<std::string, double> named;
    for (std::size_t i = 0; i < sides.size(); ++i)
      named[std::string(fx::side_parameter_names()[i])] = sides[i];
    out.push_back(named);
  }
  return out;
}

LidCheck check_lids(const rt::TransferResult& r,
                    const std::vector<std::map<std::string, double>>& emotions) {
  LidCheck out;
  const auto& rig = r.face.rig;
  const double h = r.report.head_height * r.report.scale;  // rig frame
  const ms::FaceSolver solver(r.face.mesh, rig);
  const auto n = solver.deform(std::map<std::string, double>{});
  const auto blink =
      solver.deform(std::map<std::string, double>{{"eye_blink_l", 1.0}, {"eye_blink_r", 1.0}});
  const auto au7 = solver.deform(std::map<std::string, double>{
      {"orbicularis_oculi_palpebralis_l", 1.0}, {"orbicularis_oculi_palpebralis_r", 1.0}});
  for (int e = 0; e < 2; ++e) {
    const auto& up = r.report.lid_margin_upper[static_cast<std::size_t>(e)];
    const auto& lo = r.report.lid_margin_lower[static_cast<std::size_t>(e)];
    if (up.size() < 3 || lo.size() < 3) {
      ADD_FAILURE() << "no lid margin for eye " << e;
      continue;
    }
    // partner of an upper margin vertex: the lower margin at the same neutral x (linear)
    auto partner = [&](const fm::Vertices& X, double x) {
      for (std::size_t k = 1; k < lo.size(); ++k) {
        const double x0 = n.vertices(lo[k - 1], 0), x1 = n.vertices(lo[k], 0);
        if (x <= x1 || k + 1 == lo.size()) {
          const double t = x1 > x0 ? std::clamp((x - x0) / (x1 - x0), 0.0, 1.0) : 0.0;
          return Eigen::Vector3d(((1 - t) * X.row(lo[k - 1]) + t * X.row(lo[k])).transpose());
        }
      }
      return Eigen::Vector3d(X.row(lo.back()).transpose());
    };
    const double x_lo = n.vertices(up.front(), 0), x_hi = n.vertices(up.back(), 0);
    double s_open = 0, s_closed = 0, s_narrow = 0, narrow_min = 1e300;
    int count = 0;
    for (std::size_t k = 1; k + 1 < up.size(); ++k) {
      const double x = n.vertices(up[k], 0);
      const double gap_open = (n.vertices.row(up[k]).transpose() - partner(n.vertices, x)).norm();
      const Eigen::Vector3d pb = partner(blink.vertices, x);
      const double gap_closed = (blink.vertices.row(up[k]).transpose() - pb).norm();
      const double gap_narrow =
          au7.vertices(up[k], 1) - partner(au7.vertices, x).y();  // vertical opening under AU7
      s_open += gap_open, s_closed += gap_closed, s_narrow += gap_narrow, ++count;
      out.worst_closed[static_cast<std::size_t>(e)] =
          std::max(out.worst_closed[static_cast<std::size_t>(e)], 100 * gap_closed / h);
      out.worst_crossing[static_cast<std::size_t>(e)] =
          std::max(out.worst_crossing[static_cast<std::size_t>(e)],
                   100 * (pb.y() - blink.vertices(up[k], 1)) / h);
      if (std::abs(x - 0.5 * (x_lo + x_hi)) < 0.25 * (x_hi - x_lo))
        narrow_min = std::min(narrow_min, gap_narrow);
    }
    out.open[static_cast<std::size_t>(e)] = 100 * s_open / count / h;
    out.closed[static_cast<std::size_t>(e)] = 100 * s_closed / count / h;
    out.narrowed[static_cast<std::size_t>(e)] = 100 * s_narrow / count / h;
    out.narrowed_min[static_cast<std::size_t>(e)] = 100 * narrow_min / h;
  }
  // eye region: triangles with a vertex in a lid list or an eye-hole list of the head
  std::vector<std::uint8_t> eye_vertex(static_cast<std::size_t>(r.face.mesh.vertices.rows()), 0);
  for (const auto& eye : rig.eyes) {
    for (int v : eye.upper_lid) eye_vertex[static_cast<std::size_t>(v)] = 1;
    for (int v : eye.lower_lid) eye_vertex[static_cast<std::size_t>(v)] = 1;
  }
  const auto& F = r.face.mesh.faces;
  auto normal = [&](const fm::Vertices& X, Eigen::Index f) {
    const Eigen::Vector3d a = X.row(F(f, 0)), b = X.row(F(f, 1)), c = X.row(F(f, 2));
    return Eigen::Vector3d((b - a).cross(c - a));
  };
  std::vector<std::pair<std::string, std::map<std::string, double>>> cases = {
      {"blink", {{"eye_blink_l", 1.0}, {"eye_blink_r", 1.0}}}};
  for (std::size_t k = 0; k < emotions.size(); ++k)
    cases.push_back({"emotion " + std::to_string(k), emotions[k]});
  for (const auto& [name, values] : cases) {
    const auto d = solver.deform(values);
    int flipped = 0;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      if (!eye_vertex[static_cast<std::size_t>(F(f, 0))] &&
          !eye_vertex[static_cast<std::size_t>(F(f, 1))] &&
          !eye_vertex[static_cast<std::size_t>(F(f, 2))])
        continue;
      const Eigen::Vector3d a = normal(n.vertices, f), b = normal(d.vertices, f);
      if (a.norm() < 1e-14 || b.norm() < 1e-14) continue;  // degenerate in the input
      if (a.dot(b) <= 0.0) ++flipped;
    }
    if (flipped > 0) out.worst_case += name + ": " + std::to_string(flipped) + " ";
    out.flipped += flipped;
  }
  return out;
}

}  // namespace
