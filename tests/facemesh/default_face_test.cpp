#include "emoface/facemesh/default_face.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <unordered_set>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/io.hpp"

namespace emoface::facemesh {
namespace {

const Face& face() {
  static const Face f = make_generic_face();
  return f;
}

TEST(DefaultFace, SizeAndValidity) {
  const auto& f = face();
  EXPECT_GE(f.mesh.vertex_count(), 2000u);
  EXPECT_LE(f.mesh.vertex_count(), 6000u);
  EXPECT_NO_THROW(validate_mesh(f.mesh, "default"));
  EXPECT_NO_THROW(validate_rig(f.rig, "default"));
  EXPECT_EQ(f.rig.vertex_count, f.mesh.vertex_count());
}

TEST(DefaultFace, IsClosed) {
  // Every directed edge has its reverse: the head (with socket and mouth caps) and the eyeballs are
  // closed, consistently oriented surfaces.
  std::unordered_set<std::uint64_t> edges;
  const auto& F = face().mesh.faces;
  auto key = [](int a, int b) { return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b); };
  for (long f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) edges.insert(key(F(f, k), F(f, (k + 1) % 3)));
  }
  std::size_t open = 0;
  for (long f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) open += edges.count(key(F(f, (k + 1) % 3), F(f, k))) ? 0 : 1;
  }
  EXPECT_EQ(open, 0u);
}

