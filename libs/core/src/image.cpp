#include "emoface/core/image.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::core {

namespace {

bool size_ok(long long width, long long height) {
  return width >= 1 && height >= 1 && width <= kMaxImageSide && height <= kMaxImageSide &&
         width * height <= kMaxImagePixels;
}

std::string size_text(long long width, long long height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

}  // namespace

Image::Image(int w, int h, Rgb background) : width(w), height(h) {
  if (!size_ok(w, h))
    throw InvalidInput("Image: size " + size_text(w, h) + " out of range (sides 1 … " +
                       std::to_string(kMaxImageSide) + ", at most 2^26 pixels)");
  rgb.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
  fill(*this, background);
}

Rgb Image::at(int x, int y) const {
  if (!contains(x, y))
    throw InvalidInput("Image::at: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                       ") outside the " + size_text(width, height) + " image");
  const std::uint8_t* p = &rgb[offset(x, y)];
  return {p[0], p[1], p[2]};
}

void Image::validate() const {
  const bool sides = (width == 0 && height == 0) || size_ok(width, height);
  if (!sides) throw InvalidInput("Image: size " + size_text(width, height) + " out of range");
  const std::size_t want = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3;
  if (rgb.size() != want)
    throw InvalidInput("Image: " + std::to_string(rgb.size()) + " bytes for a " +
                       size_text(width, height) + " RGB image (expected " + std::to_string(want) +
                       ")");
}

void fill(Image& image, Rgb colour) {
  image.validate();
  for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
    image.rgb[i] = colour[0];
    image.rgb[i + 1] = colour[1];
    image.rgb[i + 2] = colour[2];
  }
}

void blend(Image& image, int x, int y, Rgb colour, double alpha) {
  if (!image.contains(x, y)) return;
  const double a = alpha > 0.0 ? std::min(alpha, 1.0) : 0.0;  // NaN → 0
  std::uint8_t* p = &image.rgb[image.offset(x, y)];
  for (int k = 0; k < 3; ++k)
    p[k] =
        static_cast<std::uint8_t>(std::lround(p[k] + a * (static_cast<double>(colour[k]) - p[k])));
}

void fill_rect(Image& image, int x, int y, int width, int height, Rgb colour) {
  if (width <= 0 || height <= 0) return;
  const long long x1 = std::min<long long>(static_cast<long long>(x) + width, image.width);
  const long long y1 = std::min<long long>(static_cast<long long>(y) + height, image.height);
  for (long long py = std::max(y, 0); py < y1; ++py)
    for (long long px = std::max(x, 0); px < x1; ++px)
      image.set(static_cast<int>(px), static_cast<int>(py), colour);
}

void fill_circle(Image& image, double cx, double cy, double radius, Rgb colour) {
  if (!std::isfinite(cx) || !std::isfinite(cy) || !std::isfinite(radius) || radius < 0.0) return;
  // The bounding box [⌊c − r⌋, ⌈c + r⌉], clipped to the image (the same pixels, fewer tests).
  const double ylo = std::max(std::floor(cy - radius), 0.0),
               yhi = std::min(std::ceil(cy + radius), image.height - 1.0);
  const double xlo = std::max(std::floor(cx - radius), 0.0),
               xhi = std::min(std::ceil(cx + radius), image.width - 1.0);
  if (ylo > yhi || xlo > xhi) return;  // wholly outside (and no cast of a huge value below)
  for (int y = static_cast<int>(ylo); y <= yhi; ++y)
    for (int x = static_cast<int>(xlo); x <= xhi; ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius) image.set(x, y, colour);
}

void draw_line(Image& image, double x0, double y0, double x1, double y1, Rgb colour,
               int thickness) {
  if (thickness < 1 || thickness > 16)
    throw InvalidInput("draw_line: thickness must be in [1, 16] pixels");
  for (double v : {x0, y0, x1, y1})
    if (!(std::abs(v) <= 1e9)) return;  // non-finite or far away: nothing to round to a pixel
  const double length = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
  if (length > 1e5) return;
  const int steps = static_cast<int>(std::ceil(length)) + 1;
  const int lo = -((thickness - 1) / 2), hi = thickness / 2;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
    const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    for (int dy = lo; dy <= hi; ++dy)
      for (int dx = lo; dx <= hi; ++dx) image.set(x + dx, y + dy, colour);
  }
}

void draw_text(Image& image, int x, int y, std::string_view text, Rgb colour, int scale) {
  draw_text(image.rgb, image.width, image.height, x, y, text, colour, scale);
}

