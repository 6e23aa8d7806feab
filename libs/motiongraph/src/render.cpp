#include "emoface/motiongraph/render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emoface/core/chart.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {

namespace {
const std::uint32_t kPalette[] = {0x1f77b4, 0xd62728, 0x2ca02c, 0x9467bd, 0xff7f0e,
                                  0x8c564b, 0xe377c2, 0x17becf, 0x7f7f7f, 0xbcbd22};
std::uint32_t palette(int i) { return kPalette[static_cast<std::size_t>(std::abs(i)) % 10]; }

// Lines 2 pixels thick (core::draw_line), dots as filled discs (core::fill_circle).
void line(core::Image& img, double x0, double y0, double x1, double y1, std::uint32_t colour) {
  core::draw_line(img, x0, y0, x1, y1, core::rgb_from_hex(colour), 2);
}
}  // namespace

View fit_view(const std::vector<Pose>& frames, int width, int height, double margin) {
  if (frames.empty() || width < 2 || height < 2 || !(margin >= 0.0 && margin < 0.5))
    throw InvalidInput("fit_view: need frames, a size >= 2 and a margin in [0, 0.5)");
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const Pose& p : frames) {
    if (p.cols() < 2) throw InvalidInput("fit_view: poses need x and y columns");
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
      if (!std::isfinite(p(i, 0)) || !std::isfinite(p(i, 1))) continue;
      x0 = std::min(x0, p(i, 0));
      x1 = std::max(x1, p(i, 0));
      y0 = std::min(y0, p(i, 1));
      y1 = std::max(y1, p(i, 1));
    }
  }
  View v;
  if (!(x1 >= x0)) return v;  // no finite point
  const double w = std::max(x1 - x0, 1e-9), h = std::max(y1 - y0, 1e-9);
  v.scale = std::min(width * (1.0 - 2.0 * margin) / w, height * (1.0 - 2.0 * margin) / h);
  v.offset_x = 0.5 * width - v.scale * 0.5 * (x0 + x1);
  v.offset_y = 0.5 * height - v.scale * 0.5 * (y0 + y1);
  return v;
}

void draw_pose(core::Image& image, const Pose& pose, const std::vector<int>& groups,
               const View& view, double dot_radius) {
  if (pose.cols() < 2) throw InvalidInput("draw_pose: poses need at least 2 columns");
  if (!(dot_radius > 0.0 && dot_radius < 100.0)) throw InvalidInput("draw_pose: dot_radius must be in (0, 100)");
  for (Eigen::Index i = 0; i < pose.rows(); ++i) {
    const int g = static_cast<std::size_t>(i) < groups.size() ? groups[static_cast<std::size_t>(i)] : 0;
    const double x = view.offset_x + view.scale * pose(i, 0), y = view.offset_y + view.scale * pose(i, 1);
    if (!std::isfinite(x) || !std::isfinite(y) || std::abs(x) > 1e6 || std::abs(y) > 1e6) continue;
    core::fill_circle(image, x, y, dot_radius, core::rgb_from_hex(palette(g)));
  }
}

const std::vector<std::vector<int>>& ibug68_contours() {
  // iBUG 300-W 68-point mark-up (Sagonas et al. 2013): the standard groups of the annotation.
  static const std::vector<std::vector<int>> c = [] {
    auto range = [](int a, int b, bool closed) {
      std::vector<int> v;
      for (int i = a; i <= b; ++i) v.push_back(i);
      if (closed) v.push_back(a);
      return v;
    };
    return std::vector<std::vector<int>>{range(0, 16, false),  range(17, 21, false), range(22, 26, false),
                                         range(27, 30, false), range(31, 35, false), range(36, 41, true),
                                         range(42, 47, true),  range(48, 59, true),  range(60, 67, true)};
  }();
  return c;
}

std::vector<std::vector<int>> contours_for(const std::vector<int>& landmark_ids) {
  std::vector<std::vector<int>> out;
  for (const auto& contour : ibug68_contours()) {
    std::vector<int> rows;
    for (int id : contour) {
      const auto it = std::find(landmark_ids.begin(), landmark_ids.end(), id);
      if (it != landmark_ids.end()) rows.push_back(static_cast<int>(it - landmark_ids.begin()));
    }
    // A closed contour whose first landmark is missing must not end on a dangling repeat.
    while (rows.size() >= 2 && rows.back() == rows[rows.size() - 2]) rows.pop_back();
    if (rows.size() >= 2) out.push_back(std::move(rows));
  }
  return out;
}

void draw_contours(core::Image& image, const Pose& pose,
                   const std::vector<std::vector<int>>& contours, const View& view,
                   std::uint32_t colour) {
  if (pose.cols() < 2) throw InvalidInput("draw_contours: poses need at least 2 columns");
  auto px = [&](int r, double& x, double& y) {
    if (r < 0 || r >= pose.rows()) throw InvalidInput("draw_contours: contour row out of range");
    x = view.offset_x + view.scale * pose(r, 0);
    y = view.offset_y + view.scale * pose(r, 1);
    return std::isfinite(x) && std::isfinite(y) && std::abs(x) < 1e6 && std::abs(y) < 1e6;
  };
  for (const auto& c : contours)
    for (std::size_t i = 1; i < c.size(); ++i) {
      double x0, y0, x1, y1;
      const bool a = px(c[i - 1], x0, y0), b = px(c[i], x1, y1);
      if (a && b) line(image, x0, y0, x1, y1, colour);
    }
}

