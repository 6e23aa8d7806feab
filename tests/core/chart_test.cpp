// core::draw_chart (issue 18 item 3): pixel positions worked out by hand from the mapping in
// chart.hpp (each test's comments), log axes, gaps, clipping, degenerate ranges, tick values and
// their thinning, the legend, markers, layouts of the parlee charts it replaced, bad specs naming
// their field, and a property test over random series (no ink outside the plot, same bytes twice).
#include "emoface/core/chart.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::core {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr Rgb kRed{200, 0, 0}, kBlue{0, 0, 200}, kInk{40, 40, 40}, kWhite{255, 255, 255};

// A one-panel chart without text: left = 10, plot_width = width − 26, top = 8, so with width 126
// and panel height 100 the x range maps onto columns 10 … 110 and the y range onto rows 108 … 8.
ChartSpec plain(double x_max = 100, double y_max = 1) {
  ChartSpec spec;
  spec.width = 126;
  spec.text_scale = 0;
  spec.x.min = 0;
  spec.x.max = x_max;
  ChartPanel panel;
  panel.height = 100;
  panel.y.min = 0;
  panel.y.max = y_max;
  spec.panels.push_back(panel);
  return spec;
}

ChartSeries series(std::vector<double> x, std::vector<double> y, Rgb colour = kRed,
                   int thickness = 1) {
  ChartSeries s;
  s.x = std::move(x);
  s.y = std::move(y);
  s.colour = colour;
  s.thickness = thickness;
  return s;
}

int count(const Image& im, Rgb c, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
  if (x1 < 0) x1 = im.width;
  if (y1 < 0) y1 = im.height;
  int k = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) k += im.at(x, y) == c;
  return k;
}

TEST(Chart, APointLandsWhereTheMappingSays) {
  ChartSpec spec = plain();
  spec.panels[0].series.push_back(series({50}, {0.25}));
  const ChartLayout l = chart_layout(spec);
  EXPECT_EQ(l.left, 10);
  EXPECT_EQ(l.plot_width, 100);
  EXPECT_EQ(l.panel_top[0], 8);
  EXPECT_EQ(l.axis_y, 108);
  EXPECT_EQ(l.height, 108 + 8);
  EXPECT_DOUBLE_EQ(l.x_pixel(50), 60.0);       // 10 + 50/100 · 100
  EXPECT_DOUBLE_EQ(l.y_pixel(0, 0.25), 83.0);  // 8 + 100 − 0.25 · 100
  const Image im = draw_chart(spec);
  ASSERT_EQ(im.width, 126);
  ASSERT_EQ(im.height, 116);
  EXPECT_EQ(count(im, kRed), 1);  // an isolated point is a dot of its thickness
  EXPECT_EQ(im.at(60, 83), kRed);
  // the frame: left column 10, right column 110, top row 8, bottom row 108
  const Rgb frame{120, 120, 120};
  EXPECT_EQ(im.at(10, 50), frame);
  EXPECT_EQ(im.at(110, 50), frame);
  EXPECT_EQ(im.at(50, 8), frame);
  EXPECT_EQ(im.at(50, 108), frame);
  EXPECT_EQ(im.at(9, 50), kWhite);
  EXPECT_EQ(im.at(111, 50), kWhite);
}

TEST(Chart, ALineRunsBetweenItsMappedEnds) {
  ChartSpec spec = plain();
  spec.panels[0].series.push_back(series({0, 100}, {0.5, 0.5}, kRed, 3));
  const Image im = draw_chart(spec);
  // y = 0.5 → row 58; thickness 3 covers rows 57 … 59 over columns 10 … 110 (then 1 px beyond)
  for (int x = 10; x <= 110; ++x)
    for (int y = 57; y <= 59; ++y) ASSERT_EQ(im.at(x, y), kRed) << x << "," << y;
  EXPECT_EQ(count(im, kRed, 0, 0, -1, 57), 0);
  EXPECT_EQ(count(im, kRed, 0, 60), 0);
}

