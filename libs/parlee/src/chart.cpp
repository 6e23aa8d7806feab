#include "emoface/parlee/chart.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/core/image.hpp"

namespace emoface::parlee {
namespace {

// Integer end points in, the one line routine of core (2 pixels thick for the series).
void line(core::Image& im, int x0, int y0, int x1, int y1, core::Rgb c, int thick = 1) {
  core::draw_line(im, x0, y0, x1, y1, c, thick);
}

}  // namespace

void ChartOptions::validate() const {
  if (width < 200 || width > 8192) throw InvalidInput("chart: width must be in [200, 8192] pixels");
  if (panel_height < 40 || panel_height > 2048) throw InvalidInput("chart: panel_height must be in [40, 2048] pixels");
  if (!(x_max >= 0) || !std::isfinite(x_max)) throw InvalidInput("chart: x_max must be finite and >= 0");
  for (const auto& m : markers)
    if (!std::isfinite(m.x)) throw InvalidInput("chart: marker positions must be finite");
}

namespace {

// Tick value text: integers as such, else up to two decimals without trailing zeros ("0.5").
std::string tick_text(double v) {
  const double r = std::round(v * 100.0) / 100.0;
  if (r == std::floor(r)) return std::to_string(static_cast<long long>(r));
  std::string t = std::to_string(r);
  while (!t.empty() && t.back() == '0') t.pop_back();
  return t;
}

}  // namespace

ChartLayout chart_layout(const std::vector<ChartPanel>& panels, const ChartOptions& options) {
  ChartLayout l;
  bool legend = false;
  for (const auto& p : panels)
    for (const auto& s : p.series) legend = legend || !s.name.empty();
  l.title_y = 6;
  l.legend_y = l.title_y + (options.title.empty() ? 0 : 20);
  l.top = l.legend_y + (legend ? 18 : 2);
  if (options.title.empty() && !legend) l.top = 8;
  l.left = options.y_label.empty() ? 40 : 56;
  const int n = static_cast<int>(panels.size());
  const int bottom = 28 + (options.markers.empty() ? 0 : 16) + (options.x_label.empty() ? 0 : 16);
  l.height = l.top + n * options.panel_height + (n - 1) * 22 + bottom;
  l.plot_width = options.width - l.left - 16;
  return l;
}

core::Image draw_chart(const std::vector<ChartPanel>& panels, const ChartOptions& options) {
  options.validate();
  if (panels.empty()) throw InvalidInput("chart: no panels");
  double x_max = options.x_max;
  if (x_max <= 0) {
    x_max = 10;
    for (const auto& p : panels)
      for (const auto& s : p.series)
        for (double x : s.x)
          if (std::isfinite(x)) x_max = std::max(x_max, x);
    x_max = std::ceil(x_max / 10) * 10;
  }
  const ChartLayout l = chart_layout(panels, options);
  const int left = l.left, top = l.top, gap = 22;
  const int n = static_cast<int>(panels.size());
  const int panel_height = options.panel_height;
  const int width = options.width;
  const int height = l.height;
  core::Image cv(width, height);
  const std::array<std::uint8_t, 3> grid{225, 225, 225}, frame{120, 120, 120}, ink{40, 40, 40};
  const int pw = l.plot_width;
  auto X = [&](double x) { return left + static_cast<int>(std::lround(std::clamp(x / x_max, 0.0, 1.0) * pw)); };
  const int plot_bottom = top + n * panel_height + (n - 1) * gap;
  for (int p = 0; p < n; ++p) {
    const int y0 = top + p * (panel_height + gap);
    const ChartPanel& panel = panels[static_cast<std::size_t>(p)];
    if (!(panel.y_max > 0) || !std::isfinite(panel.y_max)) throw InvalidInput("chart: panel y_max must be > 0");
    auto Y = [&](double y) {
      const double t = std::isfinite(y) ? std::clamp(y / panel.y_max, 0.0, 1.0) : 0.0;
      return y0 + panel_height - static_cast<int>(std::lround(t * panel_height));
    };
    for (double gx = 0; gx <= x_max + 1e-9; gx += 10) line(cv, X(gx), y0, X(gx), y0 + panel_height, grid);
    line(cv, left, Y(panel.y_max / 2), left + pw, Y(panel.y_max / 2), grid);
    for (const auto& m : options.markers) line(cv, X(m.x), y0, X(m.x), y0 + panel_height, m.rgb);
    line(cv, left, y0, left + pw, y0, frame);
    line(cv, left, y0 + panel_height, left + pw, y0 + panel_height, frame);
    line(cv, left, y0, left, y0 + panel_height, frame);
    line(cv, left + pw, y0, left + pw, y0 + panel_height, frame);
    // y tick values 0, y_max/2, y_max right-aligned against the axis, with tick marks
    for (double f : {0.0, 0.5, 1.0}) {
      const std::string t = tick_text(f * panel.y_max);
      const int ty = std::clamp(Y(f * panel.y_max) - 5, y0, y0 + panel_height - 10);
      core::draw_text(cv, left - 6 - core::text_width(t), ty, t, ink);
      line(cv, left - 4, Y(f * panel.y_max), left - 1, Y(f * panel.y_max), frame);
    }
    for (const auto& s : panel.series)
      for (std::size_t i = 1; i < s.x.size() && i < s.y.size(); ++i)
        line(cv, X(s.x[i - 1]), Y(s.y[i - 1]), X(s.x[i]), Y(s.y[i]), s.rgb, 2);
    core::draw_text(cv, left + 6, y0 + 4, panel.title, ink);
  }
  if (!options.y_label.empty())  // vertical, centred on the panels
    core::draw_text_vertical(cv, 4,
                             top + (plot_bottom - top + core::text_width(options.y_label)) / 2,
                             options.y_label, ink, 2);
  for (double gx = 0; gx <= x_max + 1e-9; gx += 10) {
    const std::string label = std::to_string(static_cast<int>(gx));
    line(cv, X(gx), plot_bottom + 1, X(gx), plot_bottom + 4, frame);
    core::draw_text(cv, X(gx) - 4 * static_cast<int>(label.size()), plot_bottom + 8, label, ink);
  }
  int below = plot_bottom + 26;
  for (const auto& m : options.markers)
    core::draw_text(cv, X(m.x) - core::text_width(m.label) / 2, below, m.label, m.rgb);
  if (!options.markers.empty()) below += 16;
  if (!options.x_label.empty())
    core::draw_text(cv, left + (pw - core::text_width(options.x_label)) / 2, below, options.x_label,
                    ink);
  if (!options.title.empty())
    core::draw_text(cv, left + (pw - core::text_width(options.title)) / 2, l.title_y, options.title,
                    ink);
  // legend: every distinct (name, colour) of the named series, in order, one row
  std::vector<std::pair<std::string, std::array<std::uint8_t, 3>>> entries;
  for (const auto& p : panels)
    for (const auto& s : p.series)
      if (!s.name.empty() &&
          std::find(entries.begin(), entries.end(), std::make_pair(s.name, s.rgb)) == entries.end())
        entries.emplace_back(s.name, s.rgb);
  int lx = left;
  for (const auto& [name, rgb] : entries) {
    for (int dy = 0; dy < 4; ++dy)
      line(cv, lx, l.legend_y + 3 + dy, lx + 18, l.legend_y + 3 + dy, rgb);
    core::draw_text(cv, lx + 24, l.legend_y, name, ink);
    lx += 24 + core::text_width(name) + 20;
  }
  return cv;
}

std::string render_chart(const std::vector<ChartPanel>& panels, const ChartOptions& options) {
  return core::encode_png(draw_chart(panels, options));
}

const std::vector<ChartEmotion>& chart_emotions() {
  static const std::vector<ChartEmotion> kEmotions = {{"fear", 3, {130, 40, 160}},
                                                      {"happiness", 1, {230, 140, 0}},
                                                      {"surprise", 5, {0, 140, 200}},
                                                      {"sadness", 0, {30, 60, 200}}};
  return kEmotions;
}

std::vector<ChartPanel> emotion_panels(const std::string& name, const std::vector<StepRecord>& run) {
  std::vector<ChartPanel> panels;
  for (const auto& c : chart_emotions()) {
    ChartSeries s;
    s.rgb = c.rgb;
    for (const auto& r : run) {
      s.x.push_back(r.time);
      s.y.push_back(r.basic[c.basic]);
    }
    s.name = c.name;
    panels.push_back({name + " " + c.name, {std::move(s)}, 1.0});
  }
  return panels;
}

}  // namespace emoface::parlee
