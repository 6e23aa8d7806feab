#include "emoface/facemesh/gltf.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

class Gltf : public testing::TempDirTest {};

TEST_F(Gltf, WritesMorphTargetAnimation) {
  const Mesh m = testing::tetrahedron();
  Vertices moved = m.vertices;
  moved(3, 2) = 2.0;
  write_animated_gltf(path("a.gltf"), m, {m.vertices, moved, m.vertices}, {0.0, 0.5, 1.0});
  const auto doc = core::read_json_file(path("a.gltf"));
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  ASSERT_EQ(doc["meshes"][0]["primitives"][0]["targets"].size(), 3u);
  ASSERT_EQ(doc["animations"].size(), 1u);
  EXPECT_EQ(doc["animations"][0]["channels"][0]["target"]["path"], "weights");
  // target 1 moves vertex 3 by +1 in z: max of its POSITION accessor is (0, 0, 1)
  const int acc = doc["meshes"][0]["primitives"][0]["targets"][1]["POSITION"];
  EXPECT_DOUBLE_EQ(doc["accessors"][acc]["max"][2].get<double>(), 1.0);
  write_animated_gltf(path("a.glb"), m, {m.vertices}, {0.0});
  EXPECT_EQ(core::read_file(path("a.glb")).substr(0, 4), "glTF");
}

TEST_F(Gltf, RejectsBadInput) {
  const Mesh m = testing::tetrahedron();
  EXPECT_THROW(write_animated_gltf(path("a.gltf"), m, {}, {}), InvalidInput);
  EXPECT_THROW(write_animated_gltf(path("a.gltf"), m, {m.vertices}, {0.0, 1.0}), InvalidInput);
  EXPECT_THROW(write_animated_gltf(path("a.gltf"), m, {m.vertices, m.vertices}, {1.0, 0.5}), InvalidInput);
  EXPECT_THROW(write_animated_gltf(path("a.gltf"), m, {Vertices::Zero(2, 3)}, {0.0}), InvalidInput);
  EXPECT_THROW(write_animated_gltf(path("a.obj"), m, {m.vertices}, {0.0}), InvalidInput);
}

}  // namespace
}  // namespace emoface::facemesh
