#include "emoface/core/chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

#include "emoface/core/errors.hpp"

namespace emoface::core {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr long long kMaxLines = 10000;  // grid lines or ticks per axis

// A data value in axis units: itself (Linear) or its log10 (Log10); NaN when not drawable.
double axis_units(AxisScale scale, double v) noexcept {
  if (!std::isfinite(v)) return kNaN;
  if (scale == AxisScale::Linear) return v;
  return v > 0 ? std::log10(v) : kNaN;
}

void check_axis(const ChartAxis& a, const std::string& name) {
  for (const auto& [v, end] : {std::pair{a.min, ".min"}, std::pair{a.max, ".max"}}) {
    if (std::isnan(v)) continue;
    if (!std::isfinite(v)) throw InvalidInput(name + end + ": must be finite or NaN (from data)");
    if (a.scale == AxisScale::Log10 && !(v > 0))
      throw InvalidInput(name + end + ": must be > 0 on a log10 axis");
  }
  if (!std::isnan(a.min) && !std::isnan(a.max) && !(a.min < a.max))
    throw InvalidInput(name + ".max: must be greater than min");
  if (!(a.grid_step >= 0) || !std::isfinite(a.grid_step))
    throw InvalidInput(name + ".grid_step: must be finite and >= 0");
  if (!(a.tick_step >= 0) || !std::isfinite(a.tick_step))
    throw InvalidInput(name + ".tick_step: must be finite and >= 0");
}

// The axis range [lo, hi] in axis units from the given ends and the drawable data values.
std::pair<double, double> resolve_ends(const ChartAxis& a, const std::vector<double>& data) {
  double lo = axis_units(a.scale, a.min), hi = axis_units(a.scale, a.max);
  const bool free_lo = std::isnan(lo), free_hi = std::isnan(hi);
  if (!free_lo && !free_hi) return {lo, hi};
  double dlo = kNaN, dhi = kNaN;
  for (double v : data) {
    const double t = axis_units(a.scale, v);
    if (std::isnan(t)) continue;
    dlo = std::isnan(dlo) ? t : std::min(dlo, t);
    dhi = std::isnan(dhi) ? t : std::max(dhi, t);
  }
  if (std::isnan(dlo)) {  // no data: [0, 1], or one unit from the given end
    if (free_lo && free_hi) return {0.0, 1.0};
    return free_lo ? std::pair{hi - 1.0, hi} : std::pair{lo, lo + 1.0};
  }
  if (free_lo) lo = dlo;
  if (free_hi) hi = dhi;
  const double tiny = 1e-12 * std::max({1.0, std::abs(lo), std::abs(hi)});
  if (hi - lo > tiny) return {lo, hi};
  if (free_lo && free_hi) return {lo - 0.5, hi + 0.5};
  return free_lo ? std::pair{hi - 1.0, hi} : std::pair{lo, lo + 1.0};
}

// resolve_ends, and a located error when the span overflows (data near ±1.8e308).
std::pair<double, double> resolve_range(const ChartAxis& a, const std::vector<double>& data,
                                        const std::string& name) {
  const auto range = resolve_ends(a, data);
  if (!std::isfinite(range.second - range.first))
    throw InvalidInput(name + ": the range from the data is wider than a double can hold");
  return range;
}

// The step actually used: `step` times the smallest power of ten that leaves at most 10,000
// multiples of it in [lo, hi] (a fine step over a wide range from data draws no line soup).
double effective_step(double step, double lo, double hi) {
  if (step <= 0) return 0.0;
  while ((hi - lo) / step >= static_cast<double>(kMaxLines)) step *= 10;
  return step;
}

// The multiples k·step (axis units) inside [lo, hi] of the effective step; step 0 = none.
std::vector<double> multiples(double step, double lo, double hi) {
  std::vector<double> out;
  step = effective_step(step, lo, hi);
  if (step <= 0) return out;
  const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor(hi / step + 1e-9);
  for (double k = k0; k <= k1; k += 1) out.push_back(k * step);
  return out;
}

// The data value at axis units t, for its label.
double data_value(AxisScale scale, double t) {
  return scale == AxisScale::Linear ? t : std::pow(10.0, t);
}

// Label every `every`-th tick so that labels `need` pixels apart fit at `spacing` pixels.
int label_every(double need, double spacing) {
  if (!(spacing > 0)) return 1;
  return std::max(1, static_cast<int>(std::ceil(need / spacing - 1e-9)));
}

// Liang–Barsky: clips the segment (x0, y0)–(x1, y1) to [xa, xb] × [ya, yb]; false when outside.
bool clip(double& x0, double& y0, double& x1, double& y1, double xa, double xb, double ya,
          double yb) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = x1 - x0, dy = y1 - y0;
  const double p[4] = {-dx, dx, -dy, dy}, q[4] = {x0 - xa, xb - x0, y0 - ya, yb - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  const double ax = x0 + t0 * dx, ay = y0 + t0 * dy;
  x1 = x0 + t1 * dx;
  y1 = y0 + t1 * dy;
  x0 = ax;
  y0 = ay;
  return true;
}

std::string panel_name(std::size_t p) { return "ChartSpec.panels[" + std::to_string(p) + "]"; }

// Every distinct (name, colour) of the named series, in order.
std::vector<std::pair<std::string, Rgb>> legend_entries(const ChartSpec& spec) {
  std::vector<std::pair<std::string, Rgb>> out;
  if (!spec.legend || spec.text_scale == 0) return out;
  for (const auto& p : spec.panels)
    for (const auto& s : p.series)
      if (!s.name.empty() &&
          std::find(out.begin(), out.end(), std::make_pair(s.name, s.colour)) == out.end())
        out.emplace_back(s.name, s.colour);
  return out;
}

// Legend geometry at font scale s: a 9s+1 × 2s swatch, the name 12s to its right, 10s after it.
int legend_entry_width(const std::string& name, int s) {
  return 12 * s + text_width(name, s) + 10 * s;
}

}  // namespace

