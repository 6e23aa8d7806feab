#pragma once
// The rig file `emoface.rig` (JSON, envelope kind "rig", version 1.1; a 1.0 file reads with the 1.1
// defaults) and loading a rigged face.
// nlohmann-json stays behind this header's implementation.
#include <memory>
#include <string>
#include <string_view>

#include "emoface/facemesh/mesh.hpp"
#include "emoface/facemesh/mesh_document.hpp"
#include "emoface/facemesh/rig.hpp"

namespace emoface::facemesh {

/// Current rig format version.
inline constexpr int kRigFormatMajor = 1;
inline constexpr int kRigFormatMinor = 3;

/// Parses rig JSON text; `source` names it in errors. Throws FormatError (with JSON pointer) on any
/// problem, including validate_rig failures.
Rig parse_rig(std::string_view text, const std::string& source = "<rig>");
/// Serialises a rig (deterministic, human-readable JSON, ends with a newline).
std::string format_rig(const Rig& rig);

Rig read_rig(const std::string& path);
/// Writes atomically.
void write_rig(const std::string& path, const Rig& rig);

struct Face {
  Mesh mesh;  ///< in the rig frame (rig.frame.to_rig of the file's positions)
  Rig rig;
  /// The mesh file as load_face read it when it is an OBJ, PLY or glTF document (its UVs, groups,
  /// materials, vertex colours, other meshes ... in the mesh frame); null for OFF and faces built
  /// in memory.
  std::shared_ptr<const MeshDocument> document;
};

/// Reads a rig and the mesh it references (relative to the rig's directory); checks that they fit.
/// .obj/.ply/.gltf/.glb are read as a MeshDocument (vertex order = file order, several parts
/// allowed; kept in Face::document), .off with read_mesh. The file's positions are in the rig's
/// mesh frame; the returned mesh is converted into the rig frame (rig.frame.to_rig), so every
/// consumer works in the rig frame unchanged.
Face load_face(const std::string& rig_path);
/// Writes `face.rig` to rig_path and the mesh to the directory of rig_path under
/// face.rig.mesh_file, converted back into the mesh frame (rig.frame.to_mesh). With a document of
/// the same kind as the file name (OBJ to .obj, PLY to .ply, glTF to .gltf/.glb) the mesh is
/// written through MeshDocument::write (every other line/attribute kept), otherwise with
/// write_mesh.
void save_face(const std::string& rig_path, const Face& face);

/// The file format that keeps what face.document holds when frames of the face are written:
/// "glb" for a glTF document, "ply" for a PLY document, otherwise "obj" (faceanim's default).
std::string frame_format(const Face& face);

/// Writes `positions` (#V by 3, rig frame: face.mesh or a deformation of it) as a mesh file in the
/// mesh frame (to_mesh_frame, unmoved vertices bit for bit): through face.document when `path` is
/// of the document's kind (.obj for an OBJ, .ply for a PLY, .gltf/.glb for a glTF document: UVs,
/// groups, materials, vertex colours, other meshes kept, normals recomputed, .mtl copied), else
/// with write_mesh (.obj/.ply/.off). Throws InvalidInput for a size mismatch, or .gltf/.glb without
/// a glTF document.
void write_face_mesh(const std::string& path, const Face& face, const Vertices& positions);

/// The face's positions (#V by 3, rig frame) in the mesh file's frame (rig.frame.to_mesh; the same
/// matrix, bit for bit, when the frame is the identity). With `original` (#V by 3, the file's own
/// positions, mesh frame): a vertex whose position is to_rig(original) bit for bit gets its original
/// back, so an unmoved vertex is written exactly as it was read (to_mesh(to_rig(p)) may differ from p
/// in the last bit).
Vertices to_mesh_frame(const Rig& rig, const Vertices& positions, const Vertices* original = nullptr);

}  // namespace emoface::facemesh
