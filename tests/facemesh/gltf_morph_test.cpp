#include "emoface/facemesh/gltf_morph.hpp"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

class GltfMorph : public testing::TempDirTest {};

std::vector<MorphTarget> two_targets(const Mesh& m) {
  MorphTarget lift{"lift", Vertices::Zero(m.vertices.rows(), 3), Vertices::Zero(m.vertices.rows(), 3)};
  lift.position_deltas(3, 2) = 1.0;
  MorphTarget none{"none", Vertices::Zero(m.vertices.rows(), 3), {}};
  return {lift, none};
}

TEST_F(GltfMorph, NamedSparseTargetsAndWeightAnimation) {
  const Mesh m = testing::tetrahedron();
  WeightAnimation a;
  a.name = "smile";
  a.times = {0.0, 0.5, 1.0};
  a.weights = {{0.0, 0.0}, {1.0, 0.0}, {0.25, 1.0}};
  a.head_rotations = {Eigen::Quaterniond::Identity(),
                      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())),
                      Eigen::Quaterniond::Identity()};
  MorphGltfOptions o;
  o.head_pivot = Eigen::Vector3d(0.0, -0.1, 0.0);
  o.colors.assign(4, Eigen::Vector3f(0.8f, 0.6f, 0.5f));
  const auto report = write_morph_gltf(path("m.gltf"), m, two_targets(m), {a}, o);
  EXPECT_EQ(report.sparse_accessors, 4u);  // two targets × (POSITION, NORMAL), all smaller sparse
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadASCIIFromFile(&model, &err, &warn, path("m.gltf"))) << err;
  const auto& mesh = model.meshes[0];
  ASSERT_TRUE(mesh.extras.Has("targetNames"));
  EXPECT_EQ(mesh.extras.Get("targetNames").Get(0).Get<std::string>(), "lift");
  EXPECT_EQ(mesh.extras.Get("targetNames").Get(1).Get<std::string>(), "none");
  const auto& prim = mesh.primitives[0];
  ASSERT_EQ(prim.targets.size(), 2u);
  EXPECT_TRUE(prim.attributes.count("COLOR_0"));
  EXPECT_TRUE(prim.attributes.count("NORMAL"));
  // target "lift": sparse, one entry, vertex 3 by (0, 0, 1); bounds include the implicit zeros
  const auto& acc = model.accessors[static_cast<std::size_t>(prim.targets[0].at("POSITION"))];
  ASSERT_TRUE(acc.sparse.isSparse);
  EXPECT_EQ(acc.sparse.count, 1);
  EXPECT_EQ(acc.count, 4u);
  EXPECT_EQ(acc.maxValues, (std::vector<double>{0, 0, 1}));
  EXPECT_EQ(acc.minValues, (std::vector<double>{0, 0, 0}));
  const auto& iv = model.bufferViews[static_cast<std::size_t>(acc.sparse.indices.bufferView)];
  const auto& vv = model.bufferViews[static_cast<std::size_t>(acc.sparse.values.bufferView)];
  std::uint16_t index = 0;
  float value[3];
  std::memcpy(&index, model.buffers[0].data.data() + iv.byteOffset, 2);
  std::memcpy(value, model.buffers[0].data.data() + vv.byteOffset, 12);
  EXPECT_EQ(index, 3);
  EXPECT_EQ(value[2], 1.0f);
  // nodes: head at the pivot, the mesh node offset back
  EXPECT_EQ(model.nodes[0].translation, (std::vector<double>{0, -0.1, 0}));
  EXPECT_EQ(model.nodes[1].translation, (std::vector<double>{-0.0, 0.1, -0.0}));
  // animation: weights (3 keys × 2 targets) on the mesh node, rotation on the head node
  const auto& an = model.animations[0];
  EXPECT_EQ(an.name, "smile");
  ASSERT_EQ(an.channels.size(), 2u);
  EXPECT_EQ(an.channels[0].target_path, "weights");
  EXPECT_EQ(an.channels[0].target_node, 1);
  EXPECT_EQ(an.channels[1].target_path, "rotation");
  EXPECT_EQ(an.channels[1].target_node, 0);
  EXPECT_EQ(model.accessors[static_cast<std::size_t>(an.samplers[0].output)].count, 6u);
  const auto& q = model.accessors[static_cast<std::size_t>(an.samplers[1].output)];
  const auto& qv = model.bufferViews[static_cast<std::size_t>(q.bufferView)];
  float quat[4];
  std::memcpy(quat, model.buffers[0].data.data() + qv.byteOffset + 16, 16);
  EXPECT_NEAR(quat[1], std::sin(0.15), 1e-6);  // (x, y, z, w) of 0.3 rad about y
  EXPECT_NEAR(quat[3], std::cos(0.15), 1e-6);
  write_morph_gltf(path("m.glb"), m, two_targets(m), {a}, o);
  EXPECT_EQ(core::read_file(path("m.glb")).substr(0, 4), "glTF");
}

