#include "emoface/mindmap/chart.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "fixtures.hpp"

namespace mm = emoface::mindmap;

TEST(Chart, DrawsEveryEmotionAndTheActionTicks) {
  mm::Event e;
  e.time = 1.0;
  e.target = "alice";
  e.stimulus = "gift";
  const auto r = mm::simulate({mm::test::make_alice()}, {e}, {});
  const auto img = mm::mood_chart(r, mm::test::make_alice(), 0, {320, 120});
  ASSERT_EQ(img.width, 320);
  ASSERT_EQ(img.height, 120);
  ASSERT_EQ(img.rgb.size(), 320u * 120u * 3u);
  std::size_t count[2] = {0, 0}, white = 0;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) {
    const std::uint32_t c = (std::uint32_t{img.rgb[i]} << 16) | (std::uint32_t{img.rgb[i + 1]} << 8) | img.rgb[i + 2];
    for (std::size_t k = 0; k < 2; ++k) count[k] += c == mm::emotion_colour(k);
    white += c == 0xffffff;
  }
  EXPECT_GT(count[0], 200u);  // lines of ~300 px plus swatch and ticks
  EXPECT_GT(count[1], 200u);
  EXPECT_GT(white, img.rgb.size() / 3 / 2);
  EXPECT_NE(mm::emotion_colour(0), mm::emotion_colour(1));
}

TEST(Chart, BadArgumentsThrow) {
  const auto r = mm::simulate({mm::test::make_alice()}, {}, {});
  EXPECT_THROW(mm::mood_chart(r, mm::test::make_alice(), 0, {10, 100}), emoface::InvalidInput);
  EXPECT_THROW(mm::mood_chart(r, mm::test::make_alice(), 1), emoface::InvalidInput);
  mm::MindMap three = mm::test::make_alice();
  three.emotions.push_back("fear");
  EXPECT_THROW(mm::mood_chart(r, three, 0, {100, 100}), emoface::InvalidInput);
}

// Issue 19 item 4: title, legend names, tick values and axis labels in ink (40, 40, 40); small
// charts keep no text.
TEST(Chart, CarriesTitleLegendTicksAndLabels) {
  mm::Event e;
  e.time = 1.0;
  e.target = "alice";
  e.stimulus = "gift";
  const auto r = mm::simulate({mm::test::make_alice()}, {e}, {});
  auto ink_in = [](const emoface::core::Image& im, int x0, int y0, int x1, int y1) {
    int k = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const std::size_t i = (static_cast<std::size_t>(y) * im.width + x) * 3;
        k += im.rgb[i] == 40 && im.rgb[i + 1] == 40 && im.rgb[i + 2] == 40;
      }
    return k;
  };
  const auto big = mm::mood_chart(r, mm::test::make_alice(), 0, {800, 300});
  EXPECT_GT(ink_in(big, 300, 3, 500, 13), 40);          // "alice: mood", centred, scale 2
  EXPECT_GT(ink_in(big, 20, 17, 300, 27), 60);          // legend names after the swatches
  EXPECT_GT(ink_in(big, 300, 300 - 13, 500, 300), 20);  // "time (s)"
  EXPECT_GT(ink_in(big, 0, 40, 14, 260), 20);           // "mood", vertical
  const auto small = mm::mood_chart(r, mm::test::make_alice(), 0, {320, 120});
  EXPECT_GT(ink_in(small, 0, 0, 320, 120), 100);  // scale 1 text
  const auto tiny = mm::mood_chart(r, mm::test::make_alice(), 0, {150, 80});
  EXPECT_EQ(ink_in(tiny, 0, 0, 150, 80), 0);
}
