#include "emoface/core/font.hpp"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <string>

#include "emoface/core/errors.hpp"

namespace emoface::core {
namespace {

// 3×5 pixel font: each glyph is 5 rows of 3 bits (MSB = left).
struct Glyph {
  char c;
  std::uint8_t rows[5];
};
constexpr Glyph kFont[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}},  {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}},  {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}},  {'a', {2, 5, 7, 5, 5}}, {'b', {6, 5, 6, 5, 6}},
    {'c', {7, 4, 4, 4, 7}}, {'d', {6, 5, 5, 5, 6}},  {'e', {7, 4, 6, 4, 7}}, {'f', {7, 4, 6, 4, 4}},
    {'g', {7, 4, 5, 5, 7}}, {'h', {5, 5, 7, 5, 5}},  {'i', {7, 2, 2, 2, 7}}, {'j', {1, 1, 1, 5, 7}},
    {'k', {5, 5, 6, 5, 5}}, {'l', {4, 4, 4, 4, 7}},  {'m', {5, 7, 7, 5, 5}}, {'n', {6, 5, 5, 5, 5}},
    {'o', {7, 5, 5, 5, 7}}, {'p', {7, 5, 7, 4, 4}},  {'q', {7, 5, 5, 7, 1}}, {'r', {7, 5, 6, 5, 5}},
    {'s', {7, 4, 7, 1, 7}}, {'t', {7, 2, 2, 2, 2}},  {'u', {5, 5, 5, 5, 7}}, {'v', {5, 5, 5, 5, 2}},
    {'w', {5, 5, 7, 7, 5}}, {'x', {5, 5, 2, 5, 5}},  {'y', {5, 5, 7, 2, 2}}, {'z', {7, 1, 2, 4, 7}},
    {'-', {0, 0, 7, 0, 0}}, {'_', {0, 0, 0, 0, 7}},  {'.', {0, 0, 0, 0, 2}}, {' ', {0, 0, 0, 0, 0}},
    {':', {0, 2, 0, 2, 0}}, {'\'', {2, 2, 0, 0, 0}}, {'!', {2, 2, 2, 0, 2}}, {',', {0, 0, 0, 2, 4}},
    {'/', {1, 1, 2, 4, 4}}, {'+', {0, 2, 7, 2, 0}},  {'(', {1, 2, 2, 2, 1}}, {')', {4, 2, 2, 2, 4}},
    {'%', {5, 1, 2, 4, 5}}, {'=', {0, 7, 0, 7, 0}},  {'<', {1, 2, 4, 2, 1}}, {'>', {4, 2, 1, 2, 4}},
};

const Glyph* glyph(char ch) {
  const char lc = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (const auto& g : kFont)
    if (g.c == lc) return &g;
  return nullptr;
}

void check(const std::vector<std::uint8_t>& rgb, int width, int height) {
  if (width < 0 || height < 0 ||
      rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3)
    throw InvalidInput("draw_text: the image buffer does not hold width x height x 3 bytes");
}

void put(std::vector<std::uint8_t>& rgb, int width, int height, int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  const auto i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)) *
                 3;
  rgb[i] = c[0];
  rgb[i + 1] = c[1];
  rgb[i + 2] = c[2];
}

}  // namespace

bool has_glyph(char c) noexcept { return glyph(c) != nullptr; }

int text_width(std::string_view text, int scale) noexcept {
  return static_cast<int>(text.size()) * 4 * std::max(scale, 1);
}

void draw_text(std::vector<std::uint8_t>& rgb, int width, int height, int x, int y,
               std::string_view text, Rgb colour, int scale) {
  check(rgb, width, height);
  scale = std::max(scale, 1);
  for (char ch : text) {
    if (const Glyph* g = glyph(ch)) {
      for (int r = 0; r < 5; ++r)
        for (int b = 0; b < 3; ++b)
          if (g->rows[r] & (4 >> b))
            for (int a = 0; a < scale; ++a)
              for (int d = 0; d < scale; ++d)
                put(rgb, width, height, x + b * scale + a, y + r * scale + d, colour);
    }
    x += 4 * scale;
  }
}

void draw_text_vertical(std::vector<std::uint8_t>& rgb, int width, int height, int x, int y,
                        std::string_view text, Rgb colour, int scale) {
  check(rgb, width, height);
  scale = std::max(scale, 1);
  // a quarter turn counter-clockwise: glyph column b → up (−y), glyph row r → right (+x)
  for (char ch : text) {
    if (const Glyph* g = glyph(ch)) {
      for (int r = 0; r < 5; ++r)
        for (int b = 0; b < 3; ++b)
          if (g->rows[r] & (4 >> b))
            for (int a = 0; a < scale; ++a)
              for (int d = 0; d < scale; ++d)
                put(rgb, width, height, x + r * scale + d, y - b * scale - a - 1, colour);
    }
    y -= 4 * scale;
  }
}

}  // namespace emoface::core
