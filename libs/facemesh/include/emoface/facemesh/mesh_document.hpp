#pragma once
// A user's mesh file as a document: read once, keep everything the user made (UVs, normals, groups,
// objects, materials, other meshes, morph targets, skins), expose the triangles emoface works on,
// and write the same file back with new vertex positions. Used by `retarget --transfer` (the output
// rig's mesh *is* the user's mesh) and by `faceanim` frames on a transferred rig.
//
//   MeshDocument doc = read_mesh_document("head.obj");   // .obj, .ply, .off, .gltf, .glb
//   const Mesh& tri = doc.triangles();                   // input frame and units, vertex order
//   kept doc.write("frame_0001.obj", deformed_vertices);      // everything else unchanged
//
// OBJ is parsed here (not through OpenMesh) so that the vertex order is exactly the file's `v`
// order and every other line survives verbatim; polygons are fan-triangulated for triangles().
// glTF 2.0 goes through tinygltf: the first mesh, all of its triangle primitives (vertices of
// primitive k follow those of k−1). PLY is parsed here too (ASCII and binary): every element and
// property is kept, vertex colours are read, and writing patches only the x/y/z (and nx/ny/nz)
// numbers of moved vertices. OFF is read with read_mesh and written with write_mesh (no extra
// content to keep).
#include <memory>
#include <string>
#include <vector>

#include "emoface/facemesh/gltf_morph.hpp"
#include "emoface/facemesh/mesh.hpp"

namespace emoface::facemesh {

enum class MeshFormat { Obj, Ply, Off, Gltf, Glb };
std::string to_string(MeshFormat format);
/// From the extension (case-insensitive); throws InvalidInput naming the path for anything else.
MeshFormat mesh_format_from_path(const std::string& path);

/// One named group of triangles in the file: an OBJ `o`/`g` name and `usemtl` material, or a glTF
/// primitive (mesh name + index, material name). Used to recognise parts (eyes, teeth, lashes).
/// Knobs of MeshDocument::write_gltf_with_targets.
struct DocumentTargetsOptions {
  bool sparse = true;            ///< sparse accessors where they take fewer bytes
  double sparse_epsilon = 1e-7;  ///< a delta component below this counts as zero (sparse), >= 0
  /// Appended to an added target's name that the document already uses (then "2", "3", ...).
  std::string clash_suffix = "_emoface";
  void validate() const;
};

/// What write_gltf_with_targets wrote.
struct DocumentTargetsReport {
  std::vector<std::string> names;    ///< the added targets' names as written (renamed on a clash)
  std::size_t existing_targets = 0;  ///< the document's own targets, kept first
  std::size_t animated_nodes = 0;    ///< nodes of the first mesh the weight channels drive
  std::size_t sparse_accessors = 0, dense_accessors = 0;
};

/// A file that goes with a copy of a document: its path relative to the copy's directory (inside
/// it,
/// '/' separated) and its bytes.
struct CompanionFile {
  std::string path;
  std::string bytes;
};
/// MeshDocument::companion_files: what to write beside a copy, and what could not be (warnings).
struct Companions {
  std::vector<CompanionFile> files;
  std::vector<std::string> warnings;
};

struct MeshGroup {
  std::string object;    ///< OBJ `o` (or glTF mesh name), may be empty
  std::string group;     ///< OBJ `g` (or "primitive_<k>"), may be empty
  std::string material;  ///< OBJ `usemtl` / glTF material name, may be empty
  std::vector<int> faces;  ///< ids into triangles().faces, ascending
};

class MeshDocument {
 public:
  MeshDocument();
  ~MeshDocument();
  MeshDocument(MeshDocument&&) noexcept;
  MeshDocument& operator=(MeshDocument&&) noexcept;
  MeshDocument(const MeshDocument&);
  MeshDocument& operator=(const MeshDocument&);

  MeshFormat format() const;
  const std::string& path() const;
  /// Positions (input frame and units, file order) and fan-triangulated faces. Faces that are
  /// degenerate (repeated id, zero area) are left out here and listed in dropped_faces(); they stay in
  /// the file. Not necessarily one connected component, not necessarily closed.
  const Mesh& triangles() const;
  /// Per triangle, the 0-based index of the polygon (OBJ `f` line / glTF triangle) it came from.
  const std::vector<int>& polygon_of_triangle() const;
  std::size_t dropped_faces() const;
  const std::vector<MeshGroup>& groups() const;
  /// Texture coordinates present (OBJ `vt` referenced by faces, glTF TEXCOORD_0).
  bool has_uvs() const;
  /// Per-vertex colours when every vertex has one (OBJ `v x y z r g b`, glTF COLOR_0 on every
  /// primitive, PLY red/green/blue (or diffuse_*) as uchar/ushort (scaled to 0-1) or float/double),
  /// else empty.
  const std::vector<Eigen::Vector3f>& vertex_colors() const;
  /// OBJ `mtllib` files named by the document (paths as written, relative to the file's directory).
  const std::vector<std::string>& material_libraries() const;
  /// OBJ: the files a copy of this document written into another directory needs — every `mtllib`
  /// and every texture its `map_*`/`bump`/`disp`/`decal`/`refl`/`norm` statements name (option
  /// flags such as `-s 1 1 1 -bm 0.5` skipped, names with spaces kept), at the same paths relative
  /// to the copy as to the original. Nothing lands outside the copy's directory: a texture with an
  /// absolute path or one leaving the mesh's directory (`..`) is copied in beside its .mtl under
  /// its base name (made unique) and the .mtl line rewritten to name it; a material library outside
  /// it is not copied. Missing files are warnings, not errors. glTF/GLB: every image with a file
  /// uri (not a data URI or buffer view) at its uri relative to the copy; one leaving the
  /// document's directory (absolute, `..`) or missing is a warning, not copied. Empty for other
  /// formats. Reads the files; throws IoError when an existing one cannot be read.
  Companions companion_files() const;
  /// glTF: the first mesh's own morph targets (dense or sparse accessors), in file order: name from
  /// mesh.extras.targetNames ("target_<k>" when unnamed), POSITION deltas per vertex of triangles()
  /// (#V by 3, the file's frame and units; zero rows where a primitive's target has no POSITION),
  /// NORMAL deltas likewise or empty when no primitive has any. Empty for other formats.
  const std::vector<MorphTarget>& morph_targets() const;

