#include "emoface/facemesh/gltf_morph.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

#include <tiny_gltf.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"
#include "gltf_buffers.hpp"

namespace emoface::facemesh {
namespace {

class Builder {
 public:
  tinygltf::Model model;
  Builder() {
    model.asset.version = "2.0";
    model.asset.generator = emoface::kGenerator;
    model.buffers.resize(1);
  }
  int view(const void* data, std::size_t bytes, int target) {
    return detail::add_view(model, data, bytes, target);
  }
  int accessor(int view, int component, std::size_t count, int type, std::vector<double> min = {},
               std::vector<double> max = {}) {
    return detail::add_accessor(model, view, component, count, type, std::move(min), std::move(max));
  }
  int vec3(const std::vector<float>& xyz, bool with_bounds) {
    return detail::add_vec3(model, xyz, with_bounds);
  }
  // A morph-target delta: sparse (indices + values of the non-zero rows) when that is smaller.
  int delta(const std::vector<float>& xyz, double eps, bool with_bounds, MorphGltfReport& report) {
    bool sparse = false;
    const int a = detail::add_delta(model, xyz, eps, with_bounds, true, sparse);
    ++(sparse ? report.sparse_accessors : report.dense_accessors);
    return a;
  }
};

std::vector<float> to_floats(const Vertices& v) {
  std::vector<float> out(static_cast<std::size_t>(v.rows()) * 3);
  for (long i = 0; i < v.rows(); ++i) {
    for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(i) * 3 + k] = static_cast<float>(v(i, k));
  }
  return out;
}

// A triangle primitive: POSITION (`positions`), NORMAL from `normal_source` (same rows, its own
// frame: normals do not change under the translation to a part's pivot), COLOR_0, indices.
tinygltf::Primitive triangle_primitive(Builder& b, const Vertices& positions,
                                       const Vertices& normal_source, const Faces& faces,
                                       const std::vector<Eigen::Vector3f>& colors, bool normals) {
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = b.vec3(to_floats(positions), true);
  if (normals) prim.attributes["NORMAL"] = b.vec3(to_floats(vertex_normals(normal_source, faces)), false);
  if (!colors.empty()) {
    std::vector<float> rgb;
    for (const auto& c : colors) {
      for (int k = 0; k < 3; ++k) rgb.push_back(std::clamp(c[k], 0.0f, 1.0f));
    }
    prim.attributes["COLOR_0"] = b.vec3(rgb, false);
  }
  std::vector<std::uint32_t> idx;
  for (long f = 0; f < faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) idx.push_back(static_cast<std::uint32_t>(faces(f, k)));
  }
  const int iv = b.view(idx.data(), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  prim.indices = b.accessor(iv, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, idx.size(), TINYGLTF_TYPE_SCALAR);
  return prim;
}

}  // namespace

void MorphGltfOptions::validate() const {
  if (!(sparse_epsilon >= 0.0) || !std::isfinite(sparse_epsilon))
    throw InvalidInput("MorphGltfOptions: sparse_epsilon must be >= 0");
  if (!head_pivot.allFinite()) throw InvalidInput("MorphGltfOptions: head_pivot must be finite");
  if (name.empty()) throw InvalidInput("MorphGltfOptions: empty name");
}