void draw_text_vertical(Image& image, int x, int y, std::string_view text, Rgb colour, int scale) {
  draw_text_vertical(image.rgb, image.width, image.height, x, y, text, colour, scale);
}

void blit(Image& target, const Image& source, int x, int y) {
  target.validate();
  source.validate();
  const int x0 = std::max(x, 0), x1 = static_cast<int>(std::min<long long>(
                                     static_cast<long long>(x) + source.width, target.width));
  if (x1 <= x0) return;
  const int y0 = std::max(y, 0), y1 = static_cast<int>(std::min<long long>(
                                     static_cast<long long>(y) + source.height, target.height));
  for (int ty = y0; ty < y1; ++ty)
    std::memcpy(&target.rgb[target.offset(x0, ty)], &source.rgb[source.offset(x0 - x, ty - y)],
                static_cast<std::size_t>(x1 - x0) * 3);
}

Image tile(const std::vector<Image>& images, int columns, int gap, Rgb background) {
  if (images.empty()) throw InvalidInput("tile: no images");
  if (columns < 1) throw InvalidInput("tile: columns must be >= 1");
  if (gap < 0 || gap > 1000) throw InvalidInput("tile: gap must be in [0, 1000] pixels");
  const int w = images[0].width, h = images[0].height;
  for (const Image& im : images) {
    im.validate();
    if (im.width != w || im.height != h || im.empty())
      throw InvalidInput("tile: images differ in size or are empty");
  }
  const int cols =
      std::min<int>(columns, static_cast<int>(std::min<std::size_t>(images.size(), kMaxImageSide)));
  const long long rows = (static_cast<long long>(images.size()) + cols - 1) / cols;
  const long long width = static_cast<long long>(cols) * w + (cols + 1LL) * gap;
  const long long height = rows * h + (rows + 1) * gap;
  if (!size_ok(width, height))
    throw InvalidInput("tile: the sheet of " + size_text(width, height) + " pixels is too large");
  Image sheet(static_cast<int>(width), static_cast<int>(height), background);
  for (std::size_t i = 0; i < images.size(); ++i)
    blit(sheet, images[i], gap + static_cast<int>(i % static_cast<std::size_t>(cols)) * (w + gap),
         gap + static_cast<int>(i / static_cast<std::size_t>(cols)) * (h + gap));
  return sheet;
}

std::string encode_png(const Image& image, const std::vector<PngText>& extra) {
  image.validate();
  if (image.empty()) throw InvalidInput("encode_png: empty image");
  return encode_png(image.width, image.height, image.rgb.data(), image.rgb.size(), extra);
}

void write_png(const std::string& path, const Image& image, const std::vector<PngText>& extra) {
  write_file_atomic(path, encode_png(image, extra));
}

// ---- PNG decoding (PNG spec, 2nd ed.: §5 datastream, §11.2.2 IHDR, §9 filtering) ----

namespace {

class PngReader {
 public:
  PngReader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw FormatError({name_, "", 0, 0}, message);
  }

  std::uint32_t u32(std::size_t at) const {
    return (std::uint32_t{static_cast<std::uint8_t>(bytes_[at])} << 24) |
           (std::uint32_t{static_cast<std::uint8_t>(bytes_[at + 1])} << 16) |
           (std::uint32_t{static_cast<std::uint8_t>(bytes_[at + 2])} << 8) |
           std::uint32_t{static_cast<std::uint8_t>(bytes_[at + 3])};
  }

