#include "emoface/retarget/retarget.hpp"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/retarget/io.hpp"
#include "emoface/retarget/plot.hpp"
#include "emoface/retarget/validation.hpp"

namespace fm = emoface::facemesh;
namespace rt = emoface::retarget;

namespace {
const fm::Face& face() {
  static const fm::Face f = fm::make_generic_face();
  return f;
}

rt::RetargetOptions quick() {
  rt::RetargetOptions o;
  o.ga.generations = 3;
  o.ga.population = 8;
  return o;
}

double mouth_corner_motion(const fm::Face& f) {
  const emoface::muscles::FaceSolver solver(f.mesh, f.rig);
  const auto d = solver.deform(std::map<std::string, double>{{"zygomatic_major_l", 1.0}});
  int v = 0;
  for (const auto& l : f.rig.retarget_landmarks)
    if (l.name == "mouth_corner_l") v = l.vertex;
  return (d.vertices.row(v) - f.mesh.vertices.row(v)).norm();
}
}  // namespace

TEST(Transfer, IdentityNetworkKeepsTheFaceAndScalesLengths) {
  Eigen::MatrixX3d lm(static_cast<Eigen::Index>(face().rig.retarget_landmarks.size()), 3);
  for (std::size_t i = 0; i < face().rig.retarget_landmarks.size(); ++i)
    lm.row(static_cast<Eigen::Index>(i)) = face().mesh.vertices.row(face().rig.retarget_landmarks[i].vertex);
  const auto net = rt::fit_rbf(lm, lm);
  const auto out = rt::transfer_face(face(), net, 2.0);
  EXPECT_LT((out.mesh.vertices - face().mesh.vertices).cwiseAbs().maxCoeff(), 1e-12);
  ASSERT_EQ(out.rig.muscles.size(), face().rig.muscles.size());
  EXPECT_DOUBLE_EQ(out.rig.muscles[0].rf, 2.0 * face().rig.muscles[0].rf);
  EXPECT_LT((out.rig.muscles[0].head - face().rig.muscles[0].head).norm(), 1e-12);
  EXPECT_LT((out.rig.jaw.pivot - face().rig.jaw.pivot).norm(), 1e-12);
  EXPECT_DOUBLE_EQ(out.rig.eyes[1].radius, 2.0 * face().rig.eyes[1].radius);
  EXPECT_THROW(rt::transfer_face(face(), net, 0.0), emoface::InvalidInput);
}

