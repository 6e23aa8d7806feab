#include "plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

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
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  core::Image img(width, height);
  const int m = 20;  // margin, pixels
  const double duration = frames > 1 ? static_cast<double>(frames - 1) / fps : 1.0;
  const auto X = [&](double t) { return m + (width - 2 * m) * t / duration; };
  const auto Y = [&](double v) { return height - m - (height - 2 * m) * (v - lo) / (hi - lo); };
  const core::Rgb grid{225, 225, 225}, axis{120, 120, 120};
  for (double v = std::ceil(lo * 10) / 10; v <= hi + 1e-9; v += 0.1)
    core::draw_line(img, X(0), Y(v), X(duration), Y(v), grid, 1);
  const double step = duration > 60 ? 10.0 : 1.0;
  for (double t = 0; t <= duration + 1e-9; t += step)
    core::draw_line(img, X(t), Y(lo), X(t), Y(hi), grid, 1);
  core::draw_line(img, X(0), Y(0), X(duration), Y(0), axis, 1);
  core::draw_line(img, X(0), Y(lo), X(0), Y(hi), axis, 1);
  for (std::size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    for (std::size_t f = 1; f < s.size(); ++f)
      core::draw_line(img, X((f - 1) / fps), Y(s[f - 1]), X(f / fps), Y(s[f]), kRgb[k % 8], 3);
  }
  core::write_png(path, img);
}

}  // namespace emoface::talkinghead
