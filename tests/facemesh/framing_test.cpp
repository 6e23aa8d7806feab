// Camera framing of render(): any mesh, any frame and units (issue 13: a head in decimetres used to
// render as an empty image).
#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/render.hpp"

namespace emoface::facemesh {
namespace {

const Face& face() {
  static const Face f = make_generic_face();
  return f;
}

// Fraction of pixels that differ from the background.
double covered(const core::Image& image, const RenderOptions& o) {
  long n = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    bool bg = true;
    for (int k = 0; k < 3; ++k) {
      const int b = static_cast<int>(std::lround(o.background[k] * 255.0));
      if (std::abs(static_cast<int>(image.rgb[i + static_cast<std::size_t>(k)]) - b) > 2) bg = false;
    }
    if (!bg) ++n;
  }
  return static_cast<double>(n) / static_cast<double>(image.rgb.size() / 3);
}

// The built-in face in decimetres, turned and moved far off the default view.
Mesh far_head() {
  Mesh m = face().mesh;
  m.vertices *= 10.0;
  m.vertices.col(0).array() += 30.0;
  m.vertices.col(1).array() += 12.0;
  return m;
}

TEST(Framing, DefaultViewOfAFarHeadIsEmptyAndTheFittedOneIsNot) {
  RenderOptions o;
  o.width = 96, o.height = 112;
  const Mesh m = far_head();
  EXPECT_EQ(visible_fraction(m.vertices, o), 0.0);
  EXPECT_LT(covered(render(m, {}, {}, o), o), 1e-9);  // the old behaviour: a blank picture
  const RenderOptions fitted = frame_camera(m.vertices, o);
  EXPECT_EQ(visible_fraction(m.vertices, fitted), 1.0);
  const double c = covered(render(m, {}, {}, fitted), fitted);
  EXPECT_GT(c, 0.25);
  // the same picture as the face in metres at the origin, fitted the same way (scale/shift invariant)
  const RenderOptions own = fit_camera(face().mesh.vertices, o);
  EXPECT_NEAR(fitted.distance, 10.0 * own.distance, 1e-9 * fitted.distance);
  EXPECT_TRUE(fitted.target.isApprox(10.0 * own.target + Eigen::Vector3d(30, 12, 0), 1e-12));
}

TEST(Framing, FitSpansTheRequestedFillAndKeepsTheFaceFraming) {
  RenderOptions o;
  const RenderOptions f = fit_camera(far_head().vertices, o, 0.8);
  // independent check: the projected vertices span at most the image and about 80 % of it
  const double focal = 0.5 * o.height / std::tan(0.5 * o.field_of_view);
  const Eigen::Vector3d eye = f.target + f.distance * Eigen::Vector3d::UnitZ();  // front view looks along -z
  double extent = 0.0;
  const Mesh m = far_head();
  for (long v = 0; v < m.vertices.rows(); ++v) {
    const Eigen::Vector3d d = m.vertices.row(v).transpose() - eye;
    const double z = -d.z();
    extent = std::max({extent, std::abs(focal * d.x() / z) / (0.5 * o.width), std::abs(focal * d.y() / z) / (0.5 * o.height)});
  }
  EXPECT_GT(extent, 0.7);
  EXPECT_LE(extent, 0.9);
  // the built-in face in the thesis frame keeps the default camera (pictures stay as they were)
  for (auto view : {View::Front, View::ThreeQuarter}) {
    RenderOptions d;
    d.view = view;
    const RenderOptions kept = frame_camera(face().mesh.vertices, d);
    EXPECT_EQ(kept.distance, d.distance);
    EXPECT_EQ(kept.target, d.target);
  }
}

TEST(Framing, RejectsMeshesWithoutExtent) {
  RenderOptions o;
  EXPECT_THROW(fit_camera(Vertices(0, 3), o), InvalidInput);
  EXPECT_THROW(fit_camera(Vertices::Ones(5, 3), o), InvalidInput);
  Vertices bad = face().mesh.vertices;
  bad(3, 1) = std::nan("");
  EXPECT_THROW(frame_camera(bad, o), InvalidInput);
  EXPECT_THROW(fit_camera(face().mesh.vertices, o, 0.0), InvalidInput);
  EXPECT_EQ(visible_fraction(Vertices(0, 3), o), 0.0);
}

}  // namespace
}  // namespace emoface::facemesh