  /// Writes the document with `positions` (#V by 3, input frame) in place of the original vertex
  /// positions; everything else byte for byte where the format allows (OBJ: only the numbers of the
  /// `v` lines whose position changed (bit comparison) change, `%.17g`, colours on them kept; with
  /// `recompute_normals` each `vn` used by a triangle with a moved vertex is recomputed,
  /// area-weighted; glTF: POSITION (and NORMAL when recompute_normals) data of the first mesh
  /// rewritten in place, min/max updated (a sparse one that changes is written dense); `path` may
  /// be .gltf (buffers embedded) or .glb; PLY to .ply: only the x/y/z numbers (tokens or bytes) of
  /// moved vertices change, nx/ny/nz recomputed around them with `recompute_normals`, every other
  /// property kept). `positions` equal to triangles().vertices reproduces the input file byte for
  /// byte for OBJ and PLY. Copies the OBJ's material libraries and their textures, or the glTF's
  /// image files (companion_files), next to `path` when `copy_materials` and the target directory
  /// differs. Atomic (temporary file
  /// + rename); throws InvalidInput on a size mismatch or non-finite positions, IoError on failure.
  void write(const std::string& path, const Vertices& positions, bool recompute_normals = true,
             bool copy_materials = true) const;

  /// glTF/GLB only (InvalidInput otherwise): writes the document with extra named morph targets on the
  /// first mesh's primitives (POSITION deltas per vertex of triangles(), #V by 3 each, input frame;
  /// names in mesh.extras.targetNames after any existing ones), existing targets and skins kept.
  void write_gltf_with_targets(const std::string& path, const std::vector<std::string>& names,
                               const std::vector<Vertices>& deltas) const;

  /// glTF/GLB only (InvalidInput otherwise): the user's file with our named morph targets added to
  /// every primitive of the first mesh and our weight animations added; everything of theirs
  /// (nodes, skins, materials, UVs, images, their own targets and animations) kept. `targets`:
  /// POSITION deltas per vertex of triangles() (#V by 3, the file's frame and units); NORMAL deltas
  /// (#V by 3) written where the primitive has NORMAL and its own targets (if any) have NORMAL
  /// deltas too. Target names go to mesh.extras.targetNames after the document's own (placeholders
  /// "target_<k>" for unnamed ones); a name the document already uses gets options.clash_suffix.
  /// Each animation has one weight per *added* target per key; the document's own targets keep
  /// their default weights in the channel, which drives every node that holds the first mesh
  /// (InvalidInput if none does). WeightAnimation::head_rotations are not written: in a user's file
  /// the head is theirs (a skeleton's neck joint, a node), not ours to re-parent.
  DocumentTargetsReport write_gltf_with_targets(const std::string& path,
                                                const std::vector<MorphTarget>& targets,
                                                const std::vector<WeightAnimation>& animations = {},
                                                const DocumentTargetsOptions& options = {}) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
  friend MeshDocument read_mesh_document(const std::string& path);

/// An OBJ document from text in memory (the built-in default face); `source` names it in errors and
/// is the document's path (material libraries are looked up beside it). Errors as read_mesh_document.
MeshDocument parse_obj_document(std::string text, const std::string& source);
  friend MeshDocument parse_obj_document(std::string text, const std::string& source);
};

/// Reads a mesh document. Throws IoError if unreadable, FormatError naming the file and line (OBJ) or
/// JSON pointer / accessor (glTF) for malformed content, NaN/inf, ids out of range, no triangle at all,
/// an edge shared by more than two triangles of one part, or counts the file cannot hold.
MeshDocument read_mesh_document(const std::string& path);

/// An OBJ document from text in memory (the built-in default face); `source` names it in errors and
/// is the document's path (material libraries are looked up beside it). Errors as read_mesh_document.
MeshDocument parse_obj_document(std::string text, const std::string& source);

}  // namespace emoface::facemesh
