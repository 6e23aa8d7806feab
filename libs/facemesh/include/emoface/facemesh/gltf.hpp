#pragma once
// Animated glTF 2.0 export (tinygltf, private): the neutral mesh plus one morph target per frame,
// animated by a weights channel (one-hot at each frame time, linear in between), so Blender, three.js
// and game engines play the sequence.
#include <string>
#include <vector>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::facemesh {

/// `frames[i]` has the neutral mesh's vertex count; `times` (seconds, strictly increasing) one per
/// frame. Writes a .gltf (JSON with the buffer embedded as base64) or .glb (binary), atomically.
/// Throws InvalidInput on mismatched sizes, IoError on failure.
void write_animated_gltf(const std::string& path, const Mesh& neutral, const std::vector<Vertices>& frames,
                         const std::vector<double>& times);

}  // namespace emoface::facemesh
