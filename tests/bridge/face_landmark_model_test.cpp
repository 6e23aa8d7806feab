#include "emoface/bridge/face_landmark_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/fuzzyexpr/names.hpp"
#include "emoface/muscles/parameters.hpp"

namespace br = emoface::bridge;
namespace mg = emoface::motiongraph;
namespace ms = emoface::muscles;
namespace fz = emoface::fuzzyexpr;

namespace {

// Built once for the suite (the default face and its solver).
const br::FaceLandmarkModel& model() {
  static const br::FaceLandmarkModel m;
  return m;
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

// Independent re-implementation of the documented projection for one point: camera on +z through
// the neutral centroid at `distance`, pixel = centre + s·k·(x, −y), k = d / (d − z).
Eigen::Vector2d project_by_hand(const Eigen::Vector3d& q, const Eigen::Vector3d& centroid,
                                double distance, double s, const Eigen::Vector2d& centre_of_raw,
                                const Eigen::Vector2d& centre) {
  const Eigen::Vector3d r = q - centroid;
  const double k = distance / (distance - r.z());
  return centre + s * (k * Eigen::Vector2d(r.x(), -r.y()) - centre_of_raw);
}

}  // namespace

TEST(FaceLandmarkModel, SideParameterOrderMatchesFuzzyexpr) {
  ASSERT_EQ(ms::side_parameter_names().size(), fz::kSideParameterCount);
  for (std::size_t j = 0; j < fz::kSideParameterCount; ++j)
    EXPECT_EQ(ms::side_parameter_names()[j], std::string(fz::side_parameter_names()[j])) << j;
}

TEST(FaceLandmarkModel, NeutralIsTheProjectedRigLandmarks) {
  const auto& m = model();
  const mg::Identity id;
  const Eigen::MatrixXd neutral = m.project(m.neutral_landmarks_3d(), id);
  // Rig landmarks: the mesh vertices named by rig.ibug68.
  const auto& ids = m.solver().rig().ibug68;
  for (int i = 0; i < 68; ++i)
    EXPECT_EQ((m.neutral_landmarks_3d().row(i) - m.solver().neutral().vertices.row(ids[i])).norm(),
              0.0);
  EXPECT_LT(max_abs(m.landmarks(mg::Label::Neutral, 0.0, id) - neutral), 1e-12);
  EXPECT_LT(max_abs(m.landmarks(mg::Label::Neutral, 0.8, id) - neutral), 1e-12);
  for (mg::Label l : mg::all_labels()) EXPECT_LT(max_abs(m.landmarks(l, 0.0, id) - neutral), 1e-12);
  // CK+ framing: centroid at centre_px, RMS radius face_size_px, inside the 640×490 frame.
  const Eigen::RowVector2d c = neutral.colwise().mean();
  EXPECT_NEAR(c(0), m.options().centre_px.x(), 1e-9);
  EXPECT_NEAR(c(1), m.options().centre_px.y(), 1e-9);
  EXPECT_NEAR(std::sqrt((neutral.rowwise() - c).rowwise().squaredNorm().mean()),
              m.options().face_size_px, 1e-9);
  EXPECT_GT(neutral.col(0).minCoeff(), 100.0);
  EXPECT_LT(neutral.col(0).maxCoeff(), 540.0);
  EXPECT_GT(neutral.col(1).minCoeff(), 60.0);
  EXPECT_LT(neutral.col(1).maxCoeff(), 470.0);
  // Image orientation: brows above the eyes above the mouth (y down); iBUG 36 (right eye outer
  // corner) on the image left of 45.
  EXPECT_LT(neutral(19, 1), neutral(37, 1));
  EXPECT_LT(neutral(37, 1), neutral(51, 1));
  EXPECT_LT(neutral(51, 1), neutral(8, 1));
  EXPECT_LT(neutral(36, 0), neutral(45, 0));
  EXPECT_LT(neutral(48, 0), neutral(54, 0));
}

TEST(FaceLandmarkModel, PerspectiveAndOrthographicProjectionsByHand) {
  const auto& m = model();
  const Eigen::MatrixXd& n3 = m.neutral_landmarks_3d();
  const Eigen::Vector3d centroid = n3.colwise().mean().transpose();
  for (br::Projection proj : {br::Projection::Perspective, br::Projection::Orthographic}) {
    br::FaceLandmarkModelOptions o;
    o.projection = proj;
    o.camera_distance = 0.5;
    const br::FaceLandmarkModel fm(m.solver(), emoface::fuzzyexpr::Engine(), o);
    const double d =
        proj == br::Projection::Perspective ? 0.5 : 1e12;  // orthographic = infinitely far
    // Raw image (scale 1) of the neutral landmarks, its centroid and RMS radius → s, then compare.
    Eigen::MatrixXd raw(68, 2);
    for (int i = 0; i < 68; ++i) {
      const Eigen::Vector3d r = n3.row(i).transpose() - centroid;
      const double k = d / (d - r.z());
      raw.row(i) << k * r.x(), -k * r.y();
    }
    const Eigen::RowVector2d rc = raw.colwise().mean();
    const double s =
        o.face_size_px / std::sqrt((raw.rowwise() - rc).rowwise().squaredNorm().mean());
    // A displaced point (not a neutral one) to test the formula, not just the normalisation.
    Eigen::MatrixXd q = n3;
    q.row(30) += Eigen::RowVector3d(0.01, -0.02, 0.03);
    const Eigen::MatrixXd px = fm.project(q, mg::Identity());
    const Eigen::Vector2d hand =
        project_by_hand(q.row(30).transpose(), centroid, d, s, rc.transpose(), o.centre_px);
    EXPECT_NEAR(px(30, 0), hand.x(), 1e-6) << br::to_string(proj);
    EXPECT_NEAR(px(30, 1), hand.y(), 1e-6) << br::to_string(proj);
  }
  // Perspective enlarges what is nearer the camera.
  br::FaceLandmarkModelOptions o;
  o.camera_distance = 0.3;
  const br::FaceLandmarkModel near_cam(m.solver(), emoface::fuzzyexpr::Engine(), o);
  o.projection = br::Projection::Orthographic;
  const br::FaceLandmarkModel ortho(m.solver(), emoface::fuzzyexpr::Engine(), o);
  const Eigen::MatrixXd a = near_cam.project(n3, mg::Identity()),
                        b = ortho.project(n3, mg::Identity());
  // Outer eye corners (behind the nose) vs mouth corners (in front): the ratio of their widths
  // grows in the perspective image.
  const double ratio_p = (a.row(54) - a.row(48)).norm() / (a.row(45) - a.row(36)).norm();
  const double ratio_o = (b.row(54) - b.row(48)).norm() / (b.row(45) - b.row(36)).norm();
  EXPECT_GT(ratio_p, ratio_o * 1.01);
}

TEST(FaceLandmarkModel, HappinessMovesMouthCornersUpAndOut) {
  const auto& m = model();
  const mg::Identity id;
  const Eigen::MatrixXd n = m.landmarks(mg::Label::Neutral, 0.0, id);
  const Eigen::MatrixXd h = m.landmarks(mg::Label::Happiness, 1.0, id);
  EXPECT_LT(h(48, 1), n(48, 1) - 5.0);  // up (y down) by more than 5 px
  EXPECT_LT(h(54, 1), n(54, 1) - 5.0);
  EXPECT_LT(h(48, 0), n(48, 0) - 3.0);  // out
  EXPECT_GT(h(54, 0), n(54, 0) + 3.0);
  // Symmetric expression: both corners move by mirror-equal amounts.
  EXPECT_NEAR(h(48, 1) - n(48, 1), h(54, 1) - n(54, 1), 1e-6);
  // Half intensity moves them less.
  const Eigen::MatrixXd half = m.landmarks(mg::Label::Happiness, 0.5, id);
  EXPECT_GT(half(48, 1), h(48, 1));
  EXPECT_LT(half(48, 1), n(48, 1));
  // The parameters are the fuzzy engine's: one-hot ESV → FMCV → sides.
  fz::Esv esv{};
  esv[fz::index(fz::Emotion::Happiness)] = 0.7;
  const auto sides = fz::expand_to_sides(fz::Engine().convert(esv));
  const auto p = m.side_parameters(mg::Label::Happiness, 0.7);
  for (std::size_t j = 0; j < sides.size(); ++j) EXPECT_EQ(p[j], sides[j]) << j;
  EXPECT_GT(p[ms::parameter_index("zygomatic_major_l")], 0.5);
}

TEST(FaceLandmarkModel, EveryEmotionMovesTheFaceSurpriseOpensTheJaw) {
  const auto& m = model();
  const mg::Identity id;
  const Eigen::MatrixXd n = m.landmarks(mg::Label::Neutral, 0.0, id);
  for (mg::Label l : mg::all_labels()) {
    if (l == mg::Label::Neutral) continue;
    const double moved = (m.landmarks(l, 1.0, id) - n).rowwise().norm().maxCoeff();
    EXPECT_GT(moved, 5.0) << mg::to_string(l);
    // fear's and surprise's chins move most: 83 and 65 with their jaw drops (masseter VeryBig
    // and Big at 1, AU27/26; fear's since session 12)
    EXPECT_LT(moved, 95.0) << mg::to_string(l);
  }
  const Eigen::MatrixXd s = m.landmarks(mg::Label::Surprise, 1.0, id);
  EXPECT_GT(s(8, 1), n(8, 1) + 5.0);    // chin down
  EXPECT_LT(s(19, 1), n(19, 1) - 3.0);  // brows up
  const Eigen::MatrixXd a = m.landmarks(mg::Label::Anger, 1.0, id);
  EXPECT_GT(a(21, 1), n(21, 1));  // inner brows down
}

TEST(FaceLandmarkModel, ContemptIsUnilateral) {
  const auto& m = model();
  const mg::Identity id;
  const Eigen::MatrixXd n = m.landmarks(mg::Label::Neutral, 0.0, id);
  const Eigen::MatrixXd c = m.landmarks(mg::Label::Contempt, 1.0, id);
  // The subject's left corner (iBUG 54, image right) moves out and up; the right one stays.
  EXPECT_GT(c(54, 0), n(54, 0) + 5.0);
  EXPECT_LT(c(54, 1), n(54, 1) - 5.0);
  EXPECT_LT((c.row(48) - n.row(48)).norm(), 0.5);
  const auto p = br::contempt_parameters(0.5);
  EXPECT_DOUBLE_EQ(p[ms::parameter_index("zygomatic_major_l")], 0.35);
  EXPECT_DOUBLE_EQ(p[ms::parameter_index("risorius_l")], 0.5);
  EXPECT_DOUBLE_EQ(p[ms::parameter_index("orbicularis_oris_pressor")], 0.15);
  EXPECT_EQ(p[ms::parameter_index("zygomatic_major_r")], 0.0);
  for (double v : m.side_parameters(mg::Label::Neutral, 1.0)) EXPECT_EQ(v, 0.0);
}

TEST(FaceLandmarkModel, IdentityTransform) {
  const auto& m = model();
  const Eigen::MatrixXd base = m.landmarks(mg::Label::Fear, 0.6, mg::Identity());
  const Eigen::Vector2d centre = m.options().centre_px;
  mg::Identity id;
  id.scale = 1.1;
  id.roll = 0.2;
  id.translation = Eigen::Vector2d(7.0, -4.0);
  id.shape = Eigen::MatrixXd::Constant(68, 2, 0.5);
  const Eigen::MatrixXd got = m.landmarks(mg::Label::Fear, 0.6, id);
  for (int i = 0; i < 68; ++i) {
    const Eigen::Vector2d r = base.row(i).transpose() - centre;
    const double c = std::cos(0.2), s = std::sin(0.2);
    const Eigen::Vector2d want =
        centre + Eigen::Vector2d(7.0, -4.0) +
        1.1 * Eigen::Vector2d(c * r.x() - s * r.y(), s * r.x() + c * r.y()) +
        Eigen::Vector2d(0.5, 0.5);
    EXPECT_NEAR(got(i, 0), want.x(), 1e-9);
    EXPECT_NEAR(got(i, 1), want.y(), 1e-9);
  }
}

TEST(FaceLandmarkModel, BadInput) {
  const auto& m = model();
  const mg::Identity id;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(m.landmarks(mg::Label::Happiness, nan, id), emoface::InvalidInput);
  EXPECT_THROW(m.landmarks(mg::Label::Happiness, 1.5, id), emoface::InvalidInput);
  EXPECT_THROW(m.landmarks(mg::Label::Happiness, -0.1, id), emoface::InvalidInput);
  EXPECT_THROW(br::contempt_parameters(2.0), emoface::InvalidInput);
  mg::Identity bad;
  bad.scale = 0.0;
  EXPECT_THROW(m.landmarks(mg::Label::Happiness, 0.5, bad), emoface::InvalidInput);
  bad = mg::Identity();
  bad.shape = Eigen::MatrixXd::Zero(67, 2);
  EXPECT_THROW(m.landmarks(mg::Label::Happiness, 0.5, bad), emoface::InvalidInput);
  bad = mg::Identity();
  bad.roll = nan;
  EXPECT_THROW(m.landmarks(mg::Label::Happiness, 0.5, bad), emoface::InvalidInput);
  EXPECT_THROW(m.project(Eigen::MatrixXd::Zero(68, 2), id), emoface::InvalidInput);
  Eigen::MatrixXd inf = m.neutral_landmarks_3d();
  inf(3, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(m.project(inf, id), emoface::InvalidInput);
  Eigen::MatrixXd behind = m.neutral_landmarks_3d();
  behind(3, 2) += 5.0;  // 5 m towards (and past) the camera
  EXPECT_THROW(m.project(behind, id), emoface::NumericalError);
  br::FaceLandmarkModelOptions o;
  o.camera_distance = 0.0;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  o = {};
  o.face_size_px = nan;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
  o = {};
  o.centre_px.x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(br::FaceLandmarkModel(m.solver(), emoface::fuzzyexpr::Engine(), o),
               emoface::InvalidInput);
  EXPECT_EQ(br::projection_from_string("orthographic"), br::Projection::Orthographic);
  EXPECT_EQ(br::projection_from_string(br::to_string(br::Projection::Perspective)),
            br::Projection::Perspective);
  EXPECT_FALSE(br::projection_from_string("fisheye"));
}

TEST(FaceLandmarkModel, SyntheticDatabaseIsDeterministicAndStartsNeutral) {
  const auto& m = model();
  mg::SyntheticOptions o;
  o.sequences_per_label = 1;
  o.max_frames = 12;
  o.seed = 5;
  const mg::Database a = mg::generate_synthetic_database(m, o);
  const mg::Database b = mg::generate_synthetic_database(m, o);
  ASSERT_EQ(a.sequences.size(), 7u);
  for (std::size_t s = 0; s < a.sequences.size(); ++s) {
    ASSERT_EQ(a.sequences[s].frames.size(), b.sequences[s].frames.size());
    for (std::size_t f = 0; f < a.sequences[s].frames.size(); ++f)
      EXPECT_EQ(a.sequences[s].frames[f], b.sequences[s].frames[f]);  // bitwise equal
  }
  o.seed = 6;
  const mg::Database c = mg::generate_synthetic_database(m, o);
  EXPECT_GT(max_abs(c.sequences[0].frames[0] - a.sequences[0].frames[0]), 0.1);
  // Without identity scale, roll, shape changes and noise, every first frame is the neutral face up
  // to the per-recording translation.
  o.scale_std = o.roll_std = o.shape_std = o.noise_std = 0.0;
  const Eigen::MatrixXd n = m.landmarks(mg::Label::Neutral, 0.0, mg::Identity());
  const Eigen::MatrixXd nc = n.rowwise() - n.colwise().mean();
  const mg::Database d = mg::generate_synthetic_database(m, o);
  for (const mg::Sequence& s : d.sequences) {
    const Eigen::MatrixXd& f0 = s.frames.front();
    EXPECT_LT(max_abs((f0.rowwise() - f0.colwise().mean()) - nc), 1e-9) << s.id;
    const Eigen::MatrixXd& peak = s.frames.back();
    EXPECT_GT(max_abs((peak.rowwise() - f0.colwise().mean()) - nc), 3.0) << s.id;  // and it moves
  }
  // Happiness peaks raise the mouth corners relative to the eyes.
  for (const mg::Sequence& s : d.sequences)
    if (s.label == mg::Label::Happiness) {
      const auto rise = [](const Eigen::MatrixXd& p) { return p(48, 1) - p(36, 1); };
      EXPECT_LT(rise(s.frames.back()), rise(s.frames.front()) - 3.0);
    }
}
