// Eyes and jaw as glTF nodes (split_rigid_parts, bake_animation's part rotations): the nodes must
// reproduce the muscle model exactly, and the skin must be the rest of the mesh, unchanged.
#include "emoface/muscles/morph_targets.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/render.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/solver.hpp"

namespace emoface::muscles {
namespace {

// Independently of the library: does any face join a vertex of `set` to a vertex outside it?
bool face_closed(const facemesh::Faces& faces, const std::vector<int>& set) {
  const std::set<int> in(set.begin(), set.end());
  if (in.empty()) return false;
  for (long f = 0; f < faces.rows(); ++f) {
    int inside = 0;
    for (int k = 0; k < 3; ++k) inside += in.count(faces(f, k)) ? 1 : 0;
    if (inside != 0 && inside != 3) return false;
  }
  return true;
}

class SplitRigidParts : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    face_ = new facemesh::Face(facemesh::make_default_face());
    solver_ = new FaceSolver(face_->mesh, face_->rig);
    whole_ = new BakedRig(bake_rig(*solver_, face_->mesh.faces));
  }
  static void TearDownTestSuite() {
    delete whole_;
    delete solver_;
    delete face_;
  }
  static facemesh::Face* face_;
  static FaceSolver* solver_;
  static BakedRig* whole_;
};
facemesh::Face* SplitRigidParts::face_ = nullptr;
FaceSolver* SplitRigidParts::solver_ = nullptr;
BakedRig* SplitRigidParts::whole_ = nullptr;

