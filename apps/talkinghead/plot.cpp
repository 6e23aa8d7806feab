#include "plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "emoface/core/chart.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/image.hpp"
#include "emoface/core/io.hpp"

namespace emoface::talkinghead {

const char* const kPlotColours[8] = {"blue", "red", "green", "orange", "purple", "brown", "black", "cyan"};

namespace {
constexpr core::Rgb kRgb[8] = {{31, 90, 200},  {215, 40, 40}, {30, 150, 60}, {240, 140, 0},
                               {130, 60, 170}, {140, 85, 40}, {0, 0, 0},     {0, 170, 190}};
}  // namespace

void plot_png(const std::string& path, const std::vector<std::vector<double>>& series, double fps, int width,
              int height) {
  if (width < 50 || height < 50 || width > 8000 || height > 8000) throw InvalidInput("plot: bad image size");
  if (!(fps > 0)) throw InvalidInput("plot: bad fps");
  std::size_t frames = 0;
  double lo = 0.0, hi = 1.0;
  for (const auto& s : series) {
    frames = std::max(frames, s.size());
    for (double v : s) {
      if (!std::isfinite(v)) continue;  // a gap in the line
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  // core::draw_chart (issue 18 item 3): time over [0, duration], grid every second (10 s past a
  // minute) and every 0.1, no text
  core::ChartSpec spec;
  spec.width = width;
  spec.height = height;
  spec.text_scale = 0;
  spec.x.min = 0;
  spec.x.max = frames > 1 ? static_cast<double>(frames - 1) / fps : 1.0;
  spec.x.grid_step = spec.x.max > 60 ? 10.0 : 1.0;
  core::ChartPanel panel;
  panel.y.min = lo;
  panel.y.max = hi;
  panel.y.grid_step = 0.1;
  for (std::size_t k = 0; k < series.size(); ++k) {
    core::ChartSeries s;
    for (std::size_t f = 0; f < series[k].size(); ++f) s.x.push_back(static_cast<double>(f) / fps);
    s.y = series[k];
    s.colour = kRgb[k % 8];
    s.thickness = 3;
    panel.series.push_back(std::move(s));
  }
  spec.panels.push_back(std::move(panel));
  const core::Image img = core::draw_chart(spec);
  core::write_png(path, img);
}

}  // namespace emoface::talkinghead