std::string to_string(AxisScale scale) { return scale == AxisScale::Log10 ? "log10" : "linear"; }

AxisScale axis_scale_from_string(std::string_view text) {
  if (text == "linear") return AxisScale::Linear;
  if (text == "log10") return AxisScale::Log10;
  throw InvalidInput("axis scale must be \"linear\" or \"log10\", not \"" + std::string(text) +
                     "\"");
}

std::string chart_tick_text(double value) {
  if (value == 0 || !std::isfinite(value))
    return std::isnan(value) ? "nan" : value == 0 ? "0" : value > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", value);
  std::string t = buf;
  const auto e = t.find('e');
  if (e == std::string::npos) return t;
  std::string exp = t.substr(e + 1), out = t.substr(0, e + 1);
  if (!exp.empty() && (exp[0] == '+' || exp[0] == '-')) {
    if (exp[0] == '-') out += '-';
    exp.erase(0, 1);
  }
  while (exp.size() > 1 && exp[0] == '0') exp.erase(0, 1);
  return out + exp;
}

void ChartSpec::validate() const {
  if (width < 32 || width > 8192)
    throw InvalidInput("ChartSpec.width: must be in [32, 8192] pixels");
  if (height != 0 && (height < 32 || height > 8192))
    throw InvalidInput("ChartSpec.height: must be 0 (from the panels) or in [32, 8192] pixels");
  if (panels.empty() || panels.size() > 64)
    throw InvalidInput("ChartSpec.panels: must hold 1 to 64 panels");
  if (text_scale < 0 || text_scale > 8)
    throw InvalidInput("ChartSpec.text_scale: must be in [0, 8]");
  if (panel_gap < 0 || panel_gap > 1000)
    throw InvalidInput("ChartSpec.panel_gap: must be in [0, 1000] pixels");
  if (below_axis < 0 || below_axis > 1000)
    throw InvalidInput("ChartSpec.below_axis: must be in [0, 1000] pixels");
  check_axis(x, "ChartSpec.x");
  for (std::size_t p = 0; p < panels.size(); ++p) {
    const ChartPanel& panel = panels[p];
    check_axis(panel.y, panel_name(p) + ".y");
    if (height == 0 && (panel.height < 8 || panel.height > 8192))
      throw InvalidInput(panel_name(p) + ".height: must be in [8, 8192] pixels");
    for (std::size_t i = 0; i < panel.series.size(); ++i) {
      const ChartSeries& s = panel.series[i];
      const std::string name = panel_name(p) + ".series[" + std::to_string(i) + "]";
      if (s.thickness < 1 || s.thickness > 16)
        throw InvalidInput(name + ".thickness: must be in [1, 16] pixels");
      if (!s.x.empty() && s.x.size() != s.y.size())
        throw InvalidInput(name + ".x: " + std::to_string(s.x.size()) + " values for " +
                           std::to_string(s.y.size()) + " y values");
    }
  }
  for (std::size_t m = 0; m < markers.size(); ++m)
    if (!std::isfinite(markers[m].x))
      throw InvalidInput("ChartSpec.markers[" + std::to_string(m) + "].x: must be finite");
}

