#pragma once
// Private: the glTF side of MeshDocument::companion_files (obj_materials.cpp has the OBJ side),
// defined in mesh_document.cpp, where the document's glTF model lives.
#include "emoface/facemesh/mesh_document.hpp"

namespace emoface::facemesh::detail {

Companions gltf_image_companions(const MeshDocument::Impl& doc);

}  // namespace emoface::facemesh::detail
