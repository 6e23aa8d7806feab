#include "emoface/mindmap/chart.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "emoface/core/chart.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/image.hpp"

namespace emoface::mindmap {

void ChartOptions::validate() const {
  if (width < 64 || width > 8192 || height < 64 || height > 8192)
    throw InvalidInput("ChartOptions: width and height must be in [64, 8192] pixels");
}

std::uint32_t emotion_colour(std::size_t i) noexcept {
  static const std::uint32_t palette[] = {0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd,
                                          0x8c564b, 0xe377c2, 0x7f7f7f, 0xbcbd22, 0x17becf};
  return palette[i % (sizeof palette / sizeof palette[0])];
}

// The chart is a core::ChartSpec (issue 18 item 3, the one chart routine): a title (the character),
// a legend with the emotion names, the mood 0 … 1 (grid every 0.25, tick values every 0.5), time
// in seconds (grid and tick values every second, 5 s past 30 s, 30 s past 300 s), axis labels.
// Below the axis, core leaves room for the action ticks drawn here. Charts smaller than 200 × 100
// pixels keep only the lines, grid and ticks (no text).
core::Image mood_chart(const SimulationResult& result, const MindMap& map, std::size_t c,
                       const ChartOptions& options) {
  options.validate();
  const std::size_t n = map.emotion_count();
  if (c >= result.mood.size() || result.mood[c].size() != result.times.size() * n)
    throw InvalidInput("mood_chart: character index or emotion count does not match the result");
  const bool text = options.width >= 200 && options.height >= 100;
  const int ticks = text && options.height < 200 ? 12 : 24;  // action tick rows under the axis
  const double duration = std::max(result.duration, 1e-9);
  const double step = duration > 300 ? 30.0 : duration > 30 ? 5.0 : 1.0;
  core::ChartSpec spec;
  spec.width = options.width;
  spec.height = options.height;
  spec.text_scale = !text ? 0 : options.width >= 400 && options.height >= 200 ? 2 : 1;
  spec.title = map.character + ": mood";
  spec.below_axis = ticks;
  spec.x.min = 0;
  spec.x.max = duration;
  spec.x.grid_step = spec.x.tick_step = step;
  spec.x.label = "time (s)";
  core::ChartPanel panel;
  panel.y.min = 0;
  panel.y.max = 1;
  panel.y.grid_step = 0.25;
  panel.y.tick_step = 0.5;
  panel.y.label = "mood";
  const auto& mood = result.mood[c];
  for (std::size_t e = 0; e < n; ++e) {
    core::ChartSeries s;
    s.x = result.times;
    for (std::size_t k = 0; k < result.times.size(); ++k) s.y.push_back(mood[k * n + e]);
    s.colour = core::rgb_from_hex(emotion_colour(e));
    s.name = map.emotions[e];
    panel.series.push_back(std::move(s));
  }
  spec.panels.push_back(std::move(panel));
  const core::ChartLayout l = core::chart_layout(spec);
  core::Image cv = core::draw_chart(spec);
  // actions: tall = stimulus, middle = chain, short = decay hint, in the choosing emotion's colour
  for (const auto& a : result.actions) {
    if (a.character != map.character || a.time > duration) continue;
    const auto e = map.find_emotion(a.emotion);
    const int x = static_cast<int>(std::lround(l.x_pixel(a.time)));
    const int h = a.cause == Cause::Stimulus ? ticks - 2 : a.cause == Cause::Chain ? ticks * 2 / 3 : ticks / 3;
    core::fill_rect(cv, x - 1, l.axis_y + 6, 3, h,
                    core::rgb_from_hex(e ? emotion_colour(*e) : 0x000000));
  }
  return cv;
}

}  // namespace emoface::mindmap
