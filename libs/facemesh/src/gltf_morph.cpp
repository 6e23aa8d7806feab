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
  static void bounds(const std::vector<float>& xyz, std::vector<double>& lo, std::vector<double>& hi) {
    lo.assign(3, 0.0);
    hi.assign(3, 0.0);
    for (int k = 0; k < 3; ++k) {
      lo[k] = 1e300;
      hi[k] = -1e300;
    }
    for (std::size_t i = 0; i < xyz.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], static_cast<double>(xyz[i]));
      hi[i % 3] = std::max(hi[i % 3], static_cast<double>(xyz[i]));
    }
  }
  int vec3(const std::vector<float>& xyz, bool with_bounds) {
    std::vector<double> lo, hi;
    if (with_bounds) bounds(xyz, lo, hi);
    const int v = view(xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    return accessor(v, TINYGLTF_COMPONENT_TYPE_FLOAT, xyz.size() / 3, TINYGLTF_TYPE_VEC3, lo, hi);
  }
  // A morph-target delta: sparse (indices + values of the non-zero rows) when that is smaller.
  int delta(const std::vector<float>& xyz, double eps, bool with_bounds, MorphGltfReport& report) {
    const std::size_t n = xyz.size() / 3;
    std::vector<std::uint32_t> idx;
    std::vector<float> vals;
    for (std::size_t v = 0; v < n; ++v) {
      const float* p = &xyz[v * 3];
      if (std::fabs(p[0]) > eps || std::fabs(p[1]) > eps || std::fabs(p[2]) > eps) {
        idx.push_back(static_cast<std::uint32_t>(v));
        vals.insert(vals.end(), p, p + 3);
      }
    }
    // glTF: a sparse accessor needs count ≥ 1; an all-zero delta stores one zero row
    if (idx.empty()) {
      idx.push_back(0);
      vals.assign(3, 0.0f);
    }
    const bool u16 = n <= 65535;
    const std::size_t sparse_bytes = idx.size() * (u16 ? 2 : 4) + vals.size() * 4 + 8;
    if (sparse_bytes >= xyz.size() * 4) {
      ++report.dense_accessors;
      return vec3(xyz, with_bounds);
    }
    ++report.sparse_accessors;
    std::vector<double> lo, hi;
    if (with_bounds) {
      // bounds over all n rows: the implicit zeros count too
      std::vector<float> with_zero = vals;
      if (idx.size() < n) with_zero.insert(with_zero.end(), {0.0f, 0.0f, 0.0f});
      bounds(with_zero, lo, hi);
    }
    int iv;
    if (u16) {
      std::vector<std::uint16_t> i16(idx.begin(), idx.end());
      iv = view(i16.data(), i16.size() * 2, 0);
    } else {
      iv = view(idx.data(), idx.size() * 4, 0);
    }
    const int vv = view(vals.data(), vals.size() * 4, 0);
    const int a = accessor(-1, TINYGLTF_COMPONENT_TYPE_FLOAT, n, TINYGLTF_TYPE_VEC3, lo, hi);
    auto& acc = model.accessors[static_cast<std::size_t>(a)];
    acc.sparse.isSparse = true;
    acc.sparse.count = static_cast<int>(idx.size());
    acc.sparse.indices.bufferView = iv;
    acc.sparse.indices.byteOffset = 0;
    acc.sparse.indices.componentType =
        u16 ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    acc.sparse.values.bufferView = vv;
    acc.sparse.values.byteOffset = 0;
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
  for (const auto& a : animations) {
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
    if (targets.empty() && a.head_rotations.empty())
      throw InvalidInput("write_morph_gltf: animation '" + a.name + "' animates nothing");
  }

  Builder b;
  MorphGltfReport report;
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = b.vec3(to_floats(neutral.vertices), true);
  if (options.normals) prim.attributes["NORMAL"] = b.vec3(to_floats(vertex_normals(neutral.vertices, neutral.faces)), false);
  if (!options.colors.empty()) {
    std::vector<float> rgb;
    for (const auto& c : options.colors) {
      for (int k = 0; k < 3; ++k) rgb.push_back(std::clamp(c[k], 0.0f, 1.0f));
    }
    prim.attributes["COLOR_0"] = b.vec3(rgb, false);
  }
  std::vector<std::uint32_t> idx;
  for (long f = 0; f < neutral.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) idx.push_back(static_cast<std::uint32_t>(neutral.faces(f, k)));
  }
  const int iv = b.view(idx.data(), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  prim.indices = b.accessor(iv, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, idx.size(), TINYGLTF_TYPE_SCALAR);
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
    if (!targets.empty()) {
      std::vector<float> w;
      w.reserve(a.times.size() * targets.size());
      for (const auto& key : a.weights) {
        for (double x : key) w.push_back(static_cast<float>(x));
      }
      const int wv = b.view(w.data(), w.size() * 4, 0);
      tinygltf::AnimationSampler s;
      s.input = ta;
      s.output = b.accessor(wv, TINYGLTF_COMPONENT_TYPE_FLOAT, w.size(), TINYGLTF_TYPE_SCALAR);
      s.interpolation = "LINEAR";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel c;
      c.sampler = static_cast<int>(anim.samplers.size()) - 1;
      c.target_node = 1;
      c.target_path = "weights";
      anim.channels.push_back(c);
    }
    if (!a.head_rotations.empty()) {
      std::vector<float> q;
      for (const auto& r : a.head_rotations) {
        const Eigen::Quaterniond n = r.normalized();
        q.insert(q.end(), {static_cast<float>(n.x()), static_cast<float>(n.y()),
                           static_cast<float>(n.z()), static_cast<float>(n.w())});
      }
      const int qv = b.view(q.data(), q.size() * 4, 0);
      tinygltf::AnimationSampler s;
      s.input = ta;
      s.output = b.accessor(qv, TINYGLTF_COMPONENT_TYPE_FLOAT, a.head_rotations.size(), TINYGLTF_TYPE_VEC4);
      s.interpolation = "LINEAR";
      anim.samplers.push_back(s);
      tinygltf::AnimationChannel c;
      c.sampler = static_cast<int>(anim.samplers.size()) - 1;
      c.target_node = 0;
      c.target_path = "rotation";
      anim.channels.push_back(c);
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
