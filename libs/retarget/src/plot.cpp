#include "emoface/retarget/plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"

namespace emoface::retarget {

core::Image plot_series(const std::vector<std::vector<double>>& series, int width, int height,
                        bool log_y) {
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
  core::Image img(width, height);
  const int m = 12;
  const core::Rgb frame{150, 150, 150};
  core::fill_rect(img, m, height - m, width - 2 * m, 1, frame);
  core::fill_rect(img, m, m, width - 2 * m, 1, frame);
  core::fill_rect(img, m, m, 1, height - 2 * m + 1, frame);
  core::fill_rect(img, width - m, m, 1, height - 2 * m + 1, frame);
  const core::Rgb colours[3] = {{30, 80, 200}, {200, 40, 40}, {30, 150, 60}};
  for (std::size_t si = 0; si < series.size(); ++si) {
    const auto& s = series[si];
    const core::Rgb c = colours[si % 3];
    auto px = [&](std::size_t i) { return m + (width - 2 * m) * (longest > 1 ? static_cast<double>(i) / static_cast<double>(longest - 1) : 0.5); };
    auto py = [&](double v) { return height - m - (height - 2 * m) * (tr(v) - lo) / (hi - lo); };
    for (std::size_t i = 0; i + 1 < s.size(); ++i) {
      if (!std::isfinite(s[i]) || !std::isfinite(s[i + 1])) continue;
      core::draw_line(img, px(i), py(s[i]), px(i + 1), py(s[i + 1]), c, 2);
    }
    if (s.size() == 1 && std::isfinite(s[0]))
      img.set(static_cast<int>(px(0)), static_cast<int>(py(s[0])), c);
  }
  return img;
}

}  // namespace emoface::retarget
