#include "emoface/retarget/plot.hpp"

#include "emoface/core/chart.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::retarget {

core::Image plot_series(const std::vector<std::vector<double>>& series, int width, int height,
                        bool log_y) {
  if (width < 32 || height < 32 || width > 8192 || height > 8192)
    throw InvalidInput("plot_series: image size must be in [32, 8192]");
  bool any = false;
  for (const auto& s : series) any = any || !s.empty();
  if (!any) throw InvalidInput("plot_series: nothing to plot");
  // core::draw_chart (issue 18 item 3): one panel, x = the point index, no text
  core::ChartSpec spec;
  spec.width = width;
  spec.height = height;
  spec.text_scale = 0;
  spec.frame = {150, 150, 150};
  core::ChartPanel panel;
  panel.y.scale = log_y ? core::AxisScale::Log10 : core::AxisScale::Linear;
  const core::Rgb colours[3] = {{30, 80, 200}, {200, 40, 40}, {30, 150, 60}};
  for (std::size_t i = 0; i < series.size(); ++i) {
    core::ChartSeries s;
    s.y = series[i];
    s.colour = colours[i % 3];
    panel.series.push_back(std::move(s));
  }
  spec.panels.push_back(std::move(panel));
  return core::draw_chart(spec);
}

}  // namespace emoface::retarget
