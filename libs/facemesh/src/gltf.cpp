#include "emoface/facemesh/gltf.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>

#include <tiny_gltf.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"
#include "gltf_buffers.hpp"

namespace emoface::facemesh {
namespace {

using detail::add_accessor;
using detail::add_view;

int add_positions(tinygltf::Model& model, const std::vector<float>& xyz) {
  std::vector<double> lo(3, 1e300), hi(3, -1e300);
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], static_cast<double>(xyz[i]));
    hi[i % 3] = std::max(hi[i % 3], static_cast<double>(xyz[i]));
  }
  const int view = add_view(model, xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  return add_accessor(model, view, TINYGLTF_COMPONENT_TYPE_FLOAT, xyz.size() / 3, TINYGLTF_TYPE_VEC3, lo, hi);
}

}  // namespace

void write_animated_gltf(const std::string& path, const Mesh& neutral, const std::vector<Vertices>& frames,
                         const std::vector<double>& times) {
  if (frames.empty()) throw InvalidInput("write_animated_gltf: no frames");
  if (times.size() != frames.size()) throw InvalidInput("write_animated_gltf: one time per frame needed");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].rows() != neutral.vertices.rows()) throw InvalidInput("write_animated_gltf: frame vertex count differs from the mesh");
    if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1]))) throw InvalidInput("write_animated_gltf: times must be finite and increasing");
  }
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".gltf" && ext != ".glb") throw InvalidInput("write_animated_gltf: use a .gltf or .glb file name");
  const std::size_t nv = neutral.vertex_count();
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = emoface::kGenerator;
  model.buffers.resize(1);
  std::vector<float> base(nv * 3);
  for (std::size_t v = 0; v < nv; ++v) {
    for (int k = 0; k < 3; ++k) base[v * 3 + k] = static_cast<float>(neutral.vertices(static_cast<long>(v), k));
  }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = add_positions(model, base);
  std::vector<std::uint32_t> idx;
  for (long f = 0; f < neutral.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) idx.push_back(static_cast<std::uint32_t>(neutral.faces(f, k)));
  }
  const int iv = add_view(model, idx.data(), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  prim.indices = add_accessor(model, iv, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, idx.size(), TINYGLTF_TYPE_SCALAR);
  for (const auto& frame : frames) {
    std::vector<float> delta(nv * 3);
    for (std::size_t v = 0; v < nv; ++v) {
      for (int k = 0; k < 3; ++k) delta[v * 3 + k] = static_cast<float>(frame(static_cast<long>(v), k)) - base[v * 3 + k];
    }
    prim.targets.push_back({{"POSITION", add_positions(model, delta)}});
  }
  tinygltf::Mesh mesh;
  mesh.name = "face";
  mesh.primitives.push_back(prim);
  mesh.weights.assign(frames.size(), 0.0);
  mesh.weights[0] = 1.0;
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = "face";
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  if (frames.size() > 1) {
    std::vector<float> t(times.begin(), times.end());
    std::vector<float> w(frames.size() * frames.size(), 0.0f);
    for (std::size_t i = 0; i < frames.size(); ++i) w[i * frames.size() + i] = 1.0f;
    const int tv = add_view(model, t.data(), t.size() * 4, 0);
    const int ta = add_accessor(model, tv, TINYGLTF_COMPONENT_TYPE_FLOAT, t.size(), TINYGLTF_TYPE_SCALAR,
                                {static_cast<double>(t.front())}, {static_cast<double>(t.back())});
    const int wv = add_view(model, w.data(), w.size() * 4, 0);
    const int wa = add_accessor(model, wv, TINYGLTF_COMPONENT_TYPE_FLOAT, w.size(), TINYGLTF_TYPE_SCALAR);
    tinygltf::Animation anim;
    anim.name = "expression";
    tinygltf::AnimationSampler sampler;
    sampler.input = ta;
    sampler.output = wa;
    sampler.interpolation = "LINEAR";
    anim.samplers.push_back(sampler);
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = 0;
    channel.target_path = "weights";
    anim.channels.push_back(channel);
    model.animations.push_back(anim);
  }
  model.buffers[0].uri.clear();
  const std::string tmp = path + ".part" + ext;
  tinygltf::TinyGLTF writer;
  const bool binary = ext == ".glb";
  if (!writer.WriteGltfSceneToFile(&model, tmp, true, true, !binary, binary)) {
    std::filesystem::remove(tmp);
    throw IoError(path + ": could not write glTF");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp);
    throw IoError(path + ": " + ec.message());
  }
}

}  // namespace emoface::facemesh
