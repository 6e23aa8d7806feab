#pragma once
// A minimal line plot into a core::Image (for the GA error curve PNG of the retarget CLI), drawn by
// core::draw_chart (the one chart routine, issue 18 item 3).
#include <vector>

#include "emoface/core/image.hpp"

namespace emoface::retarget {

/// Plots each series (same length not required) as a polyline 2 pixels thick over the point index
/// (x from 0 to the longest series' last index), scaled to the common y range of the data, on white
/// with a grey frame and no text; series colours cycle through blue, red, green. log_y: a log10 y
/// axis. Non-finite values (and non-positive ones on the log axis) are gaps. Throws InvalidInput
/// for sizes outside [32, 8192] px or no points at all.
core::Image plot_series(const std::vector<std::vector<double>>& series, int width = 480,
                        int height = 320, bool log_y = true);

}  // namespace emoface::retarget
