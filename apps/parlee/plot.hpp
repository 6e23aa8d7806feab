#pragma once
// A tiny line-chart writer for `parlee run --plot` (PNG through libpng): stacked panels sharing
// the x axis, grid every 10 x-units with digit labels, one polyline per series.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace emoface::parlee_app {

struct Series {
  std::vector<double> x, y;
  std::array<std::uint8_t, 3> rgb{0, 0, 0};
};

struct Panel {
  std::string title;  ///< drawn in the top-left corner (a–z, 0–9, space, '-', '_')
  std::vector<Series> series;
  double y_max = 1.0;  ///< y range is [0, y_max]
};

/// Encodes the chart as PNG bytes. x range is [0, x_max].
std::string render_chart(const std::vector<Panel>& panels, double x_max, int width = 960, int panel_height = 150);

}  // namespace emoface::parlee_app
