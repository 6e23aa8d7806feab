#pragma once
// Triangle meshes: the data type every emoface geometry library passes around, plus validation and
// normals. Units: metres; axes: +x towards the subject's left, +y up, +z out of the face (the default
// face looks down +z).
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace emoface::facemesh {

/// #V by 3 vertex positions (metres, row-major rows = vertices).
using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
/// #F by 3 vertex ids per triangle, counter-clockwise seen from outside.
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct Mesh {
  Vertices vertices;
  Faces faces;
  std::size_t vertex_count() const noexcept { return static_cast<std::size_t>(vertices.rows()); }
  std::size_t face_count() const noexcept { return static_cast<std::size_t>(faces.rows()); }
};

/// Checks a mesh: at least one triangle, finite coordinates, ids in range, no repeated id inside a
/// triangle, no zero-area triangle, no edge shared by more than two triangles or twice in the same
/// direction (non-manifold / inconsistently oriented). Throws FormatError naming `source` (a file path
/// or a description) and the offending face or vertex as "line" (1-based element index).
void validate_mesh(const Mesh& mesh, const std::string& source = "<mesh>");

/// What orient_consistently did.
struct OrientationReport {
  std::size_t components = 0;         ///< edge-connected components of faces
  std::size_t closed_components = 0;  ///< of which without boundary edges (oriented outward by signed volume)
  std::size_t flipped_faces = 0;      ///< faces whose winding was reversed
  std::size_t flipped_components = 0; ///< components turned inside out as a whole (after making them consistent)
};

/// Makes the winding of the triangles consistent inside each edge-connected component (breadth-first
/// over shared edges, reversing a neighbour that runs a shared edge in the same direction), then points
/// each component outward: a closed component by the sign of its enclosed volume, an open one (a scan
/// with holes, a face mask) by the sign of Σ area·n·(centroid − component centroid). Throws InvalidInput
/// naming the face for ids out of range, an edge shared by more than two triangles (non-manifold: no
/// consistent orientation exists; remove the extra faces first) or a non-orientable component (a
/// Möbius strip). Changes nothing else (vertices, face order).
OrientationReport orient_consistently(Mesh& mesh);

/// Unit normal of every face (#F by 3); a zero-area face gets (0,0,0).
Vertices face_normals(const Vertices& vertices, const Faces& faces);

/// Area-weighted average of incident face normals, normalised (#V by 3); isolated vertices get 0.
Vertices vertex_normals(const Vertices& vertices, const Faces& faces);

/// Loop-free midpoint subdivision (each triangle into four); used to build the large benchmark face.
/// `parent_pairs` (optional) receives, per new vertex beyond the original #V, the two parent ids.
Mesh subdivide_midpoint(const Mesh& mesh, std::vector<std::pair<int, int>>* parent_pairs = nullptr);

}  // namespace emoface::facemesh
