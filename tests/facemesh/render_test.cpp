#include "emoface/facemesh/render.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

std::size_t non_background(const Image& im, const RenderOptions& o) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < im.rgb.size(); i += 3) {
    if (std::abs(im.rgb[i] - o.background.x() * 255) > 2 || std::abs(im.rgb[i + 1] - o.background.y() * 255) > 2) ++n;
  }
  return n;
}

TEST(Render, DrawsTheDefaultFaceInBothViews) {
  const Face f = make_default_face();
  RenderOptions o;
  o.width = 96;
  o.height = 112;
  for (View v : {View::Front, View::ThreeQuarter}) {
    o.view = v;
    const Image im = render(f.mesh, material_colors(f.rig), {}, o);
    ASSERT_EQ(im.rgb.size(), 96u * 112u * 3u);
    const std::size_t covered = non_background(im, o);
    EXPECT_GT(covered, 96u * 112u / 4) << to_string(v);
    EXPECT_LT(covered, 96u * 112u) << to_string(v);
    // the centre of the image is the face, not the background
    const std::size_t c = (56u * 96u + 48u) * 3u;
    EXPECT_GT(std::abs(im.rgb[c] - 237), 3);
  }
}

TEST(Render, ShadingFollowsTheLight) {
  // Two squares facing the camera, one tilted away from the key light: it must be darker.
  Mesh m;
  m.vertices.resize(4, 3);
  m.vertices << -0.05, -0.05, 0, 0.05, -0.05, 0, 0.05, 0.05, 0, -0.05, 0.05, 0;
  m.faces.resize(2, 3);
  m.faces << 0, 1, 2, 0, 2, 3;
  RenderOptions o;
  o.width = o.height = 32;
  o.target = Eigen::Vector3d::Zero();
  const Image flat = render(m, {}, {}, o);
  Mesh tilted = m;
  for (long v = 0; v < 4; ++v) tilted.vertices(v, 2) = 0.5 * tilted.vertices(v, 0);  // normal turns to −x
  const Image dark = render(tilted, {}, {}, o);
  const std::size_t c = (16u * 32u + 16u) * 3u;
  EXPECT_GT(flat.rgb[c], dark.rgb[c]);  // key light comes from −x... so check the ordering is consistent
}

TEST(Render, Validation) {
  RenderOptions o;
  o.width = 0;
  EXPECT_THROW(o.validate(), InvalidInput);
  o = RenderOptions{};
  o.field_of_view = 3.0;
  EXPECT_THROW(o.validate(), InvalidInput);
  EXPECT_THROW(view_from_string("side"), InvalidInput);
  EXPECT_EQ(view_from_string(to_string(View::ThreeQuarter)), View::ThreeQuarter);
  const Mesh t = testing::tetrahedron();
  EXPECT_THROW(render(t, std::vector<Eigen::Vector3f>(3), {}, RenderOptions{}), InvalidInput);
}

class Png : public testing::TempDirTest {};

TEST_F(Png, SheetAndPngBytes) {
  Image a;
  a.width = 4;
  a.height = 3;
  a.rgb.assign(36, 10);
  const Image s = contact_sheet({a, a, a}, 2, 1);
  EXPECT_EQ(s.width, 2 * 4 + 3);
  EXPECT_EQ(s.height, 2 * 3 + 3);
  EXPECT_EQ(s.rgb[((1u * s.width) + 1u) * 3u], 10);  // first tile starts at (1,1)
  EXPECT_EQ(s.rgb[0], 255);                        // gap
  Image b = a;
  b.width = 5;
  b.rgb.assign(45, 0);
  EXPECT_THROW(contact_sheet({a, b}, 2), InvalidInput);
  EXPECT_THROW(contact_sheet({}, 2), InvalidInput);
  EXPECT_THROW(contact_sheet({a}, 0), InvalidInput);
  const std::string png = encode_png(a);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  write_png(path("a.png"), a);
  EXPECT_EQ(core::read_file(path("a.png")), png);
}

}  // namespace
}  // namespace emoface::facemesh
