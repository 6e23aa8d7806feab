#include "emoface/motiongraph/render.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {
namespace {

TEST(Render, FitViewContactSheetAndPlot) {
  Pose p(2, 2);
  p << 10, 10, 110, 60;  // 100 × 50 box
  const View v = fit_view({p}, 200, 100, 0.0);
  EXPECT_DOUBLE_EQ(v.scale, 2.0);
  EXPECT_DOUBLE_EQ(v.offset_x + v.scale * 10, 0.0);
  EXPECT_DOUBLE_EQ(v.offset_y + v.scale * 60, 100.0);
  const core::Image sheet = contact_sheet({p, p, p}, {0, 1}, 2, 100, 50);
  EXPECT_EQ(sheet.width, 200);
  EXPECT_EQ(sheet.height, 100);
  // Landmark 0 of cell 1 (top right) sits at the fitted position, coloured.
  const View c = fit_view({p}, 100, 50);
  const int x = 100 + static_cast<int>(c.offset_x + c.scale * 10), y = static_cast<int>(c.offset_y + c.scale * 10);
  EXPECT_NE(sheet.rgb[(static_cast<std::size_t>(y) * 200 + static_cast<std::size_t>(x)) * 3], 255);
  const core::Image plot = plot_series({{0, 1, 2}, {2, 1, 0}}, 100, 50);
  EXPECT_EQ(plot.rgb.size(), 100u * 50u * 3u);
  // core::draw_chart's layout without text: columns 10 … 84 (100 − 10 − 16), two bands of
  // (50 − 8 − 8) / 2 = 17 rows from row 8. Each series' range [0, 2] (= min_range) spans 85 % of
  // its band: y from 1 − 2/1.7 to 1 + 2/1.7, so 0 lies 1.275 rows above a band's bottom, 2 15.725
  // rows.
  const core::Rgb blue = core::rgb_from_hex(0x1f77b4), red = core::rgb_from_hex(0xd62728);
  EXPECT_EQ(plot.at(10, 24), blue);  // (0, 0): row 25 − 1.275
  EXPECT_EQ(plot.at(84, 9), blue);   // (2, 2): row 25 − 15.725
  EXPECT_EQ(plot.at(10, 26), red);   // (0, 2) in the second band: row 42 − 15.725
  EXPECT_EQ(plot.at(84, 41), red);   // (2, 0): row 42 − 1.275
  EXPECT_EQ(plot.at(47, 44),
            (core::Rgb{120, 120, 120}));  // sample 1's tick under the axis (row 42)
  EXPECT_THROW(plot_series({{0, 1}}, 100, 50, 0.0), InvalidInput);
  const core::Image traj = plot_trajectories({p, p}, {0, 1});
  EXPECT_EQ(traj.width, 640);
  EXPECT_THROW(contact_sheet({}, {}, 2), InvalidInput);
  EXPECT_THROW(contact_sheet({p}, {}, 0), InvalidInput);
  EXPECT_THROW(fit_view({p}, 100, 100, 0.6), InvalidInput);
  EXPECT_THROW(core::Image(0, 5), InvalidInput);
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
  core::Image img(60, 20);
  View v;  // identity
  draw_contours(img, p, {{0, 1}}, v, 0x123456);
  const core::Rgb ink = core::rgb_from_hex(0x123456);
  EXPECT_EQ(img.at(30, 10), ink);  // midway
  EXPECT_EQ(img.at(30, 11), ink);  // 2 pixels thick (core::draw_line)
  EXPECT_NE(img.at(30, 12), ink);
  EXPECT_NE(img.at(30, 9), ink);
  EXPECT_EQ(img.at(51, 10), ink);  // the stamp reaches one pixel right of the end
  EXPECT_NE(img.at(52, 10), ink);
  EXPECT_NE(img.at(9, 10), ink);
  EXPECT_THROW(draw_contours(img, p, {{0, 2}}, v), InvalidInput);
  // The sheet draws them under the dots.
  const core::Image sheet = contact_sheet({p}, {}, 1, 64, 32, {{0, 1}});
  std::size_t grey = 0;
  for (std::size_t i = 0; i + 2 < sheet.rgb.size(); i += 3)
    grey += sheet.rgb[i] == 0xb0 && sheet.rgb[i + 1] == 0xb0 && sheet.rgb[i + 2] == 0xb0;
  EXPECT_GT(grey, 20u);
}

}  // namespace
}  // namespace emoface::motiongraph
