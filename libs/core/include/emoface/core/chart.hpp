#pragma once
// The one line-chart routine of emoface (issue 18 item 3): stacked panels sharing one x axis, each
// with its own y axis (linear or log10), grid lines and tick marks at multiples of a step, tick
// values, a panel title, vertical markers with labels, a chart title, axis labels and a legend, all
// in core's bitmap font (font.hpp), drawn into a core::Image. The parlee/obie emotion charts, the
// mind-map mood charts, the retarget GA error curve, the motiongraph trajectory plots and the
// talkinghead plot are specs for it.
//
// Mapping (pixels, x to the right, y down): with the axis range [lo, hi] in axis units (log10 of
// the values on a log10 axis), a value v lands at
//   x_pixel(v) = left + (t(v) − lo) / (hi − lo) · plot_width
//   y_pixel(p, v) = panel_top[p] + panel_height − (t(v) − lo) / (hi − lo) · panel_height,
// t(v) = v (Linear) or log10 v (Log10), and draw_line rounds to the nearest pixel. Series are
// polylines through consecutive finite points; a point whose value is NaN, ±inf or (on a log10
// axis) ≤ 0 is skipped and breaks the line (a gap); an isolated point is a dot. Segments are
// clipped to the panel's rectangle (values outside the range do not draw beyond the frame).
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/core/font.hpp"
#include "emoface/core/image.hpp"

namespace emoface::core {

enum class AxisScale { Linear, Log10 };
/// "linear", "log10".
std::string to_string(AxisScale scale);
/// Inverse of to_string; throws InvalidInput for any other text.
AxisScale axis_scale_from_string(std::string_view text);

/// One axis. Steps, like the range, are in axis units: values on a Linear axis, decades on a
/// Log10 axis (a grid_step of 1 on a Log10 axis draws a line at every power of ten).
struct ChartAxis {
  /// Range ends in data units (> 0 on a Log10 axis); NaN = from the data: the smallest / largest
  /// drawable value of the series. A range from data that is a single value v becomes [v − ½,
  /// v + ½] in axis units (or extends the free end by 1 when the other end is given); no data at
  /// all gives [0, 1] in axis units.
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
  AxisScale scale = AxisScale::Linear;
  double grid_step = 0.0;  ///< a light grid line at every multiple of it in the range; 0 = none
  double tick_step = 0.0;  ///< a tick mark and its value at every multiple of it; 0 = none
  std::string label;       ///< axis title ("" = none); on y: vertical, from the first panel's y
};

struct ChartSeries {
  std::vector<double> x;  ///< data units; empty = the point indices 0, 1, …, y.size() − 1
  std::vector<double> y;  ///< data units; x.size() == y.size() unless x is empty
  Rgb colour{0, 0, 0};
  int thickness = 2;  ///< line width in pixels, [1, 16] (core::draw_line)
  std::string name;   ///< legend entry ("" = not in the legend)
};

/// One plot rectangle with its own y axis, all panels share ChartSpec::x.
struct ChartPanel {
  std::string title;  ///< drawn inside the top-left corner ("" = none)
  std::vector<ChartSeries> series;
  ChartAxis y;
  int height = 150;  ///< plot pixels, [8, 8192]; ignored when ChartSpec::height > 0
};

/// A vertical line across every panel at x, its label under the x tick values, both in `colour`.
struct ChartMarker {
  double x = 0.0;  ///< data units, finite
  std::string label;
  Rgb colour{200, 60, 60};
};

struct ChartSpec {
  int width = 640;  ///< image pixels, [32, 8192]
  /// Image pixels, 0 or [32, 8192]: 0 = the panels' own heights plus the margins; otherwise the
  /// panels share what the margins leave (equal heights, at least 8 pixels each).
  int height = 0;
  std::vector<ChartPanel> panels;  ///< at least one, at most 64
  ChartAxis x;
  std::vector<ChartMarker> markers;
  std::string title;   ///< centred above the plot ("" = none)
  bool legend = true;  ///< one row (wrapping) of every distinct (name, colour) of named series
  /// Font scale of all text, [0, 8]; 0 = no text at all (no title, legend, tick values, panel
  /// titles, axis labels or marker labels; tick marks, lines and markers stay).
  int text_scale = 2;
  int panel_gap = 22;  ///< pixels between stacked panels, [0, 1000]
  int below_axis = 0;  ///< free pixel rows under the x axis before its tick values, [0, 1000]
  Rgb background{255, 255, 255};
  Rgb frame{120, 120, 120};  ///< panel frames and tick marks
  Rgb grid{225, 225, 225};
  Rgb ink{40, 40, 40};  ///< all text except marker labels
  /// Throws InvalidInput naming the first bad field ("ChartSpec.panels[1].y.max: …").
  void validate() const;
};

/// Where draw_chart puts things (pixels) and the resolved axis ranges (axis units).
struct ChartLayout {
  int width = 0, height = 0;
  int left = 0;        ///< x pixel of the axis minimum (the left frame)
  int plot_width = 0;  ///< the axis maximum is at left + plot_width
  int title_y = 0, legend_y = 0, legend_rows = 0;
  std::vector<int> panel_top;     ///< y pixel of each panel's maximum (its top frame)
  std::vector<int> panel_height;  ///< its minimum is at panel_top + panel_height
  int axis_y = 0;                 ///< the bottom frame of the last panel
  int tick_label_y = 0, marker_label_y = 0, x_label_y = 0;
  double x_lo = 0, x_hi = 1;
  AxisScale x_scale = AxisScale::Linear;
  std::vector<double> y_lo, y_hi;
  std::vector<AxisScale> y_scale;

  /// Pixel column of data value x (NaN when it is not drawable on the axis); not clamped.
  double x_pixel(double x) const noexcept;
  /// Pixel row of data value y in panel p (NaN when not drawable); not clamped. p < panel count.
  double y_pixel(std::size_t panel, double y) const noexcept;
};

/// The layout of `spec` (validated first; InvalidInput as validate(), or naming ChartSpec.height
/// when it leaves panels under 8 pixels, or a step that would draw more than 10,000 lines).
ChartLayout chart_layout(const ChartSpec& spec);
/// The chart as an image of layout.width × layout.height pixels.
Image draw_chart(const ChartSpec& spec);
/// Tick value text: "%.4g" without exponent padding ("0.5", "10", "1e-5", "1e6"); −0 is "0".
std::string chart_tick_text(double value);

}  // namespace emoface::core
