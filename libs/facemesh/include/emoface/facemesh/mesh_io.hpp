#pragma once
// Mesh files through OpenMesh (OBJ, PLY, OFF; chosen by extension). OpenMesh never appears in a
// public header. Reading validates the mesh (validate_mesh) and throws FormatError naming the file.
#include <string>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::facemesh {

/// Reads a triangle mesh (polygons are fan-triangulated). Throws IoError if the file cannot be read,
/// FormatError if the content is bad (unknown extension, non-manifold faces, NaN coordinates, ...).
Mesh read_mesh(const std::string& path);

/// Writes a mesh atomically (temporary file + rename). PLY is written as ASCII.
/// Throws InvalidInput for an unknown extension, IoError on failure.
void write_mesh(const std::string& path, const Mesh& mesh);

}  // namespace emoface::facemesh