TEST(Chart, Log10AxisMapsDecadesEvenly) {
  ChartSpec spec = plain();
  spec.panels[0].height = 90;
  spec.panels[0].y.scale = AxisScale::Log10;
  spec.panels[0].y.min = 1;
  spec.panels[0].y.max = 1000;  // three decades over 90 px: 30 px per decade
  spec.panels[0].series.push_back(series({0, 50, 100}, {10, 100, -5}));
  const ChartLayout l = chart_layout(spec);
  EXPECT_DOUBLE_EQ(l.y_lo[0], 0.0);
  EXPECT_DOUBLE_EQ(l.y_hi[0], 3.0);
  EXPECT_DOUBLE_EQ(l.y_pixel(0, 10), 68.0);  // 8 + 90 − 30
  EXPECT_DOUBLE_EQ(l.y_pixel(0, 100), 38.0);
  EXPECT_TRUE(std::isnan(l.y_pixel(0, 0.0)));  // not drawable on a log axis
  const Image im = draw_chart(spec);
  EXPECT_EQ(im.at(10, 68), kRed);
  EXPECT_EQ(im.at(60, 38), kRed);
  EXPECT_EQ(im.at(35, 53), kRed);  // halfway along the segment
  // −5 has no logarithm: a gap after (50, 100), nothing right of column 61
  EXPECT_EQ(count(im, kRed, 62, 0), 0);
}

TEST(Chart, NonFinitePointsLeaveAGap) {
  ChartSpec spec = plain(4);
  // x 0 … 4 → columns 10, 35, 60, 85, 110; y 0.5 → row 58
  spec.panels[0].series.push_back(series({0, 1, 2, 3, 4}, {0.5, 0.5, kNaN, 0.5, 0.5}));
  spec.panels[0].series.push_back(series({0, 1, 2, 3, 4}, {0.2, kInf, 0.2, -kInf, 0.2}, kBlue));
  const Image im = draw_chart(spec);
  EXPECT_EQ(count(im, kRed, 10, 58, 36, 59), 26);  // 10 … 35
  EXPECT_EQ(count(im, kRed, 36, 0, 85, -1), 0);    // the gap
  EXPECT_EQ(count(im, kRed, 85, 58, 111, 59), 26);
  // y 0.2 → row 88: three isolated dots at columns 10, 60, 110 and nothing between
  EXPECT_EQ(count(im, kBlue), 3);
  EXPECT_EQ(im.at(10, 88), kBlue);
  EXPECT_EQ(im.at(60, 88), kBlue);
  EXPECT_EQ(im.at(110, 88), kBlue);
}

TEST(Chart, OutOfRangeValuesAreClippedAtTheFrame) {
  ChartSpec spec = plain();
  // (0, 0.5) → (100, 1.5) leaves the range at y = 1, x = 50: the line stops at (60, 8)
  spec.panels[0].series.push_back(series({0, 100}, {0.5, 1.5}));
  // wholly below the range: nothing
  spec.panels[0].series.push_back(series({0, 100}, {-1, -2}, kBlue));
  const Image im = draw_chart(spec);
  EXPECT_EQ(im.at(10, 58), kRed);
  EXPECT_EQ(im.at(60, 8), kRed);
  EXPECT_EQ(count(im, kRed, 61, 0), 0);
  EXPECT_EQ(count(im, kRed, 0, 0, -1, 8), 0);
  EXPECT_EQ(count(im, kBlue), 0);
}

