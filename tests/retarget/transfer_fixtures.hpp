#pragma once
// Shared by transfer_test.cpp and transfer_slow_test.cpp: options, a brute-force closest point, the
// comparison against the built-in deformation, and the fixtures made once per test program.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/bspline.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"
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
