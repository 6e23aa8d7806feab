#pragma once
// Surface queries of the retargeting error function (thesis §3.5) and the GA's projection operator
// (thesis §3.2.1, §3.6.2), in the thesis frame: the face looks down +z, y is up (see mesh.hpp for x).
//
// A "half-plane" is the part of a sampling plane P_i through the vertical centreline l on one side of l;
// it is named by its azimuth a (radians, 0 = +z, π/2 = +x): points c + r·(sin a, 0, cos a) + y·ŷ, r ≥ 0.
// Curves are returned in half-plane coordinates (r, y), metres.
#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::retarget {

/// Connectivity of a triangle mesh for walking plane intersections: undirected edges with their one or
/// two faces (orientation-independent, so inconsistently oriented scans work), and the boundary loops
/// (holes: eyes, mouth, open neck, a mask's rim) as connected sets of boundary edges.
class MeshWalker {
 public:
  /// Throws InvalidInput for ids out of range or an edge shared by more than two faces.
  MeshWalker(const facemesh::Faces& faces, std::size_t vertex_count);
  ~MeshWalker();
  MeshWalker(MeshWalker&&) noexcept;
  MeshWalker& operator=(MeshWalker&&) noexcept;

  /// Intersection curve of the half-plane (centre c: only c.x and c.z matter; azimuth a) with the mesh,
  /// found by walking from `start` (the top-of-head vertex, on l) down through adjacent faces (thesis
  /// §3.5): the current edge's other face gives the next crossing edge; visited edges are marked. At a
  /// boundary edge the hole is "filled": the walk jumps to the nearest lower crossing of the same
  /// boundary loop in the same half-plane (a straight segment across the eye or mouth hole); if there is
  /// none (the neck's open end, a mask's rim) the curve ends. The walk also ends below `stop_y` or when it
  /// crosses l. Returns (r, y) points, the first one being `start`.
  std::vector<Eigen::Vector2d> half_plane_curve(const facemesh::Vertices& vertices, int start,
                                                const Eigen::Vector3d& c, double azimuth,
                                                double stop_y) const;

  /// True if the vertex lies on an open boundary (a hole's rim) or on no face at all.
  bool on_boundary(int vertex) const;

  std::size_t edge_count() const;
  std::size_t boundary_loop_count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Cylindrical projection onto a fixed mesh (thesis §3.2.1): a point p is moved along the horizontal
/// ray from the centreline l through p to where that ray meets the surface (the hit closest to p).
/// Triangles are binned on an (azimuth, height) grid so one query tests only a few triangles.
class CylindricalProjector {
 public:
  /// `centre`: a point of l (only x and z matter). Throws InvalidInput for an empty mesh or bins < 4.
  CylindricalProjector(const facemesh::Mesh& mesh, const Eigen::Vector3d& centre, int azimuth_bins = 96,
                       int height_bins = 96);
  ~CylindricalProjector();
  CylindricalProjector(CylindricalProjector&&) noexcept;
  CylindricalProjector& operator=(CylindricalProjector&&) noexcept;

  /// Projection of p; false (and `out` unchanged) when the ray misses the surface.
  bool project(const Eigen::Vector3d& p, Eigen::Vector3d& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Index of the vertex with the largest y (the top of the head, thesis §3.2.1); ties: lowest index.
int top_vertex(const facemesh::Vertices& vertices);

}  // namespace emoface::retarget
