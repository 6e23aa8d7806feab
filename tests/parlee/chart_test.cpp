// The emotion charts' content (panels, colours, time axis); the drawing itself is core::draw_chart,
// tested in tests/core/chart_test.cpp (including the layouts this file pinned before the move).
#include "emoface/parlee/chart.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"

namespace emoface::parlee {
namespace {

std::vector<StepRecord> ramp() {  // fear 0, 0.1, 0.2 at t = 0, 10, 20
  std::vector<StepRecord> run(3);
  for (std::size_t k = 0; k < 3; ++k) {
    run[k].time = static_cast<double>(k) * 10;
    run[k].basic[3] = 0.1 * static_cast<double>(k);
  }
  return run;
}

TEST(Chart, EmotionPanels) {
  const auto panels = emotion_panels("neutral", ramp());
  ASSERT_EQ(panels.size(), 4u);
  EXPECT_EQ(panels[0].title, "neutral fear");
  EXPECT_EQ(panels[0].series[0].name, "fear");
  EXPECT_EQ(panels[0].series[0].y, (std::vector<double>{0.0, 0.1, 0.2}));
  EXPECT_EQ(panels[0].series[0].x, (std::vector<double>{0, 10, 20}));
  EXPECT_EQ(panels[0].series[0].colour, chart_emotions()[0].rgb);
  EXPECT_EQ(panels[3].title, "neutral sadness");
  for (const auto& p : panels) {
    EXPECT_EQ(p.y.min, 0.0);
    EXPECT_EQ(p.y.max, 1.0);
    EXPECT_EQ(p.y.tick_step, 0.5);
    EXPECT_EQ(p.y.label, "intensity");
    EXPECT_EQ(p.height, 150);
  }
}

TEST(Chart, TimeAxisRoundsUpToTens) {
  const core::ChartAxis a = time_axis(43.5, "match minute");
  EXPECT_EQ(a.min, 0.0);
  EXPECT_EQ(a.max, 50.0);
  EXPECT_EQ(a.grid_step, 10.0);
  EXPECT_EQ(a.tick_step, 10.0);
  EXPECT_EQ(a.label, "match minute");
  EXPECT_EQ(time_axis(0, "").max, 10.0);  // at least 10
  EXPECT_EQ(time_axis(90, "").max, 90.0);
  EXPECT_THROW(time_axis(std::numeric_limits<double>::quiet_NaN(), ""), InvalidInput);
  EXPECT_EQ(last_time({ramp(), {}}), 20.0);
  EXPECT_EQ(last_time({}), 0.0);
}

// The run drawn: fear's line passes where the mapping puts it, the chart carries the stamp.
TEST(Chart, DrawnThroughTheCoreChart) {
  core::ChartSpec spec;
  spec.width = 416;  // y tick values "0.5" + the label: left = 56, plot width 344
  spec.x = time_axis(20, "minutes");
  spec.panels = emotion_panels("neutral", ramp());
  const core::ChartLayout l = core::chart_layout(spec);
  ASSERT_EQ(l.left, 56);
  // (20, 0.2) → column 56 + 344, row top + 150 − 30
  const core::Image im = core::draw_chart(spec);
  EXPECT_EQ(im.at(56 + 344, l.panel_top[0] + 120), chart_emotions()[0].rgb);
  const std::string png = core::encode_png(im);
  EXPECT_NE(png.find("tEXtSoftware"), std::string::npos);
  EXPECT_NE(png.find(kGenerator), std::string::npos);
}

}  // namespace
}  // namespace emoface::parlee