TEST(Chart, DegenerateAndMissingRanges) {
  ChartSpec spec = plain();
  spec.x = {};  // from data
  spec.panels[0].y = {};
  spec.panels[0].series.push_back(series({5, 5}, {3, 3}));
  ChartLayout l = chart_layout(spec);
  EXPECT_DOUBLE_EQ(l.x_lo, 4.5);  // one value v → [v − ½, v + ½]
  EXPECT_DOUBLE_EQ(l.x_hi, 5.5);
  EXPECT_DOUBLE_EQ(l.y_lo[0], 2.5);
  EXPECT_DOUBLE_EQ(l.y_hi[0], 3.5);
  EXPECT_EQ(draw_chart(spec).at(60, 58), kRed);  // the middle of the plot
  // a given lower end and data all at it: the free upper end one unit above
  spec.panels[0].y.min = 3;
  l = chart_layout(spec);
  EXPECT_DOUBLE_EQ(l.y_lo[0], 3.0);
  EXPECT_DOUBLE_EQ(l.y_hi[0], 4.0);
  // log10: all 100 → [1.5, 2.5] decades; no data at all → [0, 1]
  spec.panels[0].y = {};
  spec.panels[0].y.scale = AxisScale::Log10;
  spec.panels[0].series[0].y = {100, 100};
  l = chart_layout(spec);
  EXPECT_DOUBLE_EQ(l.y_lo[0], 1.5);
  EXPECT_DOUBLE_EQ(l.y_hi[0], 2.5);
  spec.panels[0].series.clear();
  l = chart_layout(spec);
  EXPECT_DOUBLE_EQ(l.x_lo, 0.0);
  EXPECT_DOUBLE_EQ(l.x_hi, 1.0);
  EXPECT_DOUBLE_EQ(l.y_lo[0], 0.0);
  EXPECT_DOUBLE_EQ(l.y_hi[0], 1.0);
  EXPECT_NO_THROW(draw_chart(spec));
  // series without x: the indices 0 … n − 1
  spec.panels[0].series.push_back(series({}, {1, 10, 100}));
  l = chart_layout(spec);
  EXPECT_DOUBLE_EQ(l.x_lo, 0.0);
  EXPECT_DOUBLE_EQ(l.x_hi, 2.0);
  EXPECT_DOUBLE_EQ(l.y_lo[0], 0.0);
  EXPECT_DOUBLE_EQ(l.y_hi[0], 2.0);
}

TEST(Chart, TickMarksValuesAndThinning) {
  ChartSpec spec = plain();
  spec.text_scale = 1;
  spec.x.tick_step = 10;
  spec.x.grid_step = 10;
  spec.panels[0].y.tick_step = 0.5;
  const ChartLayout l = chart_layout(spec);
  // y tick values "0", "0.5", "1": the widest is 12 px at scale 1 → left = 10 + 12 + 6
  EXPECT_EQ(l.left, 28);
  EXPECT_EQ(l.plot_width, 126 - 28 - 16);
  EXPECT_EQ(l.tick_label_y, l.axis_y + 8);
  EXPECT_EQ(l.height, l.axis_y + 8 + 5 + 10);
  const Image im = draw_chart(spec);
  const Rgb frame{120, 120, 120}, grid{225, 225, 225};
  // x = 10 k → column 28 + 8.2 k; marks on rows axis + 1 … axis + 4, grid lines inside
  for (int k = 0; k <= 10; ++k) {
    const int x = static_cast<int>(std::lround(28 + 8.2 * k));
    EXPECT_EQ(im.at(x, l.axis_y + 2), frame) << k;
    if (k > 0 && k < 10) {
      EXPECT_EQ(im.at(x, 50), grid) << k;
    }
  }
  // labels ("100" is 12 px + 2) need 14 px, ticks are 8.2 px apart: every second one is labelled
  const int ty = l.tick_label_y;
  EXPECT_GT(count(im, kInk, 26, ty, 31, ty + 5), 0);  // "0" centred on 28
  EXPECT_EQ(count(im, kInk, 30, ty, 40, ty + 5), 0);  // no "10" at 36
  EXPECT_GT(count(im, kInk, 40, ty, 48, ty + 5), 0);  // "20" 8 px wide from 44 − 4
  // y: "1" at the top (clamped into the panel), "0.5" centred on row 58, right-aligned at 22
  EXPECT_GT(count(im, kInk, 22 - 12, 56, 22, 61), 5);
  EXPECT_GT(count(im, kInk, 22 - 4, 8, 22, 13), 2);
  EXPECT_EQ(im.at(24, 58), frame);  // the tick mark at left − 4
  EXPECT_EQ(chart_tick_text(0.5), "0.5");
  EXPECT_EQ(chart_tick_text(10), "10");
  EXPECT_EQ(chart_tick_text(3 * 0.1), "0.3");
  EXPECT_EQ(chart_tick_text(-0.0), "0");
  EXPECT_EQ(chart_tick_text(1e-5), "1e-5");
  EXPECT_EQ(chart_tick_text(1e6), "1e6");
  EXPECT_EQ(chart_tick_text(25000), "2.5e4");
  EXPECT_EQ(chart_tick_text(-2.5), "-2.5");
}