TEST(Retarget, SelfFitKeepsTheFaceAndItsAnimation) {
  const auto r = rt::retarget_face(face(), face().mesh, quick());
  EXPECT_NEAR(r.alignment.scale, 1.0, 1e-6);
  EXPECT_LT((r.face.mesh.vertices - face().mesh.vertices).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_NO_THROW(fm::validate_rig(r.face.rig));
  EXPECT_NEAR(r.length_scale, 1.0, 1e-4);
  EXPECT_NEAR(mouth_corner_motion(r.face), mouth_corner_motion(face()), 1e-4);
  EXPECT_EQ(std::count(r.detected.begin(), r.detected.end(), true), 4);
  EXPECT_LE(r.ga.best_error, r.ga.initial_error);
}

TEST(Retarget, WarpedTargetImprovesAndTheRigAnimates) {
  rt::SyntheticWarp w;
  w.width = 1.1;
  w.nose = 0.006;
  w.scale = 3.0;  // a different scale: aligned back to the source's
  fm::Mesh target = face().mesh;
  target.vertices = w.apply(target.vertices);
  auto o = quick();
  o.ga.generations = 15;
  o.ga.population = 16;
  const auto r = rt::retarget_face(face(), target, o);
  EXPECT_NEAR(r.alignment.scale, 1.0 / 3.0, 0.02);
  EXPECT_LT(r.ga.best_error, r.ga.initial_error);
  // Mirror symmetry of the searched pairs (symmetric = true).
  const auto idx = [&](const std::string& n) {
    return static_cast<Eigen::Index>(std::find(r.landmark_names.begin(), r.landmark_names.end(), n) - r.landmark_names.begin());
  };
  const double cx = r.target_landmarks(idx("top_of_head"), 0);
  EXPECT_NEAR(r.target_landmarks(idx("cheek_l"), 0) - cx, cx - r.target_landmarks(idx("cheek_r"), 0), 1e-3);
  const double smile = mouth_corner_motion(r.face);
  EXPECT_GT(smile, 0.5 * mouth_corner_motion(face()));
  EXPECT_LT(smile, 2.0 * mouth_corner_motion(face()));
}

TEST(Retarget, RefinementNeverWorsensAndIsReported) {
  rt::SyntheticWarp w;
  w.height = 1.06;
  w.chin = 0.006;
  fm::Mesh target = face().mesh;
  target.vertices = w.apply(target.vertices);
  auto o = quick();
  o.refine.enabled = true;
  o.refine.max_iterations = 3;
  const auto r = rt::retarget_face(face(), target, o);
  EXPECT_TRUE(r.refine.ran);
  EXPECT_GE(r.refine.iterations, 1);
  EXPECT_NEAR(r.refine.initial_error, r.ga.best_error, 1e-12 + 1e-9 * r.ga.best_error);
  EXPECT_LE(r.refine.final_error, r.refine.initial_error);
  EXPECT_FALSE(r.refine.status.empty());
  const auto doc = emoface::core::parse_json(rt::format_report(r, false), "r");
  EXPECT_EQ(doc["refine"]["iterations"].get<int>(), r.refine.iterations);
  rt::RefineOptions bad;
  bad.step = 0;
  EXPECT_THROW(bad.validate(), emoface::InvalidInput);
}

TEST(Retarget, ClearErrors) {
  auto o = quick();
  o.detected = {"nose_tip", "ear_l"};
  EXPECT_THROW(rt::retarget_face(face(), face().mesh, o), emoface::InvalidInput);
  fm::Face bare = face();
  bare.rig.retarget_landmarks.erase(bare.rig.retarget_landmarks.begin());  // no top_of_head
  EXPECT_THROW(rt::retarget_face(bare, face().mesh, quick()), emoface::InvalidInput);
  fm::Mesh flat = face().mesh;
  flat.vertices.col(1).setConstant(0.1);
  EXPECT_THROW(rt::retarget_face(face(), flat, quick()), emoface::InvalidInput);
  // A mask open at the top: clear error, not nonsense.
  fm::Mesh mask = face().mesh;
  std::vector<int> keep;
  const int top = face().rig.retarget_landmarks[0].vertex;
  for (Eigen::Index f = 0; f < mask.faces.rows(); ++f)
    if (mask.faces(f, 0) != top && mask.faces(f, 1) != top && mask.faces(f, 2) != top) keep.push_back(static_cast<int>(f));
  fm::Faces kept(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t i = 0; i < keep.size(); ++i) kept.row(static_cast<Eigen::Index>(i)) = mask.faces.row(keep[i]);
  mask.faces = kept;
  mask.vertices(top, 1) -= 0.05;  // the unused pole must not count as the top
  EXPECT_THROW(rt::retarget_face(face(), mask, quick()), emoface::InvalidInput);
  o = quick();
  o.prior_weight = -1;
  EXPECT_THROW(o.validate(), emoface::InvalidInput);
}

TEST(Report, EnvelopeAndContent) {
  const auto r = rt::retarget_face(face(), face().mesh, quick());
  const std::string text = rt::format_report(r);
  const auto doc = emoface::core::parse_json(text, "report");
  EXPECT_EQ(emoface::core::check_envelope(doc, "retarget_report", {1, 0}, "report").major, 1);
  EXPECT_EQ(doc["landmarks"].size(), r.landmark_names.size());
  EXPECT_EQ(doc["ga"]["error_curve"].size(), r.ga.error_curve.size());
  EXPECT_TRUE(doc["ga"].contains("seconds"));
  EXPECT_FALSE(emoface::core::parse_json(rt::format_report(r, false), "r")["ga"].contains("seconds"));
  const auto dir = std::filesystem::temp_directory_path() / "emoface_retarget_report_test";
  std::filesystem::create_directories(dir);
  rt::write_report((dir / "report.json").string(), r, false);
  EXPECT_EQ(emoface::core::read_file((dir / "report.json").string()), rt::format_report(r, false));
  std::filesystem::remove_all(dir);
}

TEST(Plot, DrawsSeriesAndRejectsBadSizes) {
  const auto img = rt::plot_series({{4, 2, 1, 0.5}, {3, 3}}, 100, 60);
  ASSERT_EQ(img.rgb.size(), 100u * 60u * 3u);
  int blue = 0;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3)
    if (img.rgb[i] == 30 && img.rgb[i + 2] == 200) ++blue;
  EXPECT_GT(blue, 50);
  EXPECT_THROW(rt::plot_series({{1.0}}, 10, 60), emoface::InvalidInput);
  EXPECT_THROW(rt::plot_series({}, 100, 60), emoface::InvalidInput);
}

// Real third-party heads, only when ../shared/meshes exists (never copied into the repo).
