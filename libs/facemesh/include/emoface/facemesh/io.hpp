#pragma once
// The rig file `emoface.rig` (JSON, envelope kind "rig", version 1.1; a 1.0 file reads with the 1.1
// defaults) and loading a rigged face.
// nlohmann-json stays behind this header's implementation.
#include <string>
#include <string_view>

#include "emoface/facemesh/mesh.hpp"
#include "emoface/facemesh/rig.hpp"

namespace emoface::facemesh {

/// Current rig format version.
inline constexpr int kRigFormatMajor = 1;
inline constexpr int kRigFormatMinor = 1;

/// Parses rig JSON text; `source` names it in errors. Throws FormatError (with JSON pointer) on any
/// problem, including validate_rig failures.
Rig parse_rig(std::string_view text, const std::string& source = "<rig>");
/// Serialises a rig (deterministic, human-readable JSON, ends with a newline).
std::string format_rig(const Rig& rig);

Rig read_rig(const std::string& path);
/// Writes atomically.
void write_rig(const std::string& path, const Rig& rig);

struct Face {
  Mesh mesh;
  Rig rig;
};

/// Reads a rig and the mesh it references (relative to the rig's directory); checks that they fit.
Face load_face(const std::string& rig_path);
/// Writes `face.rig` to rig_path and the mesh to the directory of rig_path under face.rig.mesh_file.
void save_face(const std::string& rig_path, const Face& face);

}  // namespace emoface::facemesh