TEST(Chart, AFineStepOverAWideRangeGrowsByPowersOfTen) {
  ChartSpec spec = plain();
  spec.panels[0].y.grid_step = 1e-5;  // 100,001 lines in [0, 1]: 1e-3 is the first step ≤ 10,000
  const Image im = draw_chart(spec);
  const Rgb grid{225, 225, 225};
  // 1e-3 is under a tenth of a pixel: every row inside the panel is a grid row
  for (int y = 9; y < 108; ++y) EXPECT_EQ(im.at(50, y), grid) << y;
  spec.panels[0].y.grid_step = 0.25;  // rows 8 + 25 k
  spec.panels[0].y.max = 1;
  const Image quarter = draw_chart(spec);
  for (int y : {33, 58, 83}) EXPECT_EQ(quarter.at(50, y), grid) << y;
  EXPECT_EQ(quarter.at(50, 45), kWhite);
}

TEST(Chart, Log10TickValuesArePowersOfTen) {
  ChartSpec spec = plain();
  spec.text_scale = 1;
  spec.panels[0].y.scale = AxisScale::Log10;
  spec.panels[0].y.min = 1;
  spec.panels[0].y.max = 1000;
  spec.panels[0].y.tick_step = 1;
  spec.panels[0].height = 90;
  const ChartLayout l = chart_layout(spec);
  EXPECT_EQ(l.left, 10 + text_width("1000", 1) + 6);  // "1", "10", "100", "1000"
  const Image im = draw_chart(spec);
  // "100" right-aligned at left − 6 on row 38 (rows 36 … 40)
  Image expected(im.width, im.height, kWhite);
  draw_text(expected, l.left - 6 - 12, 36, "100", kInk, 1);
  for (int y = 36; y < 41; ++y)
    for (int x = l.left - 18; x < l.left - 6; ++x) EXPECT_EQ(im.at(x, y), expected.at(x, y));
}