MorphGltfReport write_morph_gltf(const std::string& path, const Mesh& neutral,
                                 const std::vector<MorphTarget>& targets,
                                 const std::vector<WeightAnimation>& animations,
                                 const MorphGltfOptions& options) {
  options.validate();
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".gltf" && ext != ".glb") throw InvalidInput("write_morph_gltf: use a .gltf or .glb file name");
  const long nv = neutral.vertices.rows();
  if (nv == 0 || neutral.faces.rows() == 0) throw InvalidInput("write_morph_gltf: empty mesh");
  if (!options.colors.empty() && options.colors.size() != static_cast<std::size_t>(nv))
    throw InvalidInput("write_morph_gltf: one colour per vertex");
  std::set<std::string> names;
  for (const auto& t : targets) {
    if (t.name.empty() || !names.insert(t.name).second)
      throw InvalidInput("write_morph_gltf: target names must be unique and non-empty ('" + t.name + "')");
    if (t.position_deltas.rows() != nv) throw InvalidInput("write_morph_gltf: target '" + t.name + "' has the wrong vertex count");
    if (t.normal_deltas.rows() != 0 && t.normal_deltas.rows() != nv)
      throw InvalidInput("write_morph_gltf: normal deltas of '" + t.name + "' have the wrong vertex count");
    if (!t.position_deltas.allFinite() || !t.normal_deltas.allFinite())
      throw InvalidInput("write_morph_gltf: target '" + t.name + "' is not finite");
  }
  std::set<std::string> node_names{"head", options.name};
  for (const auto& part : options.parts) {
    if (part.name.empty() || !node_names.insert(part.name).second)
      throw InvalidInput(
          "write_morph_gltf: part node names must be unique and not 'head' or the mesh name ('" +
          part.name + "')");
    if (!part.pivot.allFinite())
      throw InvalidInput("write_morph_gltf: part '" + part.name + "': pivot not finite");
    if (part.meshes.empty())
      throw InvalidInput("write_morph_gltf: part '" + part.name + "' has no mesh");
    for (const auto& pm : part.meshes) {
      const std::string who = "write_morph_gltf: part mesh '" + pm.name + "'";
      if (pm.name.empty() || !node_names.insert(pm.name).second)
        throw InvalidInput(who + ": names must be unique and non-empty");
      const long n = pm.mesh.vertices.rows();
      if (n == 0 || pm.mesh.faces.rows() == 0) throw InvalidInput(who + ": empty mesh");
      if (!pm.mesh.vertices.allFinite()) throw InvalidInput(who + ": vertices not finite");
      if (pm.mesh.faces.size() > 0 &&
          (pm.mesh.faces.minCoeff() < 0 || pm.mesh.faces.maxCoeff() >= n))
        throw InvalidInput(who + ": face index out of range");
      if (!pm.colors.empty() && pm.colors.size() != static_cast<std::size_t>(n))
        throw InvalidInput(who + ": one colour per vertex");
    }
  }
  for (const auto& a : animations) {
    if (!a.part_rotations.empty()) {
      if (a.part_rotations.size() != options.parts.size())
        throw InvalidInput("write_morph_gltf: animation '" + a.name +
                           "': one rotation list per part");
      for (const auto& r : a.part_rotations) {
        if (!r.empty() && r.size() != a.times.size())
          throw InvalidInput("write_morph_gltf: animation '" + a.name +
                             "': a part needs one rotation per key");
        for (const auto& q : r) {
          if (!q.coeffs().allFinite() || q.norm() < 1e-12)
            throw InvalidInput("write_morph_gltf: animation '" + a.name +
                               "': part rotation not a finite rotation");
        }
      }
    }
    if (a.times.empty() || a.weights.size() != a.times.size())
      throw InvalidInput("write_morph_gltf: animation '" + a.name + "' needs one weight vector per key");
    if (!a.head_rotations.empty() && a.head_rotations.size() != a.times.size())
      throw InvalidInput("write_morph_gltf: animation '" + a.name + "': one head rotation per key");
    for (std::size_t i = 0; i < a.times.size(); ++i) {
      if (!std::isfinite(a.times[i]) || a.times[i] < 0.0 || (i > 0 && !(a.times[i] > a.times[i - 1])))
        throw InvalidInput("write_morph_gltf: animation '" + a.name + "': times must be >= 0 and increasing");
      if (a.weights[i].size() != targets.size())
        throw InvalidInput("write_morph_gltf: animation '" + a.name + "': one weight per target");
      for (double w : a.weights[i]) {
        if (!std::isfinite(w)) throw InvalidInput("write_morph_gltf: animation '" + a.name + "': weight not finite");
      }
    }
    bool parts_move = false;
    for (const auto& r : a.part_rotations) parts_move = parts_move || !r.empty();
    if (targets.empty() && a.head_rotations.empty() && !parts_move)
      throw InvalidInput("write_morph_gltf: animation '" + a.name + "' animates nothing");
  }

  Builder b;
  MorphGltfReport report;
  tinygltf::Primitive prim = triangle_primitive(b, neutral.vertices, neutral.vertices, neutral.faces,
                                                options.colors, options.normals);
  for (const auto& t : targets) {
    std::map<std::string, int> attrs;
    attrs["POSITION"] = b.delta(to_floats(t.position_deltas), options.sparse_epsilon, true, report);
    if (options.normals) {
      const Vertices zero = Vertices::Zero(nv, 3);
      attrs["NORMAL"] = b.delta(to_floats(t.normal_deltas.rows() ? t.normal_deltas : zero),
                                options.sparse_epsilon, false, report);
    }
    prim.targets.push_back(attrs);
  }
  // PBR material: the vertex colours (COLOR_0) multiply a white base colour; skin-like roughness.
  tinygltf::Material mat;
  mat.name = options.name + "_skin";
  mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 0.6;
  mat.doubleSided = true;  // the open mouth shows the inside of the lips
  b.model.materials.push_back(mat);
  prim.material = 0;

  tinygltf::Mesh mesh;
  mesh.name = options.name;
  mesh.primitives.push_back(prim);
  if (!targets.empty()) {
    mesh.weights.assign(targets.size(), 0.0);
    tinygltf::Value::Array tn;
    for (const auto& t : targets) tn.emplace_back(t.name);
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(tn);
    mesh.extras = tinygltf::Value(extras);
  }
  b.model.meshes.push_back(mesh);
  // nodes: "head" (at the pivot, rotated by the animation) → the mesh node (offset back by −pivot)
  tinygltf::Node head;
  head.name = "head";
  head.translation = {options.head_pivot.x(), options.head_pivot.y(), options.head_pivot.z()};
  head.children = {1};
  tinygltf::Node face;
  face.name = options.name;
  face.mesh = 0;
  face.translation = {-options.head_pivot.x(), -options.head_pivot.y(), -options.head_pivot.z()};
  b.model.nodes = {head, face};
  // rigid parts: a transform node at the pivot (relative to the head pivot), mesh nodes below it
  std::vector<int> part_nodes;
  for (const auto& part : options.parts) {
    tinygltf::Node pn;
    pn.name = part.name;
    const Eigen::Vector3d at = part.pivot - options.head_pivot;
    pn.translation = {at.x(), at.y(), at.z()};
    const int pi = static_cast<int>(b.model.nodes.size());
    b.model.nodes.push_back(pn);
    part_nodes.push_back(pi);
    b.model.nodes[0].children.push_back(pi);
    for (const auto& pm : part.meshes) {
      Vertices local = pm.mesh.vertices;
      local.rowwise() -= part.pivot.transpose();
      tinygltf::Primitive pp = triangle_primitive(b, local, pm.mesh.vertices, pm.mesh.faces,
                                                  pm.colors, options.normals);
      pp.material = 0;
      tinygltf::Mesh m;
      m.name = pm.name;
      m.primitives.push_back(pp);
      b.model.meshes.push_back(m);
      tinygltf::Node mn;
      mn.name = pm.name;
      mn.mesh = static_cast<int>(b.model.meshes.size()) - 1;
      b.model.nodes[static_cast<std::size_t>(pi)].children.push_back(
          static_cast<int>(b.model.nodes.size()));
      b.model.nodes.push_back(mn);
    }
  }
  tinygltf::Scene scene;
  scene.name = "scene";
  scene.nodes = {0};
  b.model.scenes.push_back(scene);
  b.model.defaultScene = 0;

  for (const auto& a : animations) {
    tinygltf::Animation anim;
    anim.name = a.name;
    std::vector<float> t(a.times.begin(), a.times.end());
    const int tv = b.view(t.data(), t.size() * 4, 0);
    const int ta = b.accessor(tv, TINYGLTF_COMPONENT_TYPE_FLOAT, t.size(), TINYGLTF_TYPE_SCALAR,
                              {static_cast<double>(t.front())}, {static_cast<double>(t.back())});
    // One LINEAR sampler over the key times and the channel that plays it on `node`'s `path`.
    const auto add_channel = [&](const std::vector<float>& values, std::size_t count, int type,
                                 int node, const char* channel_path) {
      tinygltf::AnimationSampler s;
      s.input = ta;
      s.output = b.accessor(b.view(values.data(), values.size() * 4, 0),
                            TINYGLTF_COMPONENT_TYPE_FLOAT, count, type);
      s.interpolation = "LINEAR";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel c;
      c.sampler = static_cast<int>(anim.samplers.size()) - 1;
      c.target_node = node;
      c.target_path = channel_path;
      anim.channels.push_back(c);
    };
    const auto quaternions = [](const std::vector<Eigen::Quaterniond>& rotations) {
      std::vector<float> q;
      for (const auto& r : rotations) {
        const Eigen::Quaterniond n = r.normalized();
        q.insert(q.end(), {static_cast<float>(n.x()), static_cast<float>(n.y()),
                           static_cast<float>(n.z()), static_cast<float>(n.w())});
      }
      return q;
    };
    if (!targets.empty()) {
      std::vector<float> w;
      w.reserve(a.times.size() * targets.size());
      for (const auto& key : a.weights) {
        for (double x : key) w.push_back(static_cast<float>(x));
      }
      add_channel(w, w.size(), TINYGLTF_TYPE_SCALAR, 1, "weights");
    }
    if (!a.head_rotations.empty())
      add_channel(quaternions(a.head_rotations), a.head_rotations.size(), TINYGLTF_TYPE_VEC4, 0,
                  "rotation");
    for (std::size_t p = 0; p < a.part_rotations.size(); ++p) {
      if (a.part_rotations[p].empty()) continue;
      add_channel(quaternions(a.part_rotations[p]), a.part_rotations[p].size(), TINYGLTF_TYPE_VEC4,
                  part_nodes[p], "rotation");
    }
    b.model.animations.push_back(anim);
  }

  b.model.buffers[0].uri.clear();
  const std::string tmp = path + ".part" + ext;
  tinygltf::TinyGLTF writer;
  const bool binary = ext == ".glb";
  if (!writer.WriteGltfSceneToFile(&b.model, tmp, true, true, !binary, binary)) {
    std::filesystem::remove(tmp);
    throw IoError(path + ": could not write glTF");
  }
  std::error_code ec;
  report.bytes = static_cast<std::size_t>(std::filesystem::file_size(tmp, ec));
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw IoError(path + ": " + ec.message());
  }
  return report;
}

}  // namespace emoface::facemesh
