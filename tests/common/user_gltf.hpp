#pragma once
// Test fixture: a user's character as a glTF 2.0 file of their own — a skinned head (two joints
// with inverse bind matrices, JOINTS_0/WEIGHTS_0), a UV set with a texture under a named PBR
// material, one morph target of theirs ("user_smile") and an animation of theirs (the jaw joint) —
// written from any triangle mesh (e.g. the face under test). Used to check that our glTF writers
// keep everything of theirs (tests/retarget/app_test.cpp, tests/gltf/make_user_gltf.cpp). With
// `sparse_target` their target is a sparse accessor (no buffer view: zeros, then the moved rows),
// as engines export morph targets (glTF 2.0 §3.6.2.3).
#include <tiny_gltf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "emoface/facemesh/mesh.hpp"

namespace emoface::testing {

inline int user_gltf_accessor(tinygltf::Model& m, const void* data, std::size_t bytes,
                              int component, int type, std::size_t count, int target = 0) {
  auto& buf = m.buffers[0].data;
  while (buf.size() % 4) buf.push_back(0);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteOffset = buf.size();
  v.byteLength = bytes;
  if (target) v.target = target;
  buf.resize(buf.size() + bytes);
  std::memcpy(buf.data() + v.byteOffset, data, bytes);
  m.bufferViews.push_back(v);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  a.componentType = component;
  a.type = type;
  a.count = count;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

inline void user_gltf_bounds(tinygltf::Model& m, int accessor, const std::vector<float>& xyz) {
  std::vector<double> lo(3, 1e300), hi(3, -1e300);
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], static_cast<double>(xyz[i]));
    hi[i % 3] = std::max(hi[i % 3], static_cast<double>(xyz[i]));
  }
  m.accessors[static_cast<std::size_t>(accessor)].minValues = lo;
  m.accessors[static_cast<std::size_t>(accessor)].maxValues = hi;
}