// Rigid parts: a transform node at the pivot under "head", mesh nodes below it holding the vertices
// relative to the pivot (so the node's rotation turns them about the pivot), a rotation channel.
TEST_F(GltfMorph, RigidPartsAsNodesWithRotationChannels) {
  const Mesh m = testing::tetrahedron();
  MorphGltfOptions o;
  o.head_pivot = Eigen::Vector3d(0.0, -0.1, 0.0);
  NodePart eye;
  eye.name = "eye_r";
  eye.pivot = Eigen::Vector3d(2.0, 0.5, 0.25);
  Mesh ball = testing::tetrahedron();
  ball.vertices.rowwise() += Eigen::RowVector3d(2.0, 0.0, 0.0);
  eye.meshes.push_back(
      {"eyeball_r", ball, std::vector<Eigen::Vector3f>(4, Eigen::Vector3f(1, 1, 1))});
  o.parts = {eye};
  WeightAnimation a;
  a.times = {0.0, 1.0};
  a.weights = {{0.0, 0.0}, {1.0, 0.0}};
  a.part_rotations = {{Eigen::Quaterniond::Identity(),
                       Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitY()))}};
  write_morph_gltf(path("p.gltf"), m, two_targets(m), {a}, o);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadASCIIFromFile(&model, &err, &warn, path("p.gltf"))) << err;
  ASSERT_EQ(model.nodes.size(), 4u);  // head, face, eye_r, eyeball_r
  EXPECT_EQ(model.nodes[0].children, (std::vector<int>{1, 2}));
  EXPECT_EQ(model.nodes[2].name, "eye_r");
  EXPECT_EQ(model.nodes[2].children, (std::vector<int>{3}));
  // pivot − head pivot = (2, 0.6, 0.25)
  EXPECT_EQ(model.nodes[2].translation, (std::vector<double>{2.0, 0.6, 0.25}));
  EXPECT_EQ(model.nodes[3].name, "eyeball_r");
  ASSERT_EQ(model.nodes[3].mesh, 1);
  const auto& prim = model.meshes[1].primitives[0];
  EXPECT_TRUE(prim.targets.empty());
  EXPECT_TRUE(prim.attributes.count("COLOR_0"));
  const auto& pa = model.accessors[static_cast<std::size_t>(prim.attributes.at("POSITION"))];
  // vertex 3 of the ball (2, 0, 1) relative to the pivot (2, 0.5, 0.25): (0, −0.5, 0.75)
  const auto& pv = model.bufferViews[static_cast<std::size_t>(pa.bufferView)];
  float p3[3];
  std::memcpy(p3, model.buffers[0].data.data() + pv.byteOffset + pa.byteOffset + 36, 12);
  EXPECT_EQ(p3[0], 0.0f);
  EXPECT_EQ(p3[1], -0.5f);
  EXPECT_EQ(p3[2], 0.75f);
  EXPECT_EQ(pa.minValues, (std::vector<double>{0, -0.5, -0.25}));
  const auto& an = model.animations[0];
  ASSERT_EQ(an.channels.size(), 2u);  // weights + the eye (no head rotation given)
  EXPECT_EQ(an.channels[1].target_node, 2);
  EXPECT_EQ(an.channels[1].target_path, "rotation");
  const auto& q = model.accessors[static_cast<std::size_t>(an.samplers[1].output)];
  const auto& qv = model.bufferViews[static_cast<std::size_t>(q.bufferView)];
  float quat[4];
  std::memcpy(quat, model.buffers[0].data.data() + qv.byteOffset + 16, 16);
  EXPECT_NEAR(quat[1], std::sin(0.2), 1e-6);
  EXPECT_NEAR(quat[3], std::cos(0.2), 1e-6);

  // bad parts: a name clash, no mesh, a bad face index, the wrong number of rotations
  auto bad = o;
  bad.parts[0].name = "head";
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, two_targets(m), {a}, bad), InvalidInput);
  bad = o;
  bad.parts[0].meshes[0].name = "face";
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, two_targets(m), {a}, bad), InvalidInput);
  bad = o;
  bad.parts[0].meshes.clear();
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, two_targets(m), {a}, bad), InvalidInput);
  bad = o;
  bad.parts[0].meshes[0].mesh.faces(0, 0) = 4;
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, two_targets(m), {a}, bad), InvalidInput);
  bad = o;
  bad.parts[0].pivot.x() = std::nan("");
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, two_targets(m), {a}, bad), InvalidInput);
  auto b = a;
  b.part_rotations[0].pop_back();
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, two_targets(m), {b}, o), InvalidInput);
  b = a;
  b.part_rotations.clear();
  b.part_rotations.resize(2);
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, two_targets(m), {b}, o), InvalidInput);
  b = a;
  b.part_rotations[0][1] = Eigen::Quaterniond(std::nan(""), 0, 0, 0);
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, two_targets(m), {b}, o), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(path("x.gltf")));
}

TEST_F(GltfMorph, BadInputs) {
  const Mesh m = testing::tetrahedron();
  auto t = two_targets(m);
  WeightAnimation a;
  a.times = {0.0};
  a.weights = {{0.0, 0.0}};
  EXPECT_THROW(write_morph_gltf(path("x.obj"), m, t, {a}), InvalidInput);
  auto dup = t;
  dup[1].name = "lift";
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, dup, {a}), InvalidInput);
  auto empty = t;
  empty[0].name.clear();
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, empty, {a}), InvalidInput);
  auto rows = t;
  rows[0].position_deltas = Vertices::Zero(3, 3);
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, rows, {a}), InvalidInput);
  auto nan = t;
  nan[0].position_deltas(0, 0) = std::nan("");
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, nan, {a}), InvalidInput);
  WeightAnimation b = a;
  b.times = {0.0, 0.0};
  b.weights = {{0, 0}, {0, 0}};
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, t, {b}), InvalidInput);
  b = a;
  b.weights = {{0.0}};
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, t, {b}), InvalidInput);
  b = a;
  b.weights = {{std::nan(""), 0.0}};
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, t, {b}), InvalidInput);
  MorphGltfOptions o;
  o.colors.assign(2, Eigen::Vector3f::Zero());
  EXPECT_THROW(write_morph_gltf(path("x.gltf"), m, t, {a}, o), InvalidInput);
  EXPECT_FALSE(std::filesystem::exists(path("x.gltf")));
}

}  // namespace
}  // namespace emoface::facemesh