core::Image contact_sheet(const std::vector<Pose>& frames, const std::vector<int>& groups,
                          int columns, int cell_width, int cell_height,
                          const std::vector<std::vector<int>>& contours) {
  if (frames.empty() || columns < 1 || cell_width < 8 || cell_height < 8 || cell_width > 4096 ||
      cell_height > 4096)
    throw InvalidInput("contact sheet: need frames, columns >= 1 and cells of 8..4096 pixels");
  const int cols = std::min<int>(columns, static_cast<int>(frames.size()));
  const int rows = static_cast<int>((frames.size() + static_cast<std::size_t>(cols) - 1) / static_cast<std::size_t>(cols));
  core::Image img(cols * cell_width, rows * cell_height);
  const View base = fit_view(frames, cell_width, cell_height);
  const double radius = std::max(1.0, 0.012 * std::min(cell_width, cell_height));
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const int cx = static_cast<int>(f % static_cast<std::size_t>(cols)) * cell_width;
    const int cy = static_cast<int>(f / static_cast<std::size_t>(cols)) * cell_height;
    core::fill_rect(img, cx, cy, cell_width, 1, {0xcc, 0xcc, 0xcc});
    core::fill_rect(img, cx, cy, 1, cell_height, {0xcc, 0xcc, 0xcc});
    View v = base;
    v.offset_x += cx;
    v.offset_y += cy;
    draw_contours(img, frames[f], contours, v);
    draw_pose(img, frames[f], groups, v, radius);
  }
  return img;
}

core::Image plot_series(const std::vector<std::vector<double>>& series, int width, int height,
                        double min_range) {
  if (!(min_range > 0) || !std::isfinite(min_range))
    throw InvalidInput("plot_series: min_range must be finite and > 0");
  // core::draw_chart (issue 18 item 3): one panel per series, stacked without gaps, no text; a tick
  // per sample on the x axis (the frame index)
  core::ChartSpec spec;
  spec.width = width;
  spec.height = height;
  spec.text_scale = 0;
  spec.panel_gap = 0;
  spec.x.tick_step = 1;
  for (std::size_t k = 0; k < series.size(); ++k) {
    core::ChartPanel panel;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double v : series[k])
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    if (hi >= lo) {  // the series' range (at least min_range) fills 85 % of the band, centred
      const double mid = 0.5 * (lo + hi), half = std::max(hi - lo, min_range) / 1.7;
      panel.y.min = mid - half;
      panel.y.max = mid + half;
    }
    core::ChartSeries s;
    s.y = series[k];
    s.colour = core::rgb_from_hex(palette(static_cast<int>(k)));
    panel.series.push_back(std::move(s));
    spec.panels.push_back(std::move(panel));
  }
  if (spec.panels.empty()) spec.panels.emplace_back();
  return core::draw_chart(spec);
}

core::Image plot_trajectories(const std::vector<Pose>& frames, const std::vector<int>& groups,
                              int coordinate, int width, int height) {
  if (frames.empty() || coordinate < 0 || coordinate >= frames[0].cols())
    throw InvalidInput("plot_trajectories: no frames or bad coordinate");
  const Eigen::Index n = frames[0].rows();
  std::vector<Eigen::Index> best;   // per group: landmark with the largest range
  std::vector<double> range;
  for (Eigen::Index i = 0; i < n; ++i) {
    const int g = static_cast<std::size_t>(i) < groups.size() ? groups[static_cast<std::size_t>(i)] : 0;
    if (g < 0 || g > 1000) throw InvalidInput("plot_trajectories: group ids must be in [0, 1000]");
    if (static_cast<std::size_t>(g) >= best.size()) best.resize(static_cast<std::size_t>(g) + 1, -1), range.resize(best.size(), -1.0);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Pose& p : frames) {
      if (p.rows() != n) throw InvalidInput("plot_trajectories: frames differ in landmark count");
      lo = std::min(lo, p(i, coordinate));
      hi = std::max(hi, p(i, coordinate));
    }
    if (hi - lo > range[static_cast<std::size_t>(g)]) range[static_cast<std::size_t>(g)] = hi - lo, best[static_cast<std::size_t>(g)] = i;
  }
  std::vector<std::vector<double>> series;
  for (Eigen::Index i : best) {
    series.emplace_back();
    if (i < 0) continue;
    // Image y grows downwards: plot −y so "up in the face" is up in the plot.
    for (const Pose& p : frames) series.back().push_back(coordinate == 1 ? -p(i, 1) : p(i, coordinate));
  }
  return plot_series(series, width, height);
}

}  // namespace emoface::motiongraph