TEST(Chart, LegendTitleMarkersAndLabels) {
  ChartSpec spec = plain();
  spec.width = 300;
  spec.text_scale = 2;
  spec.title = "title";
  spec.x.label = "time";
  spec.panels[0].y.label = "mood";
  spec.markers = {{50, "goal", kBlue}};
  ChartSeries a = series({0, 100}, {0.2, 0.2}), b = series({0, 100}, {0.6, 0.6}, kBlue);
  a.name = "fear";
  b.name = "joy";
  spec.panels[0].series = {a, b, a};  // a repeated entry is listed once
  const ChartLayout l = chart_layout(spec);
  EXPECT_EQ(l.title_y, 6);
  EXPECT_EQ(l.legend_y, 6 + 20);
  EXPECT_EQ(l.legend_rows, 1);
  EXPECT_EQ(l.panel_top[0], 26 + 18);
  EXPECT_EQ(l.left, 4 + 22);  // the vertical label, no y ticks
  EXPECT_EQ(l.marker_label_y, l.tick_label_y + 18);
  EXPECT_EQ(l.x_label_y, l.marker_label_y + 16);
  EXPECT_EQ(l.height, l.axis_y + 8 + 20 + 16 + 16);
  const Image im = draw_chart(spec);
  // the legend: swatch 19 × 4 px at (left, legend_y + 3), name 24 px right of the swatch's start
  EXPECT_EQ(im.at(l.left, l.legend_y + 3), kRed);
  EXPECT_EQ(im.at(l.left + 18, l.legend_y + 6), kRed);
  const int second = l.left + 24 + text_width("fear") + 20;
  EXPECT_EQ(im.at(second + 9, l.legend_y + 4), kBlue);
  Image expected(im.width, im.height, kWhite);
  draw_text(expected, l.left + 24, l.legend_y, "fear", kInk);
  draw_text(expected, second + 24, l.legend_y, "joy", kInk);
  draw_text(expected, l.left + (l.plot_width - text_width("title")) / 2, 6, "title", kInk);
  for (int y = 0; y < l.panel_top[0]; ++y)
    for (int x = 0; x < im.width; ++x)
      if (expected.at(x, y) == kInk) {
        ASSERT_EQ(im.at(x, y), kInk) << x << "," << y;
      }
  EXPECT_EQ(count(im, kInk, 0, 0, -1, l.panel_top[0]),
            count(expected, kInk, 0, 0, -1, l.panel_top[0]));
  // the marker: a line at x = 50 through the panel, its label centred under the tick values
  const int mx = static_cast<int>(std::lround(l.x_pixel(50)));
  EXPECT_EQ(im.at(mx, l.panel_top[0] + 5), kBlue);
  EXPECT_GT(count(im, kBlue, mx - 8, l.marker_label_y, mx + 8, l.marker_label_y + 10), 20);
  EXPECT_GT(count(im, kInk, l.left, l.x_label_y, l.left + l.plot_width, l.x_label_y + 10), 20);
  EXPECT_GT(count(im, kInk, 4, l.panel_top[0], 14, l.axis_y), 20);  // "mood", vertical
  // text_scale 0: no text at all, no legend rows
  spec.text_scale = 0;
  const Image bare = draw_chart(spec);
  EXPECT_EQ(count(bare, kInk), 0);
  EXPECT_EQ(chart_layout(spec).panel_top[0], 8);
}

TEST(Chart, LegendWrapsIntoRows) {
  ChartSpec spec = plain();
  spec.width = 200;
  spec.text_scale = 1;
  for (const char* name : {"happiness", "surprise", "sadness", "anger"}) {
    ChartSeries s = series({0, 1}, {0, 1});
    s.name = name;
    spec.panels[0].series.push_back(s);
  }
  // entries are 12 + 4·len + 10 px: 58, 54, 50, 42; the row runs from left 10 to 200 − 8
  const ChartLayout l = chart_layout(spec);
  EXPECT_EQ(l.legend_rows, 2);  // 10 + 58 + 54 + 50 = 172, + 42 > 192
  EXPECT_EQ(l.panel_top[0], 6 + 2 * 9);
}

// The two layouts of parlee's own chart test (parlee/chart_test.cpp before the move), kept: the
// emotion charts look as before.
TEST(Chart, StackedPanelsLikeTheParleeCharts) {
  ChartSpec spec;
  spec.width = 416;  // plot width 416 − 40 − 16 = 360 px: x = 50 → pixel 40 + 180
  spec.x.min = 0;
  spec.x.max = 100;
  spec.x.grid_step = spec.x.tick_step = 10;
  for (double y_max : {1.0, 2.0}) {
    ChartPanel p;
    p.height = 100;
    p.y.min = 0;
    p.y.max = y_max;
    p.y.grid_step = p.y.tick_step = y_max / 2;
    spec.panels.push_back(p);
  }
  spec.panels[0].series.push_back(series({0, 50, 100}, {0, 1, 0}, {10, 200, 30}, 2));
  const ChartLayout l = chart_layout(spec);
  EXPECT_EQ(l.left, 40);
  EXPECT_EQ(l.panel_top[1], 8 + 100 + 22);
  const Image im = draw_chart(spec);
  EXPECT_EQ(im.height, 8 + 2 * 100 + 22 + 28);        // top + panels + gap + axis labels
  EXPECT_EQ(im.at(220, 8), (Rgb{10, 200, 30}));       // the peak (50, 1) at the top of panel 1
  EXPECT_EQ(im.at(40 + 90, 58), (Rgb{10, 200, 30}));  // (25, 0.5): halfway up the rising line
  spec.markers = {{50, "1-0", {255, 0, 0}}};
  spec.panels.pop_back();
  spec.panels[0].series.clear();
  const Image marked = draw_chart(spec);
  EXPECT_EQ(marked.height, 8 + 100 + 44);  // room for the marker labels
  EXPECT_EQ(marked.at(220, 50), (Rgb{255, 0, 0}));
  // a given image height: the panels share what the margins leave
  spec.panels.push_back(spec.panels[0]);
  spec.height = 300;
  const ChartLayout shared = chart_layout(spec);
  EXPECT_EQ(shared.panel_height[0], (300 - 8 - 22 - 44) / 2);
  EXPECT_EQ(shared.panel_height[1], shared.panel_height[0]);
  EXPECT_EQ(draw_chart(spec).height, 300);
}