/// The model (metres, the mesh's frame): node 0 "user_head" (mesh 0, skin 0, a scene root), node 1
/// "neck" (joint, at (0, −0.1, 0)) with child node 2 "jaw_bone" (joint, (0, 0.04, 0.03) from the
/// neck); vertices below y = −0.05 follow the jaw joint, the rest the neck.
inline tinygltf::Model user_gltf_model(const facemesh::Mesh& mesh, bool sparse_target = false) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "a user's modelling tool";
  m.buffers.resize(1);
  const auto nv = static_cast<std::size_t>(mesh.vertices.rows());
  std::vector<float> pos, nrm, uv, weights, smile;
  std::vector<std::uint8_t> joints;
  const facemesh::Vertices normals = facemesh::vertex_normals(mesh.vertices, mesh.faces);
  for (std::size_t i = 0; i < nv; ++i) {
    const auto v = static_cast<long>(i);
    for (int k = 0; k < 3; ++k) {
      pos.push_back(static_cast<float>(mesh.vertices(v, k)));
      nrm.push_back(static_cast<float>(normals(v, k)));
    }
    const double x = mesh.vertices(v, 0), y = mesh.vertices(v, 1);
    uv.push_back(static_cast<float>(std::clamp(0.5 + x / 0.3, 0.0, 1.0)));
    uv.push_back(static_cast<float>(std::clamp(0.5 - y / 0.3, 0.0, 1.0)));
    const bool jaw = y < -0.05;
    joints.insert(joints.end(), {static_cast<std::uint8_t>(jaw ? 1 : 0), 0, 0, 0});
    weights.insert(weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
    // their own target: the left mouth corner region up by 2 mm
    const bool corner = x > 0.01 && y < -0.02 && y > -0.06;
    smile.insert(smile.end(), {0.0f, corner ? 0.002f : 0.0f, 0.0f});
  }
  std::vector<std::uint32_t> idx;
  for (long f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) idx.push_back(static_cast<std::uint32_t>(mesh.faces(f, k)));
  tinygltf::Primitive p;
  p.mode = TINYGLTF_MODE_TRIANGLES;
  p.attributes["POSITION"] =
      user_gltf_accessor(m, pos.data(), pos.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                         TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  user_gltf_bounds(m, p.attributes["POSITION"], pos);
  p.attributes["NORMAL"] =
      user_gltf_accessor(m, nrm.data(), nrm.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                         TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  p.attributes["TEXCOORD_0"] =
      user_gltf_accessor(m, uv.data(), uv.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                         TINYGLTF_TYPE_VEC2, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  p.attributes["JOINTS_0"] =
      user_gltf_accessor(m, joints.data(), joints.size(), TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                         TINYGLTF_TYPE_VEC4, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  p.attributes["WEIGHTS_0"] =
      user_gltf_accessor(m, weights.data(), weights.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                         TINYGLTF_TYPE_VEC4, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  p.indices =
      user_gltf_accessor(m, idx.data(), idx.size() * 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                         TINYGLTF_TYPE_SCALAR, idx.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  const int t = user_gltf_accessor(m, smile.data(), smile.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                   TINYGLTF_TYPE_VEC3, nv, TINYGLTF_TARGET_ARRAY_BUFFER);
  user_gltf_bounds(m, t, smile);
  if (sparse_target) {  // the same accessor, sparse: indices (uint32) and values of the moved rows
    std::vector<std::uint32_t> rows;
    std::vector<float> values;
    for (std::size_t i = 0; i < nv; ++i) {
      if (smile[3 * i + 1] != 0.0f) {
        rows.push_back(static_cast<std::uint32_t>(i));
        values.insert(values.end(), smile.begin() + static_cast<long>(3 * i),
                      smile.begin() + static_cast<long>(3 * i + 3));
      }
    }
    const int iv =
        m.accessors[static_cast<std::size_t>(user_gltf_accessor(
                        m, rows.data(), rows.size() * 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                        TINYGLTF_TYPE_SCALAR, rows.size()))]
            .bufferView;
    const int vv = m.accessors[static_cast<std::size_t>(user_gltf_accessor(
                                   m, values.data(), values.size() * 4,
                                   TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, rows.size()))]
                       .bufferView;
    m.accessors.resize(m.accessors.size() - 2);  // only their views are used
    auto& a = m.accessors[static_cast<std::size_t>(t)];
    a.bufferView = -1;
    a.sparse.isSparse = true;
    a.sparse.count = static_cast<int>(rows.size());
    a.sparse.indices.bufferView = iv;
    a.sparse.indices.byteOffset = 0;
    a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    a.sparse.values.bufferView = vv;
    a.sparse.values.byteOffset = 0;
  }
  p.targets.push_back({{"POSITION", t}});
  p.material = 0;
  tinygltf::Mesh head;
  head.name = "user_head";
  head.primitives.push_back(p);
  head.weights = {0.0};
  tinygltf::Value::Object extras;
  extras["targetNames"] =
      tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(std::string("user_smile"))});
  head.extras = tinygltf::Value(extras);
  m.meshes.push_back(head);
  // a 1×1 PNG (skin tone) as the base colour texture
  tinygltf::Image image;
  image.name = "user_skin_texture";
  image.mimeType = "image/png";
  image.uri =
      "data:image/"
      "png;base64,"
      "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJg"
      "gg==";
  m.images.push_back(image);
  tinygltf::Texture tex;
  tex.source = 0;
  m.textures.push_back(tex);
  tinygltf::Material mat;
  mat.name = "user_skin";
  mat.pbrMetallicRoughness.baseColorFactor = {0.8, 0.6, 0.5, 1.0};
  mat.pbrMetallicRoughness.baseColorTexture.index = 0;
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 0.7;
  m.materials.push_back(mat);
  tinygltf::Node head_node, neck, jaw;
  head_node.name = "user_head";
  head_node.mesh = 0;
  head_node.skin = 0;
  neck.name = "neck";
  neck.translation = {0.0, -0.1, 0.0};
  neck.children = {2};
  jaw.name = "jaw_bone";
  jaw.translation = {0.0, 0.04, 0.03};
  m.nodes = {head_node, neck, jaw};
  // inverse bind matrices (column-major): the inverse of each joint's global translation
  const float ibm[32] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.1f,  0,      1,
                         1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0.06f, -0.03f, 1};
  tinygltf::Skin skin;
  skin.name = "user_rig";
  skin.joints = {1, 2};
  skin.skeleton = 1;
  skin.inverseBindMatrices =
      user_gltf_accessor(m, ibm, sizeof ibm, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, 2);
  m.skins.push_back(skin);
  // their own animation: the jaw joint opens by 0.1 rad about +x over a second
  const float times[2] = {0.0f, 1.0f};
  const float rot[8] = {0, 0, 0, 1, 0.04997917f, 0, 0, 0.99875026f};
  tinygltf::Animation anim;
  anim.name = "user_jaw";
  tinygltf::AnimationSampler s;
  s.input = user_gltf_accessor(m, times, sizeof times, TINYGLTF_COMPONENT_TYPE_FLOAT,
                               TINYGLTF_TYPE_SCALAR, 2);
  m.accessors[static_cast<std::size_t>(s.input)].minValues = {0.0};
  m.accessors[static_cast<std::size_t>(s.input)].maxValues = {1.0};
  s.output =
      user_gltf_accessor(m, rot, sizeof rot, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, 2);
  s.interpolation = "LINEAR";
  anim.samplers.push_back(s);
  tinygltf::AnimationChannel c;
  c.sampler = 0;
  c.target_node = 2;
  c.target_path = "rotation";
  anim.channels.push_back(c);
  m.animations.push_back(anim);
  tinygltf::Scene scene;
  scene.name = "user_scene";
  scene.nodes = {0, 1};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  return m;
}

/// Writes user_gltf_model(mesh, sparse_target) to `path` (.gltf with the buffer embedded, or .glb).
inline bool write_user_gltf(const std::string& path, const facemesh::Mesh& mesh,
                            bool sparse_target = false) {
  tinygltf::Model m = user_gltf_model(mesh, sparse_target);
  tinygltf::TinyGLTF w;
  const bool glb = path.size() > 4 && path.substr(path.size() - 4) == ".glb";
  // keep the image as its data URI (never decoded/re-encoded)
  w.SetImageWriter(
      [](const std::string*, const std::string*, const tinygltf::Image* image, bool,
         std::string* uri, void*) {
        *uri = image->uri;
        return true;
      },
      nullptr);
  return w.WriteGltfSceneToFile(&m, path, false, true, !glb, glb);
}

}  // namespace emoface::testing