TEST_F(SplitRigidParts, NodesReproduceTheMuscleModelAndTheSkinIsTheRest) {
  BakedRig rig = *whole_;
  auto colors = facemesh::material_colors(face_->rig, face_->mesh);
  const auto all_colors = colors;
  split_rigid_parts(rig, face_->rig, colors);
  const long nv = face_->mesh.vertices.rows();
  // an eye becomes a node exactly when its eyeball is a separate piece of the mesh
  for (int e = 0; e < 2; ++e) {
    const bool closed = face_closed(face_->mesh.faces,
                                    face_->rig.eyes[static_cast<std::size_t>(e)].eyeball_vertices);
    const auto drive = e == 0 ? PartDrive::EyeRight : PartDrive::EyeLeft;
    const bool node =
        std::find(rig.part_drives.begin(), rig.part_drives.end(), drive) != rig.part_drives.end();
    EXPECT_EQ(node, closed) << "eye " << e;
  }
  ASSERT_EQ(rig.parts.size(), rig.part_drives.size());
  // skin + part meshes partition the vertices; the skin keeps its rows of every target
  std::size_t part_vertices = 0;
  for (const auto& p : rig.parts)
    for (const auto& pm : p.meshes) {
      part_vertices += static_cast<std::size_t>(pm.mesh.vertices.rows());
      EXPECT_EQ(pm.colors.size(), static_cast<std::size_t>(pm.mesh.vertices.rows()));
    }
  if (rig.parts.empty()) GTEST_SKIP() << "this face has no separable eyeballs or jaw parts";
  EXPECT_EQ(rig.skin_vertices.size() + part_vertices, static_cast<std::size_t>(nv));
  ASSERT_EQ(rig.neutral.vertices.rows(), static_cast<long>(rig.skin_vertices.size()));
  ASSERT_EQ(colors.size(), rig.skin_vertices.size());
  for (std::size_t k = 0; k < rig.skin_vertices.size(); k += 97) {
    const int v = rig.skin_vertices[k];
    EXPECT_EQ(rig.neutral.vertices.row(static_cast<long>(k)), whole_->neutral.vertices.row(v));
    EXPECT_EQ(colors[k], all_colors[static_cast<std::size_t>(v)]);
    EXPECT_EQ(rig.targets[0].position_deltas.row(static_cast<long>(k)),
              whole_->targets[0].position_deltas.row(v));
    // the last target by name: with both eyes as nodes the split rig has no gaze targets, so the
    // two rigs' lists differ in length
    const auto same_name = std::find_if(
        whole_->targets.begin(), whole_->targets.end(),
        [&](const auto& t) { return t.name == rig.targets.back().name; });
    ASSERT_NE(same_name, whole_->targets.end()) << rig.targets.back().name;
    EXPECT_EQ(rig.targets.back().position_deltas.row(static_cast<long>(k)),
              same_name->position_deltas.row(v));
  }
  EXPECT_LE(rig.neutral.faces.maxCoeff(), rig.neutral.vertices.rows() - 1);
  // both eyes as nodes: the gaze halves are gone and the weights follow
  const bool both_eyes =
      std::count(rig.part_drives.begin(), rig.part_drives.end(), PartDrive::EyeRight) +
          std::count(rig.part_drives.begin(), rig.part_drives.end(), PartDrive::EyeLeft) ==
      2;
  EXPECT_EQ(rig.gaze_targets, !both_eyes);
  for (const auto& t : rig.targets)
    EXPECT_NE(both_eyes ? t.name.find("eye_gaze") : 0, 0u) << t.name;
  std::vector<double> values(kParameterCount, 0.0);
  values[parameter_index("eye_gaze_yaw")] = 0.3;
  values[parameter_index("eye_gaze_pitch")] = -0.25;
  values[parameter_index("masseter")] = 0.6;
  values[parameter_index("zygomatic_major_l")] = 0.5;
  values[parameter_index("frontalis_medialis_r")] = 0.7;
  EXPECT_EQ(target_weights(rig, values).size(), rig.targets.size());
  // the nodes' rotations about their pivots put every part vertex where the muscle model does
  const auto anim =
      bake_animation(rig, {0.0, 1.0}, {std::vector<double>(kParameterCount, 0.0), values});
  ASSERT_EQ(anim.part_rotations.size(), rig.parts.size());
  const Deformation d = solver_->deform(values);
  for (std::size_t p = 0; p < rig.parts.size(); ++p) {
    ASSERT_EQ(anim.part_rotations[p].size(), 2u) << rig.parts[p].name;
    EXPECT_TRUE(anim.part_rotations[p][0].isApprox(Eigen::Quaterniond::Identity()));
    const Eigen::Quaterniond q = anim.part_rotations[p][1];
    if (rig.part_drives[p] == PartDrive::Jaw) {
      // 0.6 · max_angle about +x, by hand: (sin(a/2), 0, 0, cos(a/2))
      const double a = 0.6 * face_->rig.jaw.max_angle;
      EXPECT_NEAR(q.w(), std::cos(a / 2), 1e-12);
      EXPECT_NEAR(q.x(), std::sin(a / 2), 1e-12);
      EXPECT_EQ(rig.parts[p].name, "jaw");
      EXPECT_EQ(rig.parts[p].pivot, face_->rig.jaw.pivot);
    }
    double worst = 0.0;
    for (const auto& pm : rig.parts[p].meshes) {
      for (long i = 0; i < pm.mesh.vertices.rows(); ++i) {
        const Eigen::Vector3d x = pm.mesh.vertices.row(i).transpose();
        const Eigen::Vector3d posed = rig.parts[p].pivot + q * (x - rig.parts[p].pivot);
        // find the vertex in the face mesh (same neutral position)
        long v = -1;
        for (long k = 0; k < nv && v < 0; ++k)
          if (whole_->neutral.vertices.row(k) == pm.mesh.vertices.row(i)) v = k;
        ASSERT_GE(v, 0);
        worst = std::max(worst, (posed - d.vertices.row(v).transpose()).norm());
      }
    }
    EXPECT_LT(worst, 1e-9) << rig.parts[p].name;
  }
}

