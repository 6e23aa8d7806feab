#pragma once
// Mood charts: one character's mood over time as a core::Image (core::encode_png makes the PNG),
// drawn by core::draw_chart (issue 18 item 3, the one chart routine). Each emotion node is a
// coloured line (palette order = emotion order, listed in docs/mindmap.md); triggered actions are
// ticks under the plot (tall = stimulus, middle = chain, short = decay hint) in the colour of the
// emotion that chose them. Grid: mood 0, 0.25, …, 1 and one vertical line per second (per 5 s past
// 30 s, per 30 s past 300 s). Charts of at least 200 × 100 pixels carry text (core's font): the
// title "<character>: mood", a legend naming the emotion nodes, tick values (mood 0, 0.5, 1;
// seconds, thinned so that they do not touch) and axis labels; smaller ones only lines and ticks.
#include <cstdint>
#include <vector>

#include "emoface/core/image.hpp"
#include "emoface/mindmap/mind_map.hpp"
#include "emoface/mindmap/simulation.hpp"

namespace emoface::mindmap {

struct ChartOptions {
  int width = 800;   ///< pixels, [64, 8192]
  int height = 300;  ///< pixels, [64, 8192]
  void validate() const;
};

/// The palette colour (0xRRGGBB) of emotion node i.
std::uint32_t emotion_colour(std::size_t i) noexcept;

/// Chart of character `c` of `result` (whose map is `map`).
core::Image mood_chart(const SimulationResult& result, const MindMap& map, std::size_t c,
                       const ChartOptions& options = {});

}  // namespace emoface::mindmap
