#pragma once
// Mesh files through OpenMesh (OBJ, PLY, OFF; chosen by extension). OpenMesh never appears in a
// public header. Reading validates the mesh (validate_mesh) and throws FormatError naming the file.
#include <string>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::facemesh {

/// Reads a triangle mesh (polygons are fan-triangulated). Throws IoError if the file cannot be read,
/// FormatError if the content is bad (unknown extension, non-manifold faces, NaN coordinates, a damaged
/// PLY/OFF header, counts the file cannot hold, binary OFF, ...).
Mesh read_mesh(const std::string& path);

struct MeshReadOptions {
  /// Accept triangles whose winding disagrees with their neighbours' (common in scans) and make the
  /// winding consistent and outward per component (orient_consistently). Edges shared by more than two
  /// triangles are still rejected (FormatError).
  bool repair_orientation = false;
};

struct MeshReadReport {
  OrientationReport orientation;  ///< filled when repair_orientation is on
};

/// read_mesh with options; `report` (optional) says what was repaired.
Mesh read_mesh(const std::string& path, const MeshReadOptions& options, MeshReadReport* report = nullptr);

/// Writes a mesh atomically (temporary file + rename). PLY is written as ASCII.
/// Throws InvalidInput for an unknown extension, IoError on failure.
void write_mesh(const std::string& path, const Mesh& mesh);

}  // namespace emoface::facemesh
