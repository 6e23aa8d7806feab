#pragma once
// The one bitmap text routine of emoface's pictures (charts, mood charts, crowd strips, key-moment
// sheets): a 3×5 pixel font — digits, a–z (upper case drawn as lower case) and the punctuation
// ` -_.:'!,/+()%=<>` — each glyph 4 columns wide with the gap, scaled by an integer factor. Drawn
// straight into 8-bit RGB buffers (row-major, top row first, 3 bytes per pixel); pixels outside the
// image are clipped. Moved here from libs/parlee (chart.cpp) so that every library draws the same
// letters (issue 19).
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace emoface::core {

using Rgb = std::array<std::uint8_t, 3>;

/// Draws `text` with its top-left corner at (x, y), `scale` ≥ 1 (smaller values count as 1).
/// Characters the font lacks advance the pen without ink. Throws InvalidInput if `rgb` does not
/// hold width·height·3 bytes.
void draw_text(std::vector<std::uint8_t>& rgb, int width, int height, int x, int y,
               std::string_view text, Rgb colour, int scale = 2);
/// Rotated a quarter turn counter-clockwise (reads bottom to top, for y-axis labels): the text's
/// baseline runs up from (x, y), glyph rows stacked to the right of x.
void draw_text_vertical(std::vector<std::uint8_t>& rgb, int width, int height, int x, int y,
                        std::string_view text, Rgb colour, int scale = 2);
/// Width in pixels of draw_text(text, scale): 4·scale per character (the last gap included).
int text_width(std::string_view text, int scale = 2) noexcept;
/// Height in pixels of a line of draw_text: 5·scale.
inline int text_height(int scale = 2) noexcept { return 5 * (scale < 1 ? 1 : scale); }
/// Whether the font has a glyph for `c` (letters of either case, digits, the punctuation above).
bool has_glyph(char c) noexcept;

}  // namespace emoface::core
