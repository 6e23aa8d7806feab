// The shared 3×5 bitmap font (issue 19: text on charts and strips).
#include "emoface/core/font.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"

namespace emoface::core {
namespace {

struct Im {
  int w, h;
  std::vector<std::uint8_t> rgb;
  Im(int w_, int h_) : w(w_), h(h_), rgb(static_cast<std::size_t>(w_) * h_ * 3, 255) {}
  bool ink(int x, int y) const { return rgb[(static_cast<std::size_t>(y) * w + x) * 3] == 0; }
  int count() const {
    int n = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) n += ink(x, y);
    return n;
  }
};

TEST(Text, GlyphPixelsByHand) {
  Im im(40, 12);
  // '1' rows 010 110 010 010 111 at scale 2: row 0 sets x 2..3, row 1 x 0..3, row 4 x 0..5
  draw_text(im.rgb, im.w, im.h, 0, 0, "1", {0, 0, 0}, 2);
  EXPECT_TRUE(im.ink(2, 0));
  EXPECT_TRUE(im.ink(3, 1));
  EXPECT_FALSE(im.ink(0, 0));
  EXPECT_TRUE(im.ink(0, 2));
  EXPECT_TRUE(im.ink(5, 9));
  EXPECT_FALSE(im.ink(6, 9));
  // 1·2 + 2·2 + 1·2 + 1·2 + 3·2 = 16 bits set in the glyph, 4 pixels each at scale 2
  EXPECT_EQ(im.count(), 4 * (1 + 2 + 1 + 1 + 3));
  EXPECT_EQ(text_width("abc", 2), 24);
  EXPECT_EQ(text_width("abc", 0), 12);  // scale < 1 counts as 1
  EXPECT_EQ(text_height(3), 15);
  EXPECT_TRUE(has_glyph('Q'));
  EXPECT_TRUE(has_glyph('%'));
  EXPECT_FALSE(has_glyph('#'));
}

TEST(Text, UpperCaseIsLowerCaseAndUnknownAdvances) {
  Im a(40, 6), b(40, 6), c(40, 6);
  draw_text(a.rgb, a.w, a.h, 0, 0, "Ab", {0, 0, 0}, 1);
  draw_text(b.rgb, b.w, b.h, 0, 0, "ab", {0, 0, 0}, 1);
  EXPECT_EQ(a.rgb, b.rgb);
  draw_text(c.rgb, c.w, c.h, 0, 0, "#b", {0, 0, 0}, 1);  // '#' leaves a blank cell
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_FALSE(c.ink(x, y));
  for (int y = 0; y < 5; ++y)
    for (int x = 4; x < 8; ++x) EXPECT_EQ(c.ink(x, y), b.ink(x, y));
}

TEST(Text, VerticalIsAQuarterTurn) {
  Im h(12, 12), v(12, 12);
  draw_text(h.rgb, h.w, h.h, 0, 0, "7", {0, 0, 0}, 1);
  draw_text_vertical(v.rgb, v.w, v.h, 0, 11, "7", {0, 0, 0}, 1);
  // horizontal pixel (col b, row r) lands at (r, 10 − b) when turned counter-clockwise
  for (int r = 0; r < 5; ++r)
    for (int b = 0; b < 3; ++b) EXPECT_EQ(v.ink(r, 10 - b), h.ink(b, r)) << r << " " << b;
  EXPECT_EQ(v.count(), h.count());
}

TEST(Text, ClipsAndRejectsWrongBuffers) {
  Im im(10, 4);
  draw_text(im.rgb, im.w, im.h, 6, 2, "zzzz", {0, 0, 0}, 3);       // partly outside: clipped
  draw_text(im.rgb, im.w, im.h, -100, -100, "abc", {0, 0, 0}, 2);  // wholly outside
  draw_text_vertical(im.rgb, im.w, im.h, 50, 50, "abc", {0, 0, 0}, 2);
  EXPECT_GT(im.count(), 0);
  std::vector<std::uint8_t> small(5);
  EXPECT_THROW(draw_text(small, 10, 4, 0, 0, "a", {0, 0, 0}), InvalidInput);
  EXPECT_THROW(draw_text_vertical(small, 10, 4, 0, 0, "a", {0, 0, 0}), InvalidInput);
  EXPECT_THROW(draw_text(small, -1, 4, 0, 0, "a", {0, 0, 0}), InvalidInput);
}

}  // namespace
}  // namespace emoface::core
