#include "emoface/mindmap/chart.hpp"

#include <algorithm>
#include <cmath>
#include <string>

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

namespace {

// A filled rectangle between two corners, both inclusive.
void rect(core::Image& image, int x0, int y0, int x1, int y1, std::uint32_t colour) {
  core::fill_rect(image, x0, y0, x1 - x0 + 1, y1 - y0 + 1, core::rgb_from_hex(colour));
}

}  // namespace

// Issue 19 item 4: a title (the character), a legend with the emotion names, tick values on both
// axes and axis labels, all with core::draw_text (the one bitmap font). Charts smaller than 200 ×
// 100 pixels keep only the swatches, lines and ticks.
core::Image mood_chart(const SimulationResult& result, const MindMap& map, std::size_t c,
                       const ChartOptions& options) {
  options.validate();
  const std::size_t n = map.emotion_count();
  if (c >= result.mood.size() || result.mood[c].size() != result.times.size() * n)
    throw InvalidInput("mood_chart: character index or emotion count does not match the result");
  core::Image cv(options.width, options.height);
  const bool text = options.width >= 200 && options.height >= 100;
  const int sc = options.width >= 400 && options.height >= 200 ? 2 : 1;  // font scale
  const int lh = core::text_height(sc) + 4;                              // line height
  const core::Rgb ink{40, 40, 40};
  auto label = [&](int x, int y, const std::string& t, core::Rgb colour) {
    core::draw_text(cv, x, y, t, colour, sc);
  };
  int left = 8, top = 8 + 10, legend_y = 4;
  if (text) {
    legend_y = 3 + lh;
    // legend entries wrap into rows of the chart's width
    int x = 8, rows = 1;
    for (std::size_t e = 0; e < n; ++e) {
      const int w = 12 + 4 + core::text_width(map.emotions[e], sc) + 10;
      if (x + w > options.width - 8 && x > 8) x = 8, ++rows;
      x += w;
    }
    top = legend_y + rows * lh + 4;
    left = 4 + lh + core::text_width("0.5", sc) + 6;
  }
  const int right = options.width - 9;
  const int ticks = text && options.height < 200 ? 12 : 24;
  const int bottom = options.height - 9 - ticks - (text ? 2 * lh : 0);
  const double duration = std::max(result.duration, 1e-9);
  auto px = [&](double t) { return left + (right - left) * t / duration; };
  auto py = [&](double m) { return bottom - (bottom - top) * m; };
  // Legend: one swatch per emotion node, in emotion order (with its name when there is room).
  {
    int x = 8, y = legend_y;
    for (std::size_t e = 0; e < n; ++e) {
      if (!text) {
        rect(cv, left + static_cast<int>(e) * 18, 4, left + static_cast<int>(e) * 18 + 12, 12,
             emotion_colour(e));
        continue;
      }
      const int w = 12 + 4 + core::text_width(map.emotions[e], sc) + 10;
      if (x + w > options.width - 8 && x > 8) x = 8, y += lh;
      rect(cv, x, y + sc, x + 12, y + core::text_height(sc) - sc, emotion_colour(e));
      label(x + 16, y, map.emotions[e], ink);
      x += w;
    }
  }
  const double step = duration > 300 ? 30.0 : duration > 30 ? 5.0 : 1.0;
  for (double t = 0.0; t <= duration + 1e-9; t += step)
    rect(cv, static_cast<int>(std::lround(px(t))), top, static_cast<int>(std::lround(px(t))),
         bottom, 0xe0e0e0);
  for (int q = 0; q <= 4; ++q) {
    const int y = static_cast<int>(std::lround(py(q / 4.0)));
    rect(cv, left, y, right, y, q == 0 || q == 4 ? 0x808080 : 0xe0e0e0);
  }
  if (text) {
    label(std::max(0, (options.width - core::text_width(map.character + ": mood", sc)) / 2), 3,
          map.character + ": mood", ink);
    for (int q = 0; q <= 2; ++q) {  // y tick values 0, 0.5, 1
      const std::string t = q == 0 ? "0" : q == 1 ? "0.5" : "1";
      const int y = static_cast<int>(std::lround(py(q / 2.0)));
      label(left - 4 - core::text_width(t, sc),
            std::clamp(y - core::text_height(sc) / 2, top, bottom), t, ink);
    }
    core::draw_text_vertical(cv, 3, (top + bottom + core::text_width("mood", sc)) / 2, "mood", ink,
                             sc);
    // x tick values under the action ticks, every k-th grid line so that labels do not touch
    const int tick_y = bottom + ticks + 6;
    auto fmt = [](double t) { return std::to_string(static_cast<long long>(std::lround(t))); };
    const double grid_px = (right - left) * step / duration;
    const int widest = core::text_width(fmt(duration), sc) + 8;
    const int every = std::max(1, static_cast<int>(std::ceil(widest / std::max(grid_px, 1e-9))));
    int k = 0;
    for (double t = 0.0; t <= duration + 1e-9; t += step, ++k) {
      if (k % every != 0) continue;
      const std::string v = fmt(t);
      const int x = static_cast<int>(std::lround(px(t)));
      label(std::clamp(x - core::text_width(v, sc) / 2, 0, options.width - core::text_width(v, sc)),
            tick_y, v, ink);
    }
    const std::string xl = "time (s)";
    label(left + (right - left - core::text_width(xl, sc)) / 2, tick_y + lh, xl, ink);
  }
  const auto& mood = result.mood[c];
  for (std::size_t e = 0; e < n; ++e)
    for (std::size_t k = 1; k < result.times.size(); ++k)
      core::draw_line(cv, px(result.times[k - 1]), py(mood[(k - 1) * n + e]), px(result.times[k]),
                      py(mood[k * n + e]), core::rgb_from_hex(emotion_colour(e)), 2);
  for (const auto& a : result.actions) {
    if (a.character != map.character || a.time > duration) continue;
    const auto e = map.find_emotion(a.emotion);
    const int x = static_cast<int>(std::lround(px(a.time)));
    const int h = a.cause == Cause::Stimulus ? ticks - 2 : a.cause == Cause::Chain ? ticks * 2 / 3 : ticks / 3;
    rect(cv, x - 1, bottom + 4, x + 1, bottom + 3 + h, e ? emotion_colour(*e) : 0x000000);
  }
  return cv;
}

}  // namespace emoface::mindmap