TEST_F(SplitRigidParts, MeshFrameAndBadInput) {
  BakedRig rig = *whole_;
  std::vector<Eigen::Vector3f> none;
  split_rigid_parts(rig, face_->rig, none);
  if (rig.parts.empty()) GTEST_SKIP() << "this face has no separable parts";
  EXPECT_TRUE(rig.parts[0].meshes[0].colors.empty());
  EXPECT_THROW(split_rigid_parts(rig, face_->rig, none), InvalidInput);  // already split
  BakedRig other = *whole_;
  std::vector<Eigen::Vector3f> short_colors(3);
  EXPECT_THROW(split_rigid_parts(other, face_->rig, short_colors), InvalidInput);
  SplitOptions bad;
  bad.tolerance = 0.0;
  EXPECT_THROW(split_rigid_parts(other, face_->rig, none, bad), InvalidInput);
  // a mesh frame: pivots and part vertices through to_mesh, rotations conjugated
  facemesh::Frame frame;
  frame.scale = 0.01;
  frame.rotation = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  frame.translation = Eigen::Vector3d(0.1, 0.2, 0.3);
  std::vector<double> values(kParameterCount, 0.0);
  values[parameter_index("eye_gaze_yaw")] = 0.2;
  values[parameter_index("masseter")] = 1.0;
  std::vector<facemesh::WeightAnimation> anims{bake_animation(rig, {0.0}, {values})};
  const BakedRig before = rig;
  const auto q0 = anims[0].part_rotations[0][0];
  express_in_mesh_frame(rig, anims, frame);
  EXPECT_TRUE(rig.parts[0].pivot.isApprox(frame.to_mesh(before.parts[0].pivot), 1e-12));
  const Eigen::Vector3d x0 = before.parts[0].meshes[0].mesh.vertices.row(0).transpose();
  EXPECT_TRUE(Eigen::Vector3d(rig.parts[0].meshes[0].mesh.vertices.row(0).transpose())
                  .isApprox(frame.to_mesh(x0), 1e-12));
  const Eigen::Quaterniond r(frame.rotation);
  EXPECT_TRUE(anims[0].part_rotations[0][0].isApprox(r.conjugate() * q0 * r, 1e-12));
}

// The ARKit blendshape character (faceanim --blendshapes, the ARKit oracle): a shape alone at
// weight 1 is the muscle model's face for the parameters the mapper fits to that shape; linear in
// between.
TEST_F(SplitRigidParts, BlendshapeCharacterPosesTheSetTargets) {
  const faceweights::Mapper arkit(faceweights::builtin_weight_set("arkit"), parameter_names());
  const BakedRig rig = bake_rig(*solver_, face_->mesh.faces, {&arkit});
  const std::size_t n = arkit.target_count();
  std::size_t jaw = n;
  for (std::size_t t = 0; t < n; ++t)
    if (arkit.set().targets[t].name == "jawOpen") jaw = t;
  ASSERT_LT(jaw, n);
  std::vector<double> set(n, 0.0);
  set[jaw] = 1.0;
  const auto w = set_target_weights(rig, set);
  ASSERT_EQ(w.size(), rig.targets.size());
  EXPECT_EQ(w[rig.parameter_target_count + jaw], 1.0);
  EXPECT_EQ(std::count(w.begin(), w.end(), 0.0), static_cast<long>(w.size()) - 1);
  std::vector<double> p(kParameterCount, 0.0);
  arkit.inverse(set, p);
  EXPECT_GT(p[parameter_index("masseter")], 0.5);  // jawOpen is the jaw's opening
  const Deformation d = solver_->deform(p);
  const facemesh::Vertices full = blend_targets(rig, w);
  EXPECT_LT((full - d.vertices).cwiseAbs().maxCoeff(), 1e-12);
  set[jaw] = 0.5;
  const facemesh::Vertices half = blend_targets(rig, set_target_weights(rig, set));
  EXPECT_LT((half - 0.5 * (rig.neutral.vertices + d.vertices)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_THROW(set_target_weights(rig, std::vector<double>(n + 1, 0.0)), InvalidInput);
  EXPECT_THROW(blend_targets(rig, std::vector<double>(3, 0.0)), InvalidInput);
  auto nan = w;
  nan[0] = std::nan("");
  EXPECT_THROW(blend_targets(rig, nan), InvalidInput);
}

TEST(PartDrive, StringRoundTrip) {
  for (auto d : {PartDrive::EyeRight, PartDrive::EyeLeft, PartDrive::Jaw})
    EXPECT_EQ(part_drive_from_string(to_string(d)), d);
  EXPECT_THROW(part_drive_from_string("nose"), InvalidInput);
}

}  // namespace
}  // namespace emoface::muscles