TEST(Chart, BadSpecsNameTheirField) {
  auto expect_field = [](const ChartSpec& spec, const std::string& field) {
    try {
      draw_chart(spec);
      ADD_FAILURE() << "no error for " << field;
    } catch (const InvalidInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind(field + ":", 0), 0u) << e.what();
    }
  };
  ChartSpec s = plain();
  s.width = 31;
  expect_field(s, "ChartSpec.width");
  s.width = 8193;
  expect_field(s, "ChartSpec.width");
  s = plain();
  s.height = 20;
  expect_field(s, "ChartSpec.height");
  s.height = 40;  // legal, but leaves the panel under 8 px
  s.text_scale = 2;
  s.x.label = "x";
  expect_field(s, "ChartSpec.height");
  s = plain();
  s.panels.clear();
  expect_field(s, "ChartSpec.panels");
  s = plain();
  s.panels[0].height = 7;
  expect_field(s, "ChartSpec.panels[0].height");
  s = plain();
  s.panels.push_back(s.panels[0]);
  s.panels[1].series.push_back(series({0, 1}, {1}));
  expect_field(s, "ChartSpec.panels[1].series[0].x");
  s.panels[1].series[0] = series({0}, {1}, kRed, 0);
  expect_field(s, "ChartSpec.panels[1].series[0].thickness");
  s = plain();
  s.x.max = -1;
  expect_field(s, "ChartSpec.x.max");
  s.x.max = kInf;
  expect_field(s, "ChartSpec.x.max");
  s = plain();
  s.panels[0].y.scale = AxisScale::Log10;  // min 0
  expect_field(s, "ChartSpec.panels[0].y.min");
  s = plain();
  s.panels[0].y.grid_step = -1;
  expect_field(s, "ChartSpec.panels[0].y.grid_step");
  s = plain();
  s.panels[0].y = {};  // from data that spans more than a double
  s.panels[0].series.push_back(series({0, 1}, {-1.7e308, 1.7e308}));
  expect_field(s, "ChartSpec.panels[0].y");
  s = plain();
  s.x.tick_step = kNaN;
  expect_field(s, "ChartSpec.x.tick_step");
  s = plain();
  s.markers = {{kNaN, "", kRed}};
  expect_field(s, "ChartSpec.markers[0].x");
  s = plain();
  s.text_scale = 9;
  expect_field(s, "ChartSpec.text_scale");
  s.text_scale = 8;
  s.panels[0].y.tick_step = 0.001;  // tick values "0.001" 160 px wide leave no plot
  expect_field(s, "ChartSpec.width");
  s = plain();
  s.panels.resize(65, s.panels[0]);
  expect_field(s, "ChartSpec.panels");
  s = plain();
  s.panels.resize(60, s.panels[0]);
  s.panels[0].height = 8000;  // 8 + 8000 + 59 · (100 + 22) + 8 > 8192
  expect_field(s, "ChartSpec.panels");
  EXPECT_EQ(axis_scale_from_string(to_string(AxisScale::Log10)), AxisScale::Log10);
  EXPECT_EQ(axis_scale_from_string(to_string(AxisScale::Linear)), AxisScale::Linear);
  EXPECT_THROW(axis_scale_from_string("log"), InvalidInput);
}

