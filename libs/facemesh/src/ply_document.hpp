#pragma once
// Private: a PLY file kept whole for MeshDocument (mesh_document.hpp). Our own parser (ASCII,
// binary little and big endian; the PLY format as described by Greg Turk, "The PLY Polygon File
// Format", 1994): every element and property is kept, the vertex positions (x, y, z, float or
// double), the optional normals (nx, ny, nz) and colours (red/green/blue[/alpha] or diffuse_*,
// uchar, ushort, float or double) are read, faces come from the `face` element's vertex_indices
// (or vertex_index) list. Writing patches the x/y/z (and nx/ny/nz) bytes or tokens of moved
// vertices in place; the header and every other byte stay as they were.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::facemesh::detail {

struct PlySlot {  // where one number of a vertex lives in the file
  std::size_t offset = 0, length = 0;
};

struct PlyDocument {
  enum class Encoding { Ascii, BinaryLittle, BinaryBig };
  Encoding encoding = Encoding::Ascii;
  std::string text;                        // the whole file
  std::vector<double> xyz;                 // 3 per vertex, file order
  std::vector<std::vector<int>> polygons;  // the face element's vertex lists
  std::vector<std::size_t> polygon_line;   // ASCII: 1-based line of each polygon, binary: 0
  std::vector<Eigen::Vector3f>
      colors;                      // per vertex when the vertex element has colours, else empty
  std::array<int, 6> slot_type{};  // PLY type ids of x, y, z, nx, ny, nz (0 = absent)
  std::vector<std::array<PlySlot, 6>> slots;  // per vertex
  bool has_normals = false;
  std::vector<std::string>
      kept_properties;  // vertex properties we do not interpret (kept as they are)
};

/// Parses PLY text; throws FormatError naming `path` and the line (ASCII / header) or the byte
/// offset (binary) for anything malformed, truncated, non-finite, out of range or too large.
PlyDocument parse_ply(std::string text, const std::string& path);

/// The file with new positions (#V by 3): the x/y/z numbers of vertices whose position changed
/// (bit comparison with the parsed ones) rewritten (`%.9g` float, `%.17g` double in ASCII; native
/// width and byte order in binary); with `normals` (#V by 3, or empty) the nx/ny/nz of `dirty`
/// vertices too. Everything else byte for byte.
std::string write_ply(const PlyDocument& doc, const Vertices& positions, const Vertices& normals,
                      const std::vector<char>& dirty);

}  // namespace emoface::facemesh::detail
