#include "emoface/parlee/chart.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"

namespace emoface::parlee {
namespace {

std::array<std::uint8_t, 3> pixel(const RgbImage& im, int x, int y) {
  const auto i = (static_cast<std::size_t>(y) * im.width + x) * 3;
  return {im.rgb[i], im.rgb[i + 1], im.rgb[i + 2]};
}

TEST(Chart, LayoutAndSeries) {
  ChartSeries s;
  s.x = {0, 50, 100};
  s.y = {0, 1, 0};
  s.rgb = {10, 200, 30};
  ChartOptions o;
  o.width = 416;  // plot width 416 − 40 − 16 = 360 px: x = 50 → pixel 40 + 180
  o.panel_height = 100;
  const RgbImage im = draw_chart({{"a", {s}, 1.0}, {"b", {}, 2.0}}, o);
  EXPECT_EQ(im.width, 416);
  EXPECT_EQ(im.height, 8 + 2 * 100 + 22 + 28);  // top + panels + gap + axis labels
  EXPECT_EQ(im.rgb.size(), 416u * im.height * 3u);
  EXPECT_EQ(pixel(im, 220, 8), s.rgb);   // the peak (50, 1) touches the top of panel 1
  EXPECT_EQ(pixel(im, 40 + 90, 58), s.rgb);  // (25, 0.5): halfway up the rising line
  o.markers = {{50, "1-0", {255, 0, 0}}};
  o.x_max = 100;  // no series to take the range from
  const RgbImage marked = draw_chart({{"a", {}, 1.0}}, o);
  EXPECT_EQ(marked.height, 8 + 100 + 44);  // room for the marker labels
  EXPECT_EQ(pixel(marked, 220, 50), (std::array<std::uint8_t, 3>{255, 0, 0}));
}

TEST(Chart, PngCarriesTheVersionStamp) {
  ChartOptions o;
  const std::string png = render_chart({{"x", {}, 1.0}}, o);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_NE(png.find("tEXtSoftware"), std::string::npos);
  EXPECT_NE(png.find(kGenerator), std::string::npos);
}

TEST(Chart, Text) {
  RgbImage im{40, 12, std::vector<std::uint8_t>(40 * 12 * 3, 255)};
  draw_text(im, 0, 0, "1", {0, 0, 0}, 2);  // glyph '1' row 0 = 010: pixels x 2..3 set
  EXPECT_EQ(pixel(im, 2, 0), (std::array<std::uint8_t, 3>{0, 0, 0}));
  EXPECT_EQ(pixel(im, 0, 0), (std::array<std::uint8_t, 3>{255, 255, 255}));
  draw_text(im, 30, 0, "zzzz", {0, 0, 0}, 2);  // clipped, no crash
  EXPECT_EQ(text_width("abc", 2), 24);
}

TEST(Chart, RejectsBadInput) {
  ChartOptions o;
  EXPECT_THROW(draw_chart({}, o), InvalidInput);
  EXPECT_THROW(draw_chart({{"a", {}, 0.0}}, o), InvalidInput);
  o.width = 10;
  EXPECT_THROW(draw_chart({{"a", {}, 1.0}}, o), InvalidInput);
  o = {};
  o.x_max = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(o.validate(), InvalidInput);
  EXPECT_THROW(encode_png(RgbImage{2, 2, {1, 2, 3}}), InvalidInput);
}

TEST(Chart, EmotionPanels) {
  std::vector<StepRecord> run(3);
  for (std::size_t k = 0; k < 3; ++k) {
    run[k].time = static_cast<double>(k) * 10;
    run[k].basic[3] = 0.1 * static_cast<double>(k);
  }
  const auto panels = emotion_panels("neutral", run);
  ASSERT_EQ(panels.size(), 4u);
  EXPECT_EQ(panels[0].title, "neutral fear");
  EXPECT_EQ(panels[0].series[0].y, (std::vector<double>{0.0, 0.1, 0.2}));
  EXPECT_EQ(panels[0].series[0].x, (std::vector<double>{0, 10, 20}));
}

}  // namespace
}  // namespace emoface::parlee