  Image read() {
    static constexpr char kSignature[] = "\x89PNG\r\n\x1a\n";
    if (bytes_.size() < 8 || bytes_.substr(0, 8) != std::string_view(kSignature, 8))
      fail("not a PNG file (bad signature)");
    std::size_t at = 8;
    int width = 0, height = 0, channels = 0;
    std::string idat;
    bool header = false, end = false;
    while (!end) {
      if (bytes_.size() - at < 12)
        fail("truncated at byte " + std::to_string(at) + " (expected a chunk)");
      const std::uint32_t length = u32(at);
      const std::string type(bytes_.substr(at + 4, 4));
      if (length > 0x7fffffffu || bytes_.size() - at - 12 < length)
        fail("chunk " + type + " at byte " + std::to_string(at) + " is truncated");
      const std::string_view data = bytes_.substr(at + 8, length);
      const auto crc = static_cast<std::uint32_t>(
          crc32(0L, reinterpret_cast<const Bytef*>(bytes_.data() + at + 4),
                static_cast<uInt>(length + 4)));
      if (crc != u32(at + 8 + length))
        fail("chunk " + type + " at byte " + std::to_string(at) + ": CRC mismatch");
      if (!header && type != "IHDR") fail("the first chunk is " + type + ", expected IHDR");
      if (type == "IHDR") {
        if (header) fail("a second IHDR chunk");
        if (length != 13) fail("IHDR has " + std::to_string(length) + " bytes, expected 13");
        header = true;
        const std::uint32_t w = u32(at + 8), h = u32(at + 12);
        const int depth = static_cast<std::uint8_t>(data[8]),
                  colour = static_cast<std::uint8_t>(data[9]);
        if (!size_ok(w, h)) fail("image size " + size_text(w, h) + " out of range for an Image");
        if (depth != 8) fail("bit depth " + std::to_string(depth) + " is not supported (only 8)");
        channels = colour == 0 ? 1 : colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 0;
        if (channels == 0)
          fail("colour type " + std::to_string(colour) + " is not supported (0, 2, 4 or 6)");
        if (data[10] != 0 || data[11] != 0) fail("unknown compression or filter method");
        if (data[12] != 0) fail("interlaced PNGs are not supported");
        width = static_cast<int>(w);
        height = static_cast<int>(h);
      } else if (type == "IDAT") {
        idat.append(data);
      } else if (type == "IEND") {
        end = true;
      } else if (type == "PLTE") {
        fail("palette images are not supported");
      } else if (!(type[0] & 0x20)) {
        fail("unknown critical chunk " + type);
      }
      at += 12 + length;
    }
    if (idat.empty()) fail("no image data (IDAT)");
    return unfilter(inflate(idat, width, height, channels), width, height, channels);
  }

 private:
  std::string inflate(const std::string& z, int width, int height, int channels) const {
    const std::size_t want =
        static_cast<std::size_t>(height) * (static_cast<std::size_t>(width) * channels + 1);
    std::string raw(want + 1, '\0');  // one spare byte: more data than the image holds is an error
    z_stream s{};
    if (inflateInit(&s) != Z_OK) throw Error("decode_png: zlib initialisation failed");
    s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(z.data()));
    s.avail_in = static_cast<uInt>(z.size());
    s.next_out = reinterpret_cast<Bytef*>(raw.data());
    s.avail_out = static_cast<uInt>(raw.size());
    const int rc = ::inflate(&s, Z_FINISH);
    const std::size_t got = raw.size() - s.avail_out;
    const std::string why = s.msg ? s.msg : "error " + std::to_string(rc);
    inflateEnd(&s);
    if (got > want) fail("the image data holds more than " + std::to_string(want) + " bytes");
    if (rc != Z_STREAM_END && rc != Z_BUF_ERROR) fail("corrupt image data (zlib: " + why + ")");
    if (got != want)
      fail("the image data holds " + std::to_string(got) + " bytes, expected " +
           std::to_string(want));
    raw.resize(want);
    return raw;
  }

  Image unfilter(const std::string& raw, int width, int height, int channels) const {
    const std::size_t stride = static_cast<std::size_t>(width) * channels;
    std::vector<std::uint8_t> prev(stride, 0), row(stride);
    Image image(width, height);
    const auto bpp = static_cast<std::size_t>(channels);
    for (int y = 0; y < height; ++y) {
      const char* in = raw.data() + static_cast<std::size_t>(y) * (stride + 1);
      const int filter = static_cast<std::uint8_t>(in[0]);
      for (std::size_t i = 0; i < stride; ++i) {
        const int a = i >= bpp ? row[i - bpp] : 0, b = prev[i], c = i >= bpp ? prev[i - bpp] : 0;
        int predictor = 0;
        switch (filter) {
          case 0:
            break;
          case 1:
            predictor = a;
            break;
          case 2:
            predictor = b;
            break;
          case 3:
            predictor = (a + b) / 2;
            break;
          case 4: {  // Paeth (§9.4)
            const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b),
                      pc = std::abs(p - c);
            predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
            break;
          }
          default:
            fail("row " + std::to_string(y) + ": unknown filter type " + std::to_string(filter));
        }
        row[i] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(in[1 + i]) + predictor);
      }
      for (int x = 0; x < width; ++x) {
        const std::uint8_t* p = &row[static_cast<std::size_t>(x) * bpp];
        image.set(x, y, channels <= 2 ? Rgb{p[0], p[0], p[0]} : Rgb{p[0], p[1], p[2]});
      }
      std::swap(prev, row);
    }
    return image;
  }

  std::string_view bytes_;
  std::string name_;
};

}  // namespace

Image decode_png(std::string_view bytes, const std::string& name) {
  return PngReader(bytes, name).read();
}

Image read_png(const std::string& path) { return decode_png(read_file(path), path); }

}  // namespace emoface::core