double ChartLayout::x_pixel(double x) const noexcept {
  const double t = axis_units(x_scale, x);
  return left + (t - x_lo) / (x_hi - x_lo) * plot_width;
}

double ChartLayout::y_pixel(std::size_t panel, double y) const noexcept {
  const double t = axis_units(y_scale[panel], y);
  return panel_top[panel] + panel_height[panel] -
         (t - y_lo[panel]) / (y_hi[panel] - y_lo[panel]) * panel_height[panel];
}

ChartLayout chart_layout(const ChartSpec& spec) {
  spec.validate();
  ChartLayout l;
  const int s = spec.text_scale;
  const bool text = s > 0;
  const std::size_t n = spec.panels.size();
  // ranges: x over every panel's series (indices when a series has no x), y per panel
  std::vector<double> xs;
  for (const auto& p : spec.panels)
    for (const auto& ser : p.series) {
      if (!ser.x.empty()) {
        xs.insert(xs.end(), ser.x.begin(), ser.x.end());
      } else if (!ser.y.empty()) {
        xs.push_back(0.0);
        xs.push_back(static_cast<double>(ser.y.size() - 1));
      }
    }
  std::tie(l.x_lo, l.x_hi) = resolve_range(spec.x, xs, "ChartSpec.x");
  l.x_scale = spec.x.scale;
  int widest = 0;  // the widest y tick value
  for (std::size_t p = 0; p < n; ++p) {
    const ChartPanel& panel = spec.panels[p];
    std::vector<double> ys;
    for (const auto& ser : panel.series) ys.insert(ys.end(), ser.y.begin(), ser.y.end());
    const auto [lo, hi] = resolve_range(panel.y, ys, panel_name(p) + ".y");
    l.y_lo.push_back(lo);
    l.y_hi.push_back(hi);
    l.y_scale.push_back(panel.y.scale);
    for (double t : multiples(panel.y.tick_step, lo, hi))
      if (text)
        widest = std::max(widest, text_width(chart_tick_text(data_value(panel.y.scale, t)), s));
  }
  // columns: [y label] [y tick values] | plot | 16 px
  const bool y_label = text && !spec.panels[0].y.label.empty();
  l.left = (y_label ? 4 + 11 * s : 10) + (widest > 0 ? widest + 6 : 0);
  l.plot_width = spec.width - l.left - 16;
  if (l.plot_width < 8)
    throw InvalidInput("ChartSpec.width: " + std::to_string(spec.width) +
                       " pixels leave no room for the plot beside the tick values");
  l.width = spec.width;
  // rows: title, legend, panels, [below_axis], x tick values, marker labels, x label
  l.title_y = 6;
  int y = 6;
  if (text && !spec.title.empty()) y += 10 * s;
  l.legend_y = y;
  const auto entries = legend_entries(spec);
  if (!entries.empty()) {
    int x = l.left;
    l.legend_rows = 1;
    for (const auto& e : entries) {
      const int w = legend_entry_width(e.first, s);
      if (x + w > spec.width - 8 && x > l.left) x = l.left, ++l.legend_rows;
      x += w;
    }
  }
  y += l.legend_rows * 9 * s;
  const int top = y > 6 ? y : 8;
  int bottom = spec.below_axis + 8;  // below the last panel
  if (text) bottom += 5 * s + 10;
  if (text && !spec.markers.empty()) bottom += 8 * s;
  if (text && !spec.x.label.empty()) bottom += 8 * s;
  const int gaps = static_cast<int>(n - 1) * spec.panel_gap;
  std::vector<int> heights;
  if (spec.height > 0) {
    const int each = (spec.height - top - bottom - gaps) / static_cast<int>(n);
    if (each < 8)
      throw InvalidInput("ChartSpec.height: " + std::to_string(spec.height) +
                         " pixels leave panels under 8 pixels");
    heights.assign(n, each);
  } else {
    for (const auto& p : spec.panels) heights.push_back(p.height);
  }
  int py = top;
  for (std::size_t p = 0; p < n; ++p) {
    l.panel_top.push_back(py);
    l.panel_height.push_back(heights[p]);
    py += heights[p] + spec.panel_gap;
  }
  l.axis_y = l.panel_top.back() + l.panel_height.back();
  l.tick_label_y = l.axis_y + spec.below_axis + 8;
  l.marker_label_y = l.tick_label_y + 5 * s + 8;
  l.x_label_y = l.marker_label_y + (spec.markers.empty() ? 0 : 8 * s);
  l.height = spec.height > 0 ? spec.height : l.axis_y + bottom;
  if (l.height > 8192)
    throw InvalidInput("ChartSpec.panels: " + std::to_string(l.height) +
                       " pixels high in all, more than 8192");
  return l;
}

