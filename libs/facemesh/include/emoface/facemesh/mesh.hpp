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

/// Unit normal of every face (#F by 3); a zero-area face gets (0,0,0).
Vertices face_normals(const Vertices& vertices, const Faces& faces);

/// Area-weighted average of incident face normals, normalised (#V by 3); isolated vertices get 0.
Vertices vertex_normals(const Vertices& vertices, const Faces& faces);

/// Loop-free midpoint subdivision (each triangle into four); used to build the large benchmark face.
/// `parent_pairs` (optional) receives, per new vertex beyond the original #V, the two parent ids.
Mesh subdivide_midpoint(const Mesh& mesh, std::vector<std::pair<int, int>>* parent_pairs = nullptr);

}  // namespace emoface::facemesh
