#include "emoface/motiongraph/render.hpp"

#include <gtest/gtest.h>

#include <zlib.h>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {
namespace {

std::uint32_t be32(const std::string& s, std::size_t o) {
  return (std::uint32_t(std::uint8_t(s[o])) << 24) | (std::uint32_t(std::uint8_t(s[o + 1])) << 16) |
         (std::uint32_t(std::uint8_t(s[o + 2])) << 8) | std::uint32_t(std::uint8_t(s[o + 3]));
}

TEST(Render, PngDecodesBackToThePixels) {
  Image img(5, 3);
  img.set(1, 2, 0x102030);
  img.set(-1, 0, 0xff0000);  // ignored
  const std::string png = encode_png(img);
  ASSERT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(be32(png, 16), 5u);
  EXPECT_EQ(be32(png, 20), 3u);
  const std::size_t idat = png.find("IDAT");
  const std::uint32_t len = be32(png, idat - 4);
  std::string raw(3 * (1 + 5 * 3), '\0');
  uLongf size = raw.size();
  ASSERT_EQ(uncompress(reinterpret_cast<Bytef*>(raw.data()), &size,
                       reinterpret_cast<const Bytef*>(png.data() + idat + 4), len), Z_OK);
  ASSERT_EQ(size, raw.size());
  // Undo the row filters (0 None or 1 Sub, PNG spec §9.2) to get the pixels back.
  for (int y = 0; y < 3; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * 16;
    ASSERT_TRUE(raw[row] == 0 || raw[row] == 1) << "filter " << int(raw[row]);
    if (raw[row] == 1)
      for (std::size_t x = 3; x < 15; ++x) raw[row + 1 + x] = static_cast<char>(raw[row + 1 + x] + raw[row + 1 + x - 3]);
  }
  EXPECT_EQ(std::uint8_t(raw[2 * 16 + 1 + 3]), 0x10);
  EXPECT_EQ(std::uint8_t(raw[2 * 16 + 1 + 5]), 0x30);
  EXPECT_EQ(std::uint8_t(raw[1]), 255);
  // CRC of IEND is the well-known ae426082.
  EXPECT_EQ(be32(png, png.size() - 4), 0xae426082u);
}

TEST(Render, FitViewContactSheetAndPlot) {
  Pose p(2, 2);
  p << 10, 10, 110, 60;  // 100 × 50 box
  const View v = fit_view({p}, 200, 100, 0.0);
  EXPECT_DOUBLE_EQ(v.scale, 2.0);
  EXPECT_DOUBLE_EQ(v.offset_x + v.scale * 10, 0.0);
  EXPECT_DOUBLE_EQ(v.offset_y + v.scale * 60, 100.0);
  const Image sheet = contact_sheet({p, p, p}, {0, 1}, 2, 100, 50);
  EXPECT_EQ(sheet.width, 200);
  EXPECT_EQ(sheet.height, 100);
  // Landmark 0 of cell 1 (top right) sits at the fitted position, coloured.
  const View c = fit_view({p}, 100, 50);
  const int x = 100 + static_cast<int>(c.offset_x + c.scale * 10), y = static_cast<int>(c.offset_y + c.scale * 10);
  EXPECT_NE(sheet.rgb[(static_cast<std::size_t>(y) * 200 + static_cast<std::size_t>(x)) * 3], 255);
  const Image plot = plot_series({{0, 1, 2}, {2, 1, 0}}, 100, 50);
  EXPECT_EQ(plot.rgb.size(), 100u * 50u * 3u);
  const Image traj = plot_trajectories({p, p}, {0, 1});
  EXPECT_EQ(traj.width, 640);
  EXPECT_THROW(contact_sheet({}, {}, 2), InvalidInput);
  EXPECT_THROW(contact_sheet({p}, {}, 0), InvalidInput);
  EXPECT_THROW(fit_view({p}, 100, 100, 0.6), InvalidInput);
  EXPECT_THROW(Image(0, 5), InvalidInput);
}

}  // namespace
}  // namespace emoface::motiongraph

namespace emoface::motiongraph {
namespace {

// Issue 19: landmark sheets with contour lines.
TEST(Contours, Ibug68GroupsAndSubsets) {
  const auto& c = ibug68_contours();
  ASSERT_EQ(c.size(), 9u);
  EXPECT_EQ(c[0].front(), 0);
  EXPECT_EQ(c[0].back(), 16);
  EXPECT_EQ(c[5], (std::vector<int>{36, 37, 38, 39, 40, 41, 36}));  // right eye, closed
  // Reduced landmarks (as synthesized poses carry them): rows of the ids present, in contour order.
  const std::vector<int> ids = {36, 39, 42, 45, 17, 21, 48, 54, 57};
  const auto sub = contours_for(ids);
  // brows: {17, 21} → rows 4, 5; right eye: 36, 39, (36) → rows 0, 1, 0; left eye 42, 45, 42 → 2, 3, 2;
  // outer lips 48, 54, 57, 48 → 6, 7, 8, 6; the rest has < 2 landmarks.
  ASSERT_EQ(sub.size(), 4u);
  EXPECT_EQ(sub[0], (std::vector<int>{4, 5}));
  EXPECT_EQ(sub[1], (std::vector<int>{0, 1, 0}));
  EXPECT_EQ(sub[2], (std::vector<int>{2, 3, 2}));
  EXPECT_EQ(sub[3], (std::vector<int>{6, 7, 8, 6}));
  // A closed contour without its first landmark does not end on a repeat.
  EXPECT_EQ(contours_for({37, 38}), (std::vector<std::vector<int>>{{0, 1}}));
}

TEST(Contours, LinesAreDrawnBetweenTheLandmarks) {
  Pose p(2, 2);
  p << 10, 10, 50, 10;
  Image img(60, 20);
  View v;  // identity
  draw_contours(img, p, {{0, 1}}, v, 0x123456);
  auto at = [&](int x, int y) {
    const std::uint8_t* q = &img.rgb[(static_cast<std::size_t>(y) * 60 + x) * 3];
    return (q[0] << 16) | (q[1] << 8) | q[2];
  };
  EXPECT_EQ(at(30, 10), 0x123456);  // midway
  EXPECT_NE(at(30, 15), 0x123456);
  EXPECT_THROW(draw_contours(img, p, {{0, 2}}, v), InvalidInput);
  // The sheet draws them under the dots.
  const Image sheet = contact_sheet({p}, {}, 1, 64, 32, {{0, 1}});
  std::size_t grey = 0;
  for (std::size_t i = 0; i + 2 < sheet.rgb.size(); i += 3)
    grey += sheet.rgb[i] == 0xb0 && sheet.rgb[i + 1] == 0xb0 && sheet.rgb[i + 2] == 0xb0;
  EXPECT_GT(grey, 20u);
}

}  // namespace
}  // namespace emoface::motiongraph
