// talkinghead --plot end to end: the tracks' points land where core::draw_chart's mapping puts them
// (computed here from the tracks CSV the same run writes), and a second run gives the same bytes.
#include <gtest/gtest.h>

#include <cmath>

#include "cli_harness.hpp"
#include "emoface/core/csv.hpp"
#include "emoface/core/image.hpp"

namespace {

class TalkingheadPlot : public emoface::test::CliTest {};

TEST_F(TalkingheadPlot, PointsLandOnTheTimeAndValueAxes) {
  // thesis Fig. 4.3: one 7 s movement of zygomatic_major_l (2 s onset, 3 s offset) at 100 fps
  const std::string script = std::string(EMOFACE_SOURCE_DIR) + "/data/channels/examples/fig4_3.xml";
  const std::string args = "--script " + script +
                           " --fps 100 --no-blinks --no-gaze-noise --no-head-noise --out " +
                           path("t.csv") + " --plot-params zygomatic_major_l --plot ";
  auto r = run_tool(TALKINGHEAD_EXE, args + path("p.png"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto table = emoface::core::CsvTable::parse(slurp(path("t.csv")), "t.csv");
  const std::size_t t_col = table.require_column("time"),
                    z_col = table.require_column("zygomatic_major_l");
  const std::size_t frames = table.size();
  ASSERT_GT(frames, 600u);
  const emoface::core::Image im = emoface::core::read_png(path("p.png"));
  ASSERT_EQ(im.width, 900);  // the default size
  ASSERT_EQ(im.height, 360);
  // No text: plot columns 10 … 10 + 874 (900 − 10 − 16), rows 8 + 344 … 8 (360 − 8 − 8); time over
  // [0, (frames − 1)/100 s], the value over [0, 1] (the data stay within it).
  const double duration = static_cast<double>(frames - 1) / 100.0;
  const emoface::core::Rgb blue{31, 90, 200};
  int checked = 0;
  for (std::size_t f = 0; f < frames; f += 50) {
    const double t = table.number(f, t_col), v = table.number(f, z_col);
    ASSERT_LE(v, 1.0);
    ASSERT_GE(v, 0.0);
    const int x = static_cast<int>(std::lround(10 + t / duration * 874));
    const int y = static_cast<int>(std::lround(8 + 344 - v * 344));
    EXPECT_EQ(im.at(x, y), blue) << "frame " << f << " t " << t << " v " << v;
    ++checked;
  }
  EXPECT_GT(checked, 10);
  ASSERT_EQ(run_tool(TALKINGHEAD_EXE, args + path("q.png")).code, 0);
  EXPECT_EQ(slurp(path("p.png")), slurp(path("q.png")));
  // --plot needs --plot-params
  EXPECT_NE(run_tool(TALKINGHEAD_EXE,
                     "--script " + script + " --out " + path("u.csv") + " --plot " + path("u.png"))
                .code,
            0);
}

}  // namespace
