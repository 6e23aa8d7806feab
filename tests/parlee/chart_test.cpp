#include "emoface/parlee/chart.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"

namespace emoface::parlee {
namespace {

std::array<std::uint8_t, 3> pixel(const core::Image& im, int x, int y) {
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
  const core::Image im = draw_chart({{"a", {s}, 1.0}, {"b", {}, 2.0}}, o);
  EXPECT_EQ(im.width, 416);
  EXPECT_EQ(im.height, 8 + 2 * 100 + 22 + 28);  // top + panels + gap + axis labels
  EXPECT_EQ(im.rgb.size(), 416u * im.height * 3u);
  EXPECT_EQ(pixel(im, 220, 8), s.rgb);   // the peak (50, 1) touches the top of panel 1
  EXPECT_EQ(pixel(im, 40 + 90, 58), s.rgb);  // (25, 0.5): halfway up the rising line
  o.markers = {{50, "1-0", {255, 0, 0}}};
  o.x_max = 100;  // no series to take the range from
  const core::Image marked = draw_chart({{"a", {}, 1.0}}, o);
  EXPECT_EQ(marked.height, 8 + 100 + 44);  // room for the marker labels
  EXPECT_EQ(pixel(marked, 220, 50), (std::array<std::uint8_t, 3>{255, 0, 0}));
}

// Issue 19 item 4: title, legend, axis labels and y tick values.
TEST(Chart, TitleLegendAxisLabelsAndTicks) {
  ChartSeries a, b;
  a.x = b.x = {0, 100};
  a.y = {0.2, 0.2};
  b.y = {0.6, 0.6};
  a.rgb = {200, 0, 0};
  b.rgb = {0, 0, 200};
  a.name = "neutral";
  b.name = "sensitive";
  ChartOptions o;
  o.width = 416;
  o.panel_height = 100;
  o.x_max = 100;
  const core::Image plain = draw_chart({{"p", {a, b}, 1.0}}, o);
  o.title = "happiness";
  o.x_label = "match minute";
  o.y_label = "intensity";
  const ChartLayout l = chart_layout({{"p", {a, b}, 1.0}}, o);
  // title row 6 + 20, legend row + 18; y label column: left 56; x label row + 16
  EXPECT_EQ(l.top, 6 + 20 + 18);
  EXPECT_EQ(l.left, 56);
  EXPECT_EQ(l.height, l.top + 100 + 28 + 16);
  const core::Image im = draw_chart({{"p", {a, b}, 1.0}}, o);
  EXPECT_EQ(im.height, l.height);
  EXPECT_EQ(plain.height, 6 + 18 + 100 + 28);  // named series: a legend row, no title
  auto count = [&](int x0, int y0, int x1, int y1, std::array<std::uint8_t, 3> c) {
    int k = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) k += pixel(im, x, y) == c;
    return k;
  };
  const std::array<std::uint8_t, 3> ink{40, 40, 40};
  // legend swatches (18 × 4 px lines) in the series colours, the first at the plot's left edge
  EXPECT_EQ(pixel(im, l.left + 9, l.legend_y + 4), a.rgb);
  const int second = l.left + 24 + core::text_width("neutral") + 20;
  EXPECT_EQ(pixel(im, second + 9, l.legend_y + 4), b.rgb);
  EXPECT_GT(count(l.left + 24, l.legend_y, second, l.legend_y + 10, ink), 40);  // "neutral"
  // title ink centred above, x label ink below the tick values, y label ink left of the ticks
  const int pw = l.plot_width;
  const int tx = l.left + (pw - core::text_width("happiness")) / 2;
  EXPECT_GT(count(tx, l.title_y, tx + core::text_width("happiness"), l.title_y + 10, ink), 60);
  EXPECT_EQ(count(0, l.title_y, tx - 1, l.title_y + 10, ink), 0);
  EXPECT_GT(count(l.left, l.height - 16, l.left + pw, l.height, ink), 60);
  EXPECT_GT(count(0, l.top, 16, l.top + 100, ink), 60);
  // y tick values: "1" at the top, "0.5" in the middle (24 px wide, right-aligned at left − 6)
  EXPECT_GT(count(l.left - 6 - 24, l.top + 45, l.left - 6, l.top + 55, ink), 10);
  EXPECT_GT(count(l.left - 6 - 8, l.top, l.left - 6, l.top + 10, ink), 5);
  // the series are where they were, shifted by the layout: y = 0.2 → 80 px down the panel
  EXPECT_EQ(pixel(im, l.left + pw / 2, l.top + 80), a.rgb);
}

TEST(Chart, PngCarriesTheVersionStamp) {
  ChartOptions o;
  const std::string png = render_chart({{"x", {}, 1.0}}, o);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_NE(png.find("tEXtSoftware"), std::string::npos);
  EXPECT_NE(png.find(kGenerator), std::string::npos);
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
  EXPECT_EQ(panels[0].series[0].name, "fear");
  EXPECT_EQ(panels[0].series[0].y, (std::vector<double>{0.0, 0.1, 0.2}));
  EXPECT_EQ(panels[0].series[0].x, (std::vector<double>{0, 10, 20}));
}

}  // namespace
}  // namespace emoface::parlee
