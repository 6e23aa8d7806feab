#include "emoface/mindmap/chart.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/core/font.hpp"

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

struct Canvas {
  Raster r;
  void set(int x, int y, std::uint32_t c) {
    if (x < 0 || y < 0 || x >= r.width || y >= r.height) return;
    std::uint8_t* p = &r.rgb[(static_cast<std::size_t>(y) * r.width + x) * 3];
    p[0] = static_cast<std::uint8_t>(c >> 16);
    p[1] = static_cast<std::uint8_t>(c >> 8);
    p[2] = static_cast<std::uint8_t>(c);
  }
  void rect(int x0, int y0, int x1, int y1, std::uint32_t c) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) set(x, y, c);
  }
  // Thick line by stamping a 2×2 block along the segment.
  void line(double x0, double y0, double x1, double y1, std::uint32_t c) {
    const int steps = static_cast<int>(std::ceil(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0)))) + 1;
    for (int s = 0; s <= steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
      const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
      rect(x, y, x + 1, y + 1, c);
    }
  }
};

}  // namespace

// Issue 19 item 4: a title (the character), a legend with the emotion names, tick values on both
// axes and axis labels, all with core::draw_text (the one bitmap font). Charts smaller than 200 ×
// 100 pixels keep only the swatches, lines and ticks.
Raster mood_chart(const SimulationResult& result, const MindMap& map, std::size_t c,
                  const ChartOptions& options) {
  options.validate();
  const std::size_t n = map.emotion_count();
  if (c >= result.mood.size() || result.mood[c].size() != result.times.size() * n)
    throw InvalidInput("mood_chart: character index or emotion count does not match the result");
  Canvas cv;
  cv.r.width = options.width;
  cv.r.height = options.height;
  cv.r.rgb.assign(static_cast<std::size_t>(options.width) * options.height * 3, 255);
  const bool text = options.width >= 200 && options.height >= 100;
  const int sc = options.width >= 400 && options.height >= 200 ? 2 : 1;  // font scale
  const int lh = core::text_height(sc) + 4;                              // line height
  const core::Rgb ink{40, 40, 40};
  auto label = [&](int x, int y, const std::string& t, core::Rgb colour) {
    core::draw_text(cv.r.rgb, cv.r.width, cv.r.height, x, y, t, colour, sc);
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
        cv.rect(left + static_cast<int>(e) * 18, 4, left + static_cast<int>(e) * 18 + 12, 12,
                emotion_colour(e));
        continue;
      }
      const int w = 12 + 4 + core::text_width(map.emotions[e], sc) + 10;
      if (x + w > options.width - 8 && x > 8) x = 8, y += lh;
      cv.rect(x, y + sc, x + 12, y + core::text_height(sc) - sc, emotion_colour(e));
      label(x + 16, y, map.emotions[e], ink);
      x += w;
    }
  }
  const double step = duration > 300 ? 30.0 : duration > 30 ? 5.0 : 1.0;
  for (double t = 0.0; t <= duration + 1e-9; t += step)
    cv.rect(static_cast<int>(std::lround(px(t))), top, static_cast<int>(std::lround(px(t))), bottom, 0xe0e0e0);
  for (int q = 0; q <= 4; ++q) {
    const int y = static_cast<int>(std::lround(py(q / 4.0)));
    cv.rect(left, y, right, y, q == 0 || q == 4 ? 0x808080 : 0xe0e0e0);
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
    core::draw_text_vertical(cv.r.rgb, cv.r.width, cv.r.height, 3,
                             (top + bottom + core::text_width("mood", sc)) / 2, "mood", ink, sc);
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
      cv.line(px(result.times[k - 1]), py(mood[(k - 1) * n + e]), px(result.times[k]),
              py(mood[k * n + e]), emotion_colour(e));
  for (const auto& a : result.actions) {
    if (a.character != map.character || a.time > duration) continue;
    const auto e = map.find_emotion(a.emotion);
    const int x = static_cast<int>(std::lround(px(a.time)));
    const int h = a.cause == Cause::Stimulus ? ticks - 2 : a.cause == Cause::Chain ? ticks * 2 / 3 : ticks / 3;
    cv.rect(x - 1, bottom + 4, x + 1, bottom + 3 + h, e ? emotion_colour(*e) : 0x000000);
  }
  return std::move(cv.r);
}

}  // namespace emoface::mindmap
