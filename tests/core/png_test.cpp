#include "emoface/core/png.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cstring>
#include <string>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/core/version.hpp"

namespace emoface::core {
namespace {

// Independent decoder: libpng reading from memory.
struct Decoded {
  int width = 0, height = 0, color_type = -1, bit_depth = 0;
  std::vector<std::uint8_t> rgb;
  std::vector<std::pair<std::string, std::string>> texts;
};

Decoded decode(const std::string& bytes) {
  Decoded d;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  EXPECT_TRUE(png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) << image.message;
  image.format = PNG_FORMAT_RGB;
  d.width = static_cast<int>(image.width);
  d.height = static_cast<int>(image.height);
  d.rgb.resize(PNG_IMAGE_SIZE(image));
  EXPECT_TRUE(png_image_finish_read(&image, nullptr, d.rgb.data(), 0, nullptr)) << image.message;
  // Text chunks through the classic API.
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  struct Reader {
    const std::string* s;
    std::size_t pos;
  } reader{&bytes, 0};
  png_set_read_fn(png, &reader, [](png_structp p, png_bytep out, png_size_t n) {
    auto* r = static_cast<Reader*>(png_get_io_ptr(p));
    std::memcpy(out, r->s->data() + r->pos, n);
    r->pos += n;
  });
  png_read_info(png, info);
  d.color_type = png_get_color_type(png, info);
  d.bit_depth = png_get_bit_depth(png, info);
  png_textp text = nullptr;
  int n = 0;
  png_get_text(png, info, &text, &n);
  for (int i = 0; i < n; ++i) d.texts.emplace_back(text[i].key, text[i].text);
  png_destroy_read_struct(&png, &info, nullptr);
  return d;
}

TEST(Png, RoundTripsThroughLibpngWithGeneratorStamp) {
  const int w = 37, h = 11;  // odd sizes
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = static_cast<std::uint8_t>((i * 7919u) >> 3);
  const std::string bytes = encode_png(w, h, rgb, {{"Title", "test image"}});
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const Decoded d = decode(bytes);
  EXPECT_EQ(d.width, w);
  EXPECT_EQ(d.height, h);
  EXPECT_EQ(d.color_type, PNG_COLOR_TYPE_RGB);
  EXPECT_EQ(d.bit_depth, 8);
  EXPECT_EQ(d.rgb, rgb);
  ASSERT_EQ(d.texts.size(), 2u);
  EXPECT_EQ(d.texts[0].first, "Software");
  EXPECT_EQ(d.texts[0].second, kGenerator);
  EXPECT_EQ(d.texts[1].first, "Title");
  EXPECT_EQ(d.texts[1].second, "test image");
  EXPECT_EQ(encode_png(w, h, rgb, {{"Title", "test image"}}), bytes);  // deterministic
}

TEST(Png, OnePixel) {
  const std::vector<std::uint8_t> rgb = {255, 0, 128};
  const Decoded d = decode(encode_png(1, 1, rgb));
  EXPECT_EQ(d.rgb, rgb);
}

TEST(Png, RejectsBadInput) {
  const std::vector<std::uint8_t> rgb(12);
  EXPECT_THROW(encode_png(0, 4, rgb), InvalidInput);
  EXPECT_THROW(encode_png(2, -1, rgb), InvalidInput);
  EXPECT_THROW(encode_png(3, 2, rgb), InvalidInput);  // 18 bytes needed
  EXPECT_THROW(encode_png(2, 2, nullptr, 12), InvalidInput);
  EXPECT_THROW(encode_png(2, 2, rgb, {{"", "x"}}), InvalidInput);
  EXPECT_THROW(encode_png(2, 2, rgb, {{" lead", "x"}}), InvalidInput);
  EXPECT_THROW(encode_png(2, 2, rgb, {{std::string(80, 'k'), "x"}}), InvalidInput);
  EXPECT_THROW(encode_png(2, 2, rgb, {{"Key", std::string("a\0b", 3)}}), InvalidInput);
}

}  // namespace
}  // namespace emoface::core
