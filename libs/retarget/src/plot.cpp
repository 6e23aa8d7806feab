#include "emoface/retarget/plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"

namespace emoface::retarget {

facemesh::Image plot_series(const std::vector<std::vector<double>>& series, int width, int height, bool log_y) {
  if (width < 32 || height < 32 || width > 8192 || height > 8192) throw InvalidInput("plot_series: image size must be in [32, 8192]");
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, min_positive = lo;
  std::size_t longest = 0;
  for (const auto& s : series) {
    longest = std::max(longest, s.size());
    for (double v : s)
      if (std::isfinite(v) && v > 0) min_positive = std::min(min_positive, v);
  }
  if (longest == 0) throw InvalidInput("plot_series: nothing to plot");
  auto tr = [&](double v) {
    if (!log_y) return v;
    return std::log10(std::max(v, std::isfinite(min_positive) ? min_positive : 1e-300));
  };
  for (const auto& s : series)
    for (double v : s)
      if (std::isfinite(v)) {
        lo = std::min(lo, tr(v));
        hi = std::max(hi, tr(v));
      }
  if (!std::isfinite(lo)) lo = hi = 0;
  if (hi - lo < 1e-12) {
    lo -= 0.5;
    hi += 0.5;
  }
  facemesh::Image img;
  img.width = width;
  img.height = height;
  img.rgb.assign(static_cast<std::size_t>(width * height * 3), 255);
  auto put = [&](int x, int y, int r, int g, int b) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    auto* px = &img.rgb[static_cast<std::size_t>((y * width + x) * 3)];
    px[0] = static_cast<std::uint8_t>(r);
    px[1] = static_cast<std::uint8_t>(g);
    px[2] = static_cast<std::uint8_t>(b);
  };
  const int m = 12;
  for (int x = m; x < width - m; ++x) put(x, height - m, 150, 150, 150), put(x, m, 150, 150, 150);
  for (int y = m; y <= height - m; ++y) put(m, y, 150, 150, 150), put(width - m, y, 150, 150, 150);
  const int colours[3][3] = {{30, 80, 200}, {200, 40, 40}, {30, 150, 60}};
  for (std::size_t si = 0; si < series.size(); ++si) {
    const auto& s = series[si];
    const auto* c = colours[si % 3];
    auto px = [&](std::size_t i) { return m + (width - 2 * m) * (longest > 1 ? static_cast<double>(i) / static_cast<double>(longest - 1) : 0.5); };
    auto py = [&](double v) { return height - m - (height - 2 * m) * (tr(v) - lo) / (hi - lo); };
    for (std::size_t i = 0; i + 1 < s.size(); ++i) {
      if (!std::isfinite(s[i]) || !std::isfinite(s[i + 1])) continue;
      const double x0 = px(i), y0 = py(s[i]), x1 = px(i + 1), y1 = py(s[i + 1]);
      const int steps = static_cast<int>(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
      for (int k = 0; k <= steps; ++k) {
        const double t = static_cast<double>(k) / steps;
        const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0))), y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
        put(x, y, c[0], c[1], c[2]);
        put(x, y + 1, c[0], c[1], c[2]);
      }
    }
    if (s.size() == 1 && std::isfinite(s[0])) put(static_cast<int>(px(0)), static_cast<int>(py(s[0])), c[0], c[1], c[2]);
  }
  return img;
}

}  // namespace emoface::retarget
