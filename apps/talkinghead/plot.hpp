#pragma once
// A small PNG line plot of parameter tracks, drawn by core::draw_chart (the one chart routine,
// issue 18 item 3): white background, grey frame, grey grid every second and every 0.1 units, one
// coloured line per series in the order of kPlotColours. No text: captions in docs/channels.md name
// the colours.
#include <string>
#include <vector>

namespace emoface::talkinghead {

/// Colour names in series order: blue, red, green, orange, purple, brown, black, cyan.
extern const char* const kPlotColours[8];

/// Plots series (each frames long, frame f at f/fps seconds) into a width × height PNG at `path`
/// (written atomically). The value axis spans [min(0, data), max(1, data)]. Throws on I/O errors.
void plot_png(const std::string& path, const std::vector<std::vector<double>>& series, double fps,
              int width = 900, int height = 360);

}  // namespace emoface::talkinghead
