#pragma once
// Emotion charts (thesis Figs. 7.4–7.11): stacked line-chart panels sharing the x axis (match
// minutes), a grid every 10 x-units with tick values, y tick values (0, y_max/2, y_max), optional
// vertical markers, a title, axis labels and a legend of the named series (issue 19: text with
// core::draw_text, the one bitmap font), drawn into a core::Image; render_chart encodes it as PNG
// with a tEXt "Software" chunk carrying emoface::kGenerator.
// Used by `parlee run --plot` and by the obie pipeline (libs/obie), so both draw the same charts.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/core/image.hpp"
#include "emoface/parlee/agent.hpp"

namespace emoface::parlee {

struct ChartSeries {
  std::vector<double> x, y;  ///< same length; x in chart units (e.g. match minutes)
  std::array<std::uint8_t, 3> rgb{0, 0, 0};
  std::string name;  ///< legend entry ("" = not in the legend)
};

struct ChartPanel {
  std::string title;  ///< drawn in the top-left corner (a–z, 0–9, space, '-', '_', '.', ':', '\'')
  std::vector<ChartSeries> series;
  double y_max = 1.0;  ///< y range is [0, y_max], > 0
};

/// A vertical line across every panel at `x` (e.g. a goal), labelled under the x axis.
struct ChartMarker {
  double x = 0.0;
  std::string label;
  std::array<std::uint8_t, 3> rgb{200, 60, 60};
};

struct ChartOptions {
  int width = 960;         ///< pixels, [200, 8192]
  int panel_height = 150;  ///< pixels per panel, [40, 2048]
  double x_max = 0.0;      ///< x range [0, x_max]; 0 = the largest x of any series rounded up to 10
  std::vector<ChartMarker> markers;
  std::string title;       ///< centred above the plot ("" = none)
  std::string x_label;     ///< under the x tick values ("" = none)
  std::string y_label;     ///< vertical, left of the y tick values ("" = none)
  void validate() const;   ///< throws InvalidInput
};

/// Where draw_chart puts things (pixels): panel p spans rows [top + p·(panel_height + 22),
/// … + panel_height], columns [left, left + plot_width]. top = 8 without title and legend.
struct ChartLayout {
  int left = 40, top = 8, plot_width = 0, height = 0, title_y = 6, legend_y = 6;
};
ChartLayout chart_layout(const std::vector<ChartPanel>& panels, const ChartOptions& options);

/// Draws the panels (lines with core::draw_line, text with core::draw_text). Throws InvalidInput
/// for no panels or bad options.
core::Image draw_chart(const std::vector<ChartPanel>& panels, const ChartOptions& options);
/// draw_chart + core::encode_png (PNG bytes with the tEXt "Software" stamp).
std::string render_chart(const std::vector<ChartPanel>& panels, const ChartOptions& options);

/// The four emotions of the thesis' charts, with their basic-emotion index (ESV order) and colour:
/// fear, happiness, surprise, sadness (Figs. 7.4, 7.5, 7.7, 7.8).
struct ChartEmotion {
  const char* name;
  std::size_t basic;  ///< index into StepRecord::basic (sadness, happiness, anger, fear, disgust, surprise)
  std::array<std::uint8_t, 3> rgb;
};
const std::vector<ChartEmotion>& chart_emotions();

/// One panel per chart_emotions() entry for one run: "<name> <emotion>", the basic intensity over
/// StepRecord::time (series named by the emotion, for the legend).
std::vector<ChartPanel> emotion_panels(const std::string& name, const std::vector<StepRecord>& run);

}  // namespace emoface::parlee
