// core::Image (issue 18 item 3): each drawing primitive against pixels computed by hand, clipping
// at the borders, PNG round trips (our encoder and libpng's, every filter and colour type we read)
// and bad input.
#include "emoface/core/image.hpp"

#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <utility>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/video.hpp"

namespace emoface::core {
namespace {

constexpr Rgb kWhite{255, 255, 255}, kInk{10, 20, 30};

// The inked pixels (those equal to kInk) as (x, y) pairs.
std::set<std::pair<int, int>> inked(const Image& im) {
  std::set<std::pair<int, int>> out;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x)
      if (im.at(x, y) == kInk) out.insert({x, y});
  return out;
}
using Pixels = std::set<std::pair<int, int>>;

TEST(Image, ConstructedFilledAndChecked) {
  const Image im(3, 2, {1, 2, 3});
  EXPECT_EQ(im.rgb.size(), 18u);
  EXPECT_EQ(im.at(2, 1), (Rgb{1, 2, 3}));
  EXPECT_EQ(im.offset(2, 1), 15u);
  EXPECT_NO_THROW(im.validate());
  EXPECT_TRUE(Image().empty());
  EXPECT_NO_THROW(Image().validate());
  EXPECT_EQ(Image(1, 1).at(0, 0), kWhite);  // white by default
}

TEST(Image, BadSizesAndBuffersAreRejected) {
  EXPECT_THROW(Image(0, 5), InvalidInput);
  EXPECT_THROW(Image(5, -1), InvalidInput);
  EXPECT_THROW(Image(kMaxImageSide + 1, 1), InvalidInput);
  EXPECT_THROW(Image(1 << 14, 1 << 13), InvalidInput);  // 2^27 pixels > 2^26
  EXPECT_NO_THROW(Image(kMaxImageSide, 1));
  Image im(4, 4);
  im.rgb.pop_back();
  EXPECT_THROW(im.validate(), InvalidInput);
  EXPECT_THROW(fill(im, kInk), InvalidInput);
  EXPECT_THROW(encode_png(im), InvalidInput);
  EXPECT_THROW(encode_png(Image()), InvalidInput);  // empty
  Image shape;
  shape.width = 2;  // 2 x 0 is not a size
  EXPECT_THROW(shape.validate(), InvalidInput);
}

TEST(Image, SetAndAtClip) {
  Image im(3, 3);
  im.set(-1, 0, kInk);
  im.set(0, 3, kInk);
  im.set(3, 0, kInk);
  EXPECT_TRUE(inked(im).empty());
  im.set(2, 2, kInk);
  EXPECT_EQ(inked(im), (Pixels{{2, 2}}));
  EXPECT_THROW(im.at(3, 0), InvalidInput);
  EXPECT_THROW(im.at(0, -1), InvalidInput);
}

TEST(Image, FillAndBlendByHand) {
  Image im(2, 2, {100, 0, 255});
  blend(im, 0, 0, {200, 255, 0}, 0.25);  // 100 + 0.25·100 = 125; 0 + 63.75 → 64; 255 − 63.75 → 191
  EXPECT_EQ(im.at(0, 0), (Rgb{125, 64, 191}));
  blend(im, 1, 0, {0, 0, 0}, 2.0);  // alpha clamped to 1: the colour itself
  EXPECT_EQ(im.at(1, 0), (Rgb{0, 0, 0}));
  blend(im, 0, 1, {0, 0, 0}, std::nan(""));  // NaN counts as 0: unchanged
  EXPECT_EQ(im.at(0, 1), (Rgb{100, 0, 255}));
  blend(im, 1, 1, {0, 255, 0}, 0.5);  // 50, 127.5 → 128 (halves away from zero), 127.5 → 128
  EXPECT_EQ(im.at(1, 1), (Rgb{50, 128, 128}));
  blend(im, 5, 5, {0, 0, 0}, 1.0);  // outside: nothing
  fill(im, kInk);
  EXPECT_EQ(inked(im).size(), 4u);
}

TEST(Image, FillRectByHandAndClipped) {
  Image im(5, 5);
  fill_rect(im, 1, 1, 2, 3, kInk);
  EXPECT_EQ(inked(im), (Pixels{{1, 1}, {2, 1}, {1, 2}, {2, 2}, {1, 3}, {2, 3}}));
  Image c(4, 4);
  fill_rect(c, -1, -1, 3, 3, kInk);  // only the 2×2 inside
  EXPECT_EQ(inked(c), (Pixels{{0, 0}, {1, 0}, {0, 1}, {1, 1}}));
  fill_rect(c, 3, 3, 100, 100, kInk);
  EXPECT_EQ(inked(c).size(), 5u);
  Image e(4, 4);
  fill_rect(e, 0, 0, 0, 3, kInk);
  fill_rect(e, 0, 0, 3, -1, kInk);
  EXPECT_TRUE(inked(e).empty());
}

TEST(Image, FillCircleByHand) {
  Image im(5, 5);
  fill_circle(im, 2, 2, 1.0, kInk);  // distance² ≤ 1: the centre and its 4 neighbours (corners: 2)
  EXPECT_EQ(inked(im), (Pixels{{2, 2}, {1, 2}, {3, 2}, {2, 1}, {2, 3}}));
  Image b(5, 5);
  fill_circle(b, 2, 2, 1.5, kInk);  // corners at distance² 2 ≤ 2.25: the 3×3 block
  EXPECT_EQ(inked(b).size(), 9u);
  Image h(4, 4);
  fill_circle(h, 0.5, 0.5, 0.5,
              kInk);  // off-grid centre: the 4 pixels at distance² 0.5 > 0.25: none
  EXPECT_TRUE(inked(h).empty());
  fill_circle(h, 0.5, 0.5, 0.75, kInk);  // 0.5 ≤ 0.5625; the next ring (2.5) is out
  EXPECT_EQ(inked(h), (Pixels{{0, 0}, {1, 0}, {0, 1}, {1, 1}}));
  Image c(4, 4);
  fill_circle(c, 0, 0, 1.0, kInk);  // clipped at the corner
  EXPECT_EQ(inked(c), (Pixels{{0, 0}, {1, 0}, {0, 1}}));
  fill_circle(c, 1e300, 0, 1.0, kInk);
  fill_circle(c, 1, 1, -1.0, kInk);
  fill_circle(c, 1, 1, std::numeric_limits<double>::infinity(), kInk);
  EXPECT_EQ(inked(c).size(), 3u);
}

TEST(Image, LinesByHand) {
  Image im(6, 3);
  draw_line(im, 0, 0, 3, 0, kInk);
  EXPECT_EQ(inked(im), (Pixels{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  // (0,0)–(2,1): n = ⌈2⌉ + 1 = 3 steps, t = 0, 1/3, 2/3, 1 → x 0, 0.67, 1.33, 2 and y 0, 0.33,
  // 0.67, 1, rounded: (0,0) (1,0) (1,1) (2,1)
  Image d(6, 3);
  draw_line(d, 0, 0, 2, 1, kInk);
  EXPECT_EQ(inked(d), (Pixels{{0, 0}, {1, 0}, {1, 1}, {2, 1}}));
  Image r(6, 3);
  draw_line(r, 2, 1, 0, 0, kInk);  // reversed: the same samples in the other order
  EXPECT_EQ(inked(r), inked(d));
  // (0,0)–(1,0): t = ½ gives x = 0.5, rounded away from zero to 1
  Image h(3, 1);
  draw_line(h, 0, 0, 1, 0, kInk);
  EXPECT_EQ(inked(h), (Pixels{{0, 0}, {1, 0}}));
}

TEST(Image, LineThicknessStamps) {
  Image two(5, 5);
  draw_line(two, 1, 1, 1, 1, kInk, 2);  // offsets 0 … 1: right, down and diagonal
  EXPECT_EQ(inked(two), (Pixels{{1, 1}, {2, 1}, {1, 2}, {2, 2}}));
  Image three(5, 5);
  draw_line(three, 2, 2, 2, 2, kInk, 3);  // offsets −1 … 1: centred
  EXPECT_EQ(inked(three).size(), 9u);
  EXPECT_EQ(three.at(1, 1), kInk);
  EXPECT_EQ(three.at(3, 3), kInk);
  Image four(6, 6);
  draw_line(four, 2, 2, 2, 2, kInk, 4);  // offsets −1 … 2
  EXPECT_EQ(inked(four).size(), 16u);
  EXPECT_EQ(four.at(1, 1), kInk);
  EXPECT_EQ(four.at(4, 4), kInk);
  EXPECT_THROW(draw_line(four, 0, 0, 1, 1, kInk, 0), InvalidInput);
  EXPECT_THROW(draw_line(four, 0, 0, 1, 1, kInk, 17), InvalidInput);
}

TEST(Image, LinesClipAndSkipBadEnds) {
  Image im(6, 3);
  draw_line(im, -5, 1, 10, 1, kInk);  // crosses the whole image: the visible row only
  EXPECT_EQ(inked(im).size(), 6u);
  for (int x = 0; x < 6; ++x) EXPECT_EQ(im.at(x, 1), kInk);
  Image n(6, 3);
  draw_line(n, 0, 0, std::nan(""), 2, kInk);
  draw_line(n, 0, 0, 2e9, 2, kInk);
  draw_line(n, 0, 0, 2e5, 0, kInk);  // longer than 10^5 pixels
  EXPECT_TRUE(inked(n).empty());
}

TEST(Image, TextThroughTheSharedFont) {
  Image im(8, 6);
  draw_text(im, 0, 0, "1", kInk, 1);  // '1' rows 010 110 010 010 111
  EXPECT_EQ(inked(im), (Pixels{{1, 0}, {0, 1}, {1, 1}, {1, 2}, {1, 3}, {0, 4}, {1, 4}, {2, 4}}));
  Image v(6, 8);
  draw_text_vertical(v, 0, 4, "-", kInk, 1);  // '-' row 2 = 111 → column x 2, rows 3, 2, 1
  EXPECT_EQ(inked(v), (Pixels{{2, 3}, {2, 2}, {2, 1}}));
}

TEST(Image, BlitClipsAtEverySide) {
  Image src(2, 2);
  src.set(0, 0, {1, 1, 1});
  src.set(1, 0, {2, 2, 2});
  src.set(0, 1, {3, 3, 3});
  src.set(1, 1, {4, 4, 4});
  Image dst(3, 3, {9, 9, 9});
  blit(dst, src, 2, 2);  // only src (0,0) lands, at (2,2)
  EXPECT_EQ(dst.at(2, 2), (Rgb{1, 1, 1}));
  EXPECT_EQ(dst.at(1, 1), (Rgb{9, 9, 9}));
  blit(dst, src, -1, -1);  // only src (1,1) lands, at (0,0)
  EXPECT_EQ(dst.at(0, 0), (Rgb{4, 4, 4}));
  EXPECT_EQ(dst.at(1, 0), (Rgb{9, 9, 9}));
  blit(dst, src, 1, -1);  // src row 1 at dst row 0, columns 1..2
  EXPECT_EQ(dst.at(1, 0), (Rgb{3, 3, 3}));
  EXPECT_EQ(dst.at(2, 0), (Rgb{4, 4, 4}));
  const Image before = dst;
  blit(dst, src, 3, 0);
  blit(dst, src, 0, -2);
  EXPECT_EQ(dst.rgb, before.rgb);
}

TEST(Image, TileLaysOutASheet) {
  std::vector<Image> images;
  for (std::uint8_t k = 1; k <= 3; ++k) images.emplace_back(2, 1, Rgb{k, k, k});
  const Image sheet = tile(images, 2, 1, {7, 7, 7});
  EXPECT_EQ(sheet.width, 2 * 2 + 3 * 1);
  EXPECT_EQ(sheet.height, 2 * 1 + 3 * 1);
  EXPECT_EQ(sheet.at(0, 0), (Rgb{7, 7, 7}));
  EXPECT_EQ(sheet.at(1, 1), (Rgb{1, 1, 1}));
  EXPECT_EQ(sheet.at(2, 1), (Rgb{1, 1, 1}));
  EXPECT_EQ(sheet.at(3, 1), (Rgb{7, 7, 7}));
  EXPECT_EQ(sheet.at(4, 1), (Rgb{2, 2, 2}));
  EXPECT_EQ(sheet.at(1, 3), (Rgb{3, 3, 3}));
  EXPECT_EQ(sheet.at(4, 3), (Rgb{7, 7, 7}));  // no fourth image
  EXPECT_EQ(tile(images, 10, 0).width, 6);    // fewer images than columns
  EXPECT_THROW(tile({}, 2), InvalidInput);
  EXPECT_THROW(tile(images, 0), InvalidInput);
  EXPECT_THROW(tile(images, 2, -1), InvalidInput);
  images.emplace_back(1, 2);
  EXPECT_THROW(tile(images, 2), InvalidInput);
}

// ---- PNG ----

Image pattern(int w, int h) {
  Image im(w, h);
  for (std::size_t i = 0; i < im.rgb.size(); ++i)
    im.rgb[i] = static_cast<std::uint8_t>((i * 7919u) >> 3);
  return im;
}

TEST(ImagePng, RoundTripsThroughOurEncoder) {
  const Image im = pattern(37, 11);
  const Image back = decode_png(encode_png(im));
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 11);
  EXPECT_EQ(back.rgb, im.rgb);
  const std::string path =
      (std::filesystem::temp_directory_path() / "emoface_image_test.png").string();
  write_png(path, im, {{"Title", "t"}});
  EXPECT_EQ(read_png(path).rgb, im.rgb);
  std::filesystem::remove(path);
  EXPECT_THROW(read_png(path), IoError);
}

// libpng writes with its own (adaptive) row filters, in any colour type: our decoder must agree.
std::string libpng_encode(const std::vector<std::uint8_t>& pixels, int w, int h,
                          png_uint_32 format) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = format;
  png_alloc_size_t size = 0;
  EXPECT_TRUE(png_image_write_to_memory(&image, nullptr, &size, 0, pixels.data(), 0, nullptr));
  std::string out(size, '\0');
  EXPECT_TRUE(png_image_write_to_memory(&image, out.data(), &size, 0, pixels.data(), 0, nullptr));
  out.resize(size);
  return out;
}

TEST(ImagePng, ReadsLibpngFilesOfEveryColourType) {
  const int w = 29, h = 13;
  const Image im = pattern(w, h);
  EXPECT_EQ(decode_png(libpng_encode(im.rgb, w, h, PNG_FORMAT_RGB)).rgb, im.rgb);
  std::vector<std::uint8_t> rgba, grey, grey_alpha;
  Image grey_image(w, h);
  for (std::size_t p = 0; p < static_cast<std::size_t>(w) * h; ++p) {
    rgba.insert(rgba.end(), {im.rgb[3 * p], im.rgb[3 * p + 1], im.rgb[3 * p + 2],
                             static_cast<std::uint8_t>(p)});
    grey.push_back(im.rgb[3 * p]);
    grey_alpha.insert(grey_alpha.end(), {im.rgb[3 * p], 200});
    grey_image.rgb[3 * p] = grey_image.rgb[3 * p + 1] = grey_image.rgb[3 * p + 2] = im.rgb[3 * p];
  }
  EXPECT_EQ(decode_png(libpng_encode(rgba, w, h, PNG_FORMAT_RGBA)).rgb, im.rgb);  // alpha dropped
  EXPECT_EQ(decode_png(libpng_encode(grey, w, h, PNG_FORMAT_GRAY)).rgb, grey_image.rgb);
  EXPECT_EQ(decode_png(libpng_encode(grey_alpha, w, h, PNG_FORMAT_GA)).rgb, grey_image.rgb);
}

// A PNG with a hand-made IHDR and one IDAT of `raw` (filter bytes included), CRCs computed by zlib.
std::string chunk(const std::string& type, const std::string& data) {
  std::string out;
  auto put32 = [&out](std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>((v >> s) & 0xff));
  };
  put32(static_cast<std::uint32_t>(data.size()));
  const std::string body = type + data;
  out += body;
  put32(static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
  return out;
}
std::string handmade(std::uint32_t w, std::uint32_t h, int depth, int colour, int interlace,
                     const std::string& raw) {
  std::string ihdr;
  for (std::uint32_t v : {w, h})
    for (int s = 24; s >= 0; s -= 8) ihdr.push_back(static_cast<char>((v >> s) & 0xff));
  ihdr += {static_cast<char>(depth), static_cast<char>(colour), 0, 0, static_cast<char>(interlace)};
  uLongf n = compressBound(static_cast<uLong>(raw.size()));
  std::string z(n, '\0');
  compress(reinterpret_cast<Bytef*>(z.data()), &n, reinterpret_cast<const Bytef*>(raw.data()),
           static_cast<uLong>(raw.size()));
  z.resize(n);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", z) +
         chunk("IEND", "");
}

TEST(ImagePng, EveryFilterByHand) {
  // 2×1 RGB rows; row 0 None (10 20 30, 40 50 60); row 1 the same pixels through each filter.
  const std::string row0("\0\x0a\x14\x1e\x28\x32\x3c", 7);
  // Up: differences to row 0 are all 0; Sub: first pixel as is, second minus the first (30 each);
  // Average: (left + up) / 2 → first 10−5=5, 20−10=10, 30−15=15; second 40−(10+40)/2=15, 50−35=15,
  // 60−45=15. Paeth: first pixel predicts up (10,20,30) → 0; second: a=b=left/up... p = a + b − c.
  const std::string up("\x02\0\0\0\0\0\0", 7), sub("\x01\x0a\x14\x1e\x1e\x1e\x1e", 7),
      avg("\x03\x05\x0a\x0f\x0f\x0f\x0f", 7);
  // Paeth, second pixel, first channel: a = 10 (left), b = 40 (up), c = 10 (up-left): p = 40,
  // pa = 30, pb = 0, pc = 30 → b; residual 40 − 40 = 0.
  const std::string paeth("\x04\0\0\0\0\0\0", 7);
  for (const std::string& row1 : {up, sub, avg, paeth}) {
    const Image im = decode_png(handmade(2, 2, 8, 2, 0, row0 + row1));
    EXPECT_EQ(im.at(0, 1), (Rgb{10, 20, 30})) << int(row1[0]);
    EXPECT_EQ(im.at(1, 1), (Rgb{40, 50, 60})) << int(row1[0]);
  }
}

void expect_format_error(const std::string& bytes, const std::string& part) {
  try {
    decode_png(bytes, "pic.png");
    ADD_FAILURE() << "no error, expected: " << part;
  } catch (const FormatError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("pic.png"), std::string::npos) << what;
    EXPECT_NE(what.find(part), std::string::npos) << what;
  }
}

TEST(ImagePng, BadFilesAreLocatedErrors) {
  const std::string good = encode_png(pattern(5, 4));
  expect_format_error("GIF89a", "signature");
  expect_format_error(good.substr(0, 8), "truncated");
  for (std::size_t n = 0; n < good.size(); ++n)  // every prefix fails cleanly
    EXPECT_THROW(decode_png(good.substr(0, n)), FormatError) << n;
  std::string crc = good;
  crc[20] ^= 1;  // inside IHDR
  expect_format_error(crc, "CRC mismatch");
  const std::string raw(2 * (2 * 3 + 1), '\0');
  expect_format_error(handmade(2, 2, 16, 2, 0, raw), "bit depth 16");
  expect_format_error(handmade(2, 2, 8, 3, 0, raw), "colour type 3");
  expect_format_error(handmade(2, 2, 8, 2, 1, raw), "interlaced");
  expect_format_error(handmade(0, 2, 8, 2, 0, raw), "out of range");
  expect_format_error(handmade(100000, 100000, 8, 2, 0, raw), "out of range");
  expect_format_error(handmade(2, 2, 8, 2, 0, raw.substr(0, 10)), "expected 14");  // short data
  expect_format_error(handmade(2, 2, 8, 2, 0, raw + std::string(5, '\0')),
                      "more than");  // long data
  std::string bad_filter = raw;
  bad_filter[7] = 9;
  expect_format_error(handmade(2, 2, 8, 2, 0, bad_filter), "row 1: unknown filter type 9");
  std::string no_end = good.substr(0, good.size() - 12);
  expect_format_error(no_end, "truncated");
  expect_format_error(std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IEND", ""), "expected IHDR");
}

TEST(ImageVideo, FrameSizeMustMatchTheVideo) {
  if (!ffmpeg_available()) GTEST_SKIP() << "ffmpeg binary not installed";
  const std::string path =
      (std::filesystem::temp_directory_path() / "emoface_image_test.mp4").string();
  VideoOptions o;
  o.width = 16;
  o.height = 8;
  VideoWriter writer(path, o);
  EXPECT_THROW(writer.add_frame(Image(8, 16)), InvalidInput);
  writer.add_frame(Image(16, 8, {200, 10, 10}));
  writer.finish();
  EXPECT_EQ(writer.frames(), 1u);
  EXPECT_TRUE(std::filesystem::exists(path));
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace emoface::core
