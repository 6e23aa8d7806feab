#pragma once
// Analytic test meshes for the retarget tests: UV spheres / ellipsoids with a pole at the top.
#include <array>
#include <cmath>
#include <vector>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget::test {

/// Ellipsoid with semi-axes (a, b, c) along (x, y, z), `rings` latitude bands and `segments` around;
/// vertex 0 is the top pole (0, b, 0), the last vertex the bottom pole. Outward counter-clockwise faces.
inline facemesh::Mesh ellipsoid(double a, double b, double c, int rings = 40, int segments = 64,
                                double azimuth_offset = 0.0) {
  const double pi = 3.14159265358979323846;
  facemesh::Mesh m;
  m.vertices.resize(2 + (rings - 1) * segments, 3);
  m.vertices.row(0) << 0, b, 0;
  for (int i = 1; i < rings; ++i) {
    const double th = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * pi * j / segments + azimuth_offset;
      m.vertices.row(1 + (i - 1) * segments + j) << a * std::sin(th) * std::sin(ph), b * std::cos(th),
          c * std::sin(th) * std::cos(ph);
    }
  }
  const int bottom = 1 + (rings - 1) * segments;
  m.vertices.row(bottom) << 0, -b, 0;
  std::vector<std::array<int, 3>> f;
  auto id = [&](int i, int j) { return 1 + (i - 1) * segments + ((j % segments) + segments) % segments; };
  for (int j = 0; j < segments; ++j) f.push_back({0, id(1, j + 1), id(1, j)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      f.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      f.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  for (int j = 0; j < segments; ++j) f.push_back({bottom, id(rings - 1, j), id(rings - 1, j + 1)});
  m.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t k = 0; k < f.size(); ++k) m.faces.row(static_cast<Eigen::Index>(k)) << f[k][0], f[k][1], f[k][2];
  return m;
}

}  // namespace emoface::retarget::test