// Random series (finite, NaN, ±inf, huge values, random ranges, linear or log10 axes, random
// thickness): the series colours never leave the panels' rectangles (grown by the thickness), and
// the same spec gives the same bytes.
TEST(Chart, RandomSeriesStayInsideTheirPanels) {
  Rng rng(20261127);
  for (int trial = 0; trial < 60; ++trial) {
    ChartSpec spec;
    spec.width = 64 + static_cast<int>(rng.uniform_int(400));
    spec.text_scale = static_cast<int>(rng.uniform_int(3));
    spec.x.tick_step = rng.uniform() < 0.5 ? 0.0 : 1.0;
    if (rng.uniform() < 0.5) spec.x.min = rng.uniform(-5, 0), spec.x.max = rng.uniform(1, 5);
    const int panels = 1 + static_cast<int>(rng.uniform_int(3));
    int max_thickness = 1;
    for (int p = 0; p < panels; ++p) {
      ChartPanel panel;
      panel.height = 8 + static_cast<int>(rng.uniform_int(120));
      panel.y.scale = rng.uniform() < 0.3 ? AxisScale::Log10 : AxisScale::Linear;
      if (rng.uniform() < 0.5) {
        const bool log = panel.y.scale == AxisScale::Log10;
        panel.y.min = log ? rng.uniform(0.01, 1) : rng.uniform(-1, 0);
        panel.y.max = log ? rng.uniform(2, 100) : rng.uniform(0.5, 2);
      }
      panel.y.tick_step = rng.uniform() < 0.5 ? 0.0 : 0.5;
      for (int k = 0; k < 2; ++k) {
        ChartSeries s;
        s.colour = {static_cast<std::uint8_t>(1 + p), static_cast<std::uint8_t>(100 + k), 7};
        s.thickness = 1 + static_cast<int>(rng.uniform_int(4));
        max_thickness = std::max(max_thickness, s.thickness);
        s.name = k == 0 ? "s" : "";
        const std::size_t n = rng.uniform_int(40);
        const bool with_x = rng.uniform() < 0.7;
        for (std::size_t i = 0; i < n; ++i) {
          const double u = rng.uniform();
          s.y.push_back(u < 0.1    ? kNaN
                        : u < 0.15 ? kInf
                        : u < 0.2  ? -1e300
                        : u < 0.25 ? 1e300
                                   : rng.uniform(-3, 3));
          if (with_x) s.x.push_back(rng.uniform() < 0.05 ? kNaN : rng.uniform(-8, 8));
        }
        panel.series.push_back(std::move(s));
      }
      spec.panels.push_back(std::move(panel));
    }
    const ChartLayout l = chart_layout(spec);
    const Image im = draw_chart(spec);
    ASSERT_EQ(im.width, l.width);
    ASSERT_EQ(im.height, l.height);
    ASSERT_EQ(im.rgb.size(), static_cast<std::size_t>(im.width) * im.height * 3);
    EXPECT_EQ(draw_chart(spec).rgb, im.rgb) << trial;
    const int t = max_thickness;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) {
        const Rgb c = im.at(x, y);
        if (c[2] != 7 || c[0] < 1 || c[0] > 3) continue;
        const std::size_t p = c[0] - 1u;
        const bool in_legend = y < l.panel_top[0];
        ASSERT_TRUE(in_legend ||
                    (x >= l.left - t && x <= l.left + l.plot_width + t && y >= l.panel_top[p] - t &&
                     y <= l.panel_top[p] + l.panel_height[p] + t))
            << "trial " << trial << " pixel " << x << "," << y << " panel " << p;
      }
  }
}

}  // namespace
}  // namespace emoface::core