Image draw_chart(const ChartSpec& spec) {
  const ChartLayout l = chart_layout(spec);
  const int s = spec.text_scale;
  const bool text = s > 0;
  Image im(l.width, l.height, spec.background);
  const int left = l.left, right = l.left + l.plot_width;
  auto hline = [&](double y, Rgb c) { draw_line(im, left, y, right, y, c); };
  const double x_span = l.x_hi - l.x_lo;
  auto x_at = [&](double t) { return left + (t - l.x_lo) / x_span * l.plot_width; };
  const auto x_grid = multiples(spec.x.grid_step, l.x_lo, l.x_hi);
  const auto x_ticks = multiples(spec.x.tick_step, l.x_lo, l.x_hi);
  for (std::size_t p = 0; p < spec.panels.size(); ++p) {
    const ChartPanel& panel = spec.panels[p];
    const int y0 = l.panel_top[p], ph = l.panel_height[p], y1 = y0 + ph;
    const double lo = l.y_lo[p], hi = l.y_hi[p];
    auto y_at = [&](double t) { return y1 - (t - lo) / (hi - lo) * ph; };
    for (double t : x_grid) draw_line(im, x_at(t), y0, x_at(t), y1, spec.grid);
    for (double t : multiples(panel.y.grid_step, lo, hi)) hline(y_at(t), spec.grid);
    for (const auto& m : spec.markers) {
      const double x = l.x_pixel(m.x);
      if (x >= left - 0.5 && x <= right + 0.5) draw_line(im, x, y0, x, y1, m.colour);
    }
    hline(y0, spec.frame);
    hline(y1, spec.frame);
    draw_line(im, left, y0, left, y1, spec.frame);
    draw_line(im, right, y0, right, y1, spec.frame);
    // y ticks: marks left of the frame, values right-aligned 6 px left of it, thinned to fit
    const auto ticks = multiples(panel.y.tick_step, lo, hi);
    const double y_step = effective_step(panel.y.tick_step, lo, hi);
    const int every = label_every(5 * s + 2, y_step / (hi - lo) * ph);
    for (std::size_t k = 0; k < ticks.size(); ++k) {
      const double y = y_at(ticks[k]);
      draw_line(im, left - 4, y, left - 1, y, spec.frame);
      const long long index = std::llround(ticks[k] / y_step);
      if (!text || index % every != 0) continue;
      const std::string t = chart_tick_text(data_value(panel.y.scale, ticks[k]));
      const int ty = std::clamp(static_cast<int>(std::lround(y)) - text_height(s) / 2, y0,
                                std::max(y0, y1 - text_height(s)));
      draw_text(im, left - 6 - text_width(t, s), ty, t, spec.ink, s);
    }
    for (const auto& ser : panel.series) {
      const std::size_t count = ser.y.size();
      std::vector<double> px(count), py(count);
      for (std::size_t i = 0; i < count; ++i) {
        px[i] = l.x_pixel(ser.x.empty() ? static_cast<double>(i) : ser.x[i]);
        py[i] = l.y_pixel(p, ser.y[i]);
      }
      auto ok = [&](std::size_t i) { return std::isfinite(px[i]) && std::isfinite(py[i]); };
      for (std::size_t i = 0; i < count; ++i) {
        if (!ok(i)) continue;
        const bool prev = i > 0 && ok(i - 1), next = i + 1 < count && ok(i + 1);
        double ax = px[i], ay = py[i], bx = ax, by = ay;
        if (next) bx = px[i + 1], by = py[i + 1];
        if (!next && prev) continue;  // the end of a line, drawn with its segment
        if (clip(ax, ay, bx, by, left, right, y0, y1))
          draw_line(im, ax, ay, bx, by, ser.colour, ser.thickness);
      }
    }
    if (text && !panel.title.empty())
      draw_text(im, left + 3 * s, y0 + 2 * s, panel.title, spec.ink, s);
  }
  // x ticks under the last panel, values centred under them and thinned so they do not touch
  int widest = 0;
  for (double t : x_ticks)
    widest =
        std::max(widest, text_width(chart_tick_text(data_value(l.x_scale, t)), std::max(s, 1)));
  const double x_step = effective_step(spec.x.tick_step, l.x_lo, l.x_hi);
  const int every = label_every(widest + 2 * s, x_step / x_span * l.plot_width);
  for (double t : x_ticks) {
    const double x = x_at(t);
    draw_line(im, x, l.axis_y + 1, x, l.axis_y + 4, spec.frame);
    if (!text || std::llround(t / x_step) % every != 0) continue;
    const std::string v = chart_tick_text(data_value(l.x_scale, t));
    const int w = text_width(v, s);
    draw_text(im, std::clamp(static_cast<int>(std::lround(x)) - w / 2, 0, std::max(0, l.width - w)),
              l.tick_label_y, v, spec.ink, s);
  }
  if (!text) return im;
  for (const auto& m : spec.markers) {
    const double x = l.x_pixel(m.x);
    if (x >= left - 0.5 && x <= right + 0.5)
      draw_text(im, static_cast<int>(std::lround(x)) - text_width(m.label, s) / 2, l.marker_label_y,
                m.label, m.colour, s);
  }
  if (!spec.x.label.empty())
    draw_text(im, left + (l.plot_width - text_width(spec.x.label, s)) / 2, l.x_label_y,
              spec.x.label, spec.ink, s);
  const std::string& y_label = spec.panels[0].y.label;
  if (!y_label.empty())  // vertical, centred on the panels
    draw_text_vertical(im, 4,
                       l.panel_top[0] + (l.axis_y - l.panel_top[0] + text_width(y_label, s)) / 2,
                       y_label, spec.ink, s);
  if (!spec.title.empty())
    draw_text(im, std::max(0, left + (l.plot_width - text_width(spec.title, s)) / 2), l.title_y,
              spec.title, spec.ink, s);
  int x = left, y = l.legend_y;
  for (const auto& [name, colour] : legend_entries(spec)) {
    const int w = legend_entry_width(name, s);
    if (x + w > l.width - 8 && x > left) x = left, y += 9 * s;
    fill_rect(im, x, y + (3 * s + 1) / 2, 9 * s + 1, 2 * s, colour);
    draw_text(im, x + 12 * s, y, name, spec.ink, s);
    x += w;
  }
  return im;
}

}  // namespace emoface::core