TEST(DefaultFace, OutwardOrientation) {
  // Signed volume of the closed mesh is positive (counter-clockwise faces seen from outside).
  const auto& m = face().mesh;
  double volume = 0.0;
  for (long f = 0; f < m.faces.rows(); ++f) {
    const Eigen::Vector3d a = m.vertices.row(m.faces(f, 0)), b = m.vertices.row(m.faces(f, 1)), c = m.vertices.row(m.faces(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  EXPECT_GT(volume, 0.001);  // a head is a few litres
  EXPECT_LT(volume, 0.01);
}

TEST(DefaultFace, RegionsSidesAndLandmarks) {
  const auto& f = face();
  const auto regions = region_vertices(f.rig);
  for (int r = 0; r < kRegionCount; ++r) EXPECT_FALSE(regions[static_cast<std::size_t>(r)].empty()) << r;
  for (int r = 0; r < 5; ++r) {
    for (int v : regions[static_cast<std::size_t>(r)]) ASSERT_LE(f.mesh.vertices(v, 0), 0.0);  // right = −x
    for (int v : regions[static_cast<std::size_t>(r + 5)]) ASSERT_GT(f.mesh.vertices(v, 0), 0.0);
  }
  ASSERT_EQ(f.rig.ibug68.size(), 68u);
  EXPECT_LT(f.mesh.vertices(f.rig.ibug68[36], 0), f.mesh.vertices(f.rig.ibug68[39], 0));  // right eye outer < inner
  EXPECT_LT(f.mesh.vertices(f.rig.ibug68[48], 0), f.mesh.vertices(f.rig.ibug68[54], 0));  // mouth corners
  EXPECT_GT(f.mesh.vertices(f.rig.ibug68[19], 1), f.mesh.vertices(f.rig.ibug68[37], 1));  // brow above eye
  EXPECT_GT(f.mesh.vertices(f.rig.ibug68[30], 2), f.mesh.vertices(f.rig.ibug68[27], 2));  // nose tip in front
  int top = -1;
  for (const auto& l : f.rig.retarget_landmarks) {
    if (l.name == "top_of_head") top = l.vertex;
  }
  ASSERT_GE(top, 0);
  EXPECT_DOUBLE_EQ(f.mesh.vertices(top, 1), f.mesh.vertices.col(1).maxCoeff());
}

TEST(DefaultFace, MusclesMirrored) {
  const auto& muscles = face().rig.muscles;
  std::set<std::string> params;
  for (const auto& m : muscles) {
    params.insert(m.parameter);
    if (m.name.find("_r") == std::string::npos) continue;
    std::string mirror = m.name;
    mirror.replace(mirror.find("_r"), 2, "_l");
    const auto it = std::find_if(muscles.begin(), muscles.end(), [&](const MuscleSpec& o) { return o.name == mirror; });
    ASSERT_NE(it, muscles.end()) << mirror;
    EXPECT_NEAR(it->head.x(), -m.head.x(), 1e-12);
    EXPECT_NEAR(it->head.y(), m.head.y(), 1e-12);
    EXPECT_NEAR(it->tail.x(), -m.tail.x(), 1e-12);
  }
  // 14 geometric muscle types × 2 sides (the other 5 types are parametric: lips, eyelids, jaw)
  EXPECT_EQ(params.size(), 28u);
}

TEST(DefaultFace, DeterministicAndMatchesCheckedInData) {
  const Face again = make_generic_face();
  EXPECT_EQ(again.mesh.vertices, face().mesh.vertices);
  EXPECT_EQ(format_rig(again.rig), format_rig(face().rig));
  const std::string rig_path = std::string(EMOFACE_SOURCE_DIR) + "/data/face/generic.rig";
  if (!std::filesystem::exists(rig_path)) GTEST_SKIP() << "data/face not present";
  const Face disk = load_face(rig_path);
  EXPECT_EQ(format_rig(disk.rig), format_rig(face().rig)) << "regenerate with: retarget --make-default-face data/face";
  EXPECT_EQ(disk.mesh.faces, face().mesh.faces);
  EXPECT_TRUE(disk.mesh.vertices.isApprox(face().mesh.vertices, 1e-7));
}

// The default head's hairline, against hand-computed values of its knots (Hairline with axis
// z = 0, eyes at y = 0, scale 1: heights in mm above the eye centres, smoothstep between knots).
TEST(DefaultHairline, HeightAtTheKnotsAndBetween) {
  const Hairline h;  // axis_z 0, eye_y 0, scale 1
  auto at = [&](double deg) {
    const double r = deg * M_PI / 180.0;
    return 1000.0 * hairline_height(h, Eigen::Vector3d(std::sin(r), 5.0, std::cos(r)));
  };
  EXPECT_NEAR(at(0), 71.0, 1e-9);     // the forehead
  EXPECT_NEAR(at(38), 76.0, 1e-9);    // the temples' recession
  EXPECT_NEAR(at(-38), 76.0, 1e-9);   // symmetric
  EXPECT_NEAR(at(74), 2.0, 1e-9);     // the sideburns' end
  EXPECT_NEAR(at(180), -45.0, 1e-9);  // the nape
  // between 84° (28 mm) and 100° (30 mm): t = 6/16, smoothstep = t²(3 − 2t) = 0.31640625
  EXPECT_NEAR(at(90), 28.0 + 2.0 * 0.31640625, 1e-9);
  Hairline s;
  s.eye_y = 0.01, s.scale = 2.0, s.axis_z = 0.05;
  EXPECT_NEAR(hairline_height(s, Eigen::Vector3d(0.0, 0.0, 0.06)), 0.01 + 2.0 * 0.071, 1e-12);
  EXPECT_NEAR(hair_cover(h, Eigen::Vector3d(0.0, 0.071, 1.0), 0.001), 0.5, 1e-12);
  EXPECT_EQ(hair_cover(h, Eigen::Vector3d(0.0, 0.0725, 1.0), 0.001), 1.0);
  EXPECT_EQ(hair_cover(h, Eigen::Vector3d(0.0, 0.0695, 1.0), 0.001), 0.0);
  EXPECT_EQ(hair_cover(h, Eigen::Vector3d(0.0, 0.0711, 1.0), 0.0), 1.0);
  // the rig must name the ears
  Rig rig;
  EXPECT_THROW(default_hairline(rig, Vertices::Zero(3, 3)), InvalidInput);
}

}  // namespace
}  // namespace emoface::facemesh
