#pragma once
// A minimal line plot into a core::Image (for the GA error curve PNG of the retarget CLI).
#include <vector>

#include "emoface/core/image.hpp"

namespace emoface::retarget {

/// Plots each series (same length not required) as a polyline (core::draw_line, 2 pixels thick)
/// scaled to the common y range, on white with a grey frame; series colours cycle through blue,
/// red, green. log_y: plot log10 of the values (non-positive values are clamped to the smallest
/// positive one). Throws InvalidInput for sizes < 32 px or no points at all.
core::Image plot_series(const std::vector<std::vector<double>>& series, int width = 480,
                        int height = 320, bool log_y = true);

}  // namespace emoface::retarget
