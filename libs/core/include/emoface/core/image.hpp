#pragma once
// The one picture type of emoface (issue 18 item 3): 8-bit RGB pixels, row-major, top row first,
// with the drawing every library needs — fill, blend, lines with a thickness, filled rectangles and
// circles, text in core's bitmap font (font.hpp), blits and tiled contact sheets — and PNG
// encoding/decoding (png.hpp) and video frames (video.hpp) for it. Every drawing function clips
// to the image: pixels outside are ignored, never an error. Faces (facemesh::render), charts
// (parlee, mindmap), landmark sheets (motiongraph), crowd frames (mindmotion) and the apps' plots
// all draw into a core::Image.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/core/font.hpp"
#include "emoface/core/png.hpp"

namespace emoface::core {

/// Largest image side and pixel count an Image may have (64 Mpx, 192 MB of pixels).
inline constexpr int kMaxImageSide = 1 << 16;
inline constexpr long long kMaxImagePixels = 1LL << 26;

/// 0xRRGGBB → {RR, GG, BB}.
constexpr Rgb rgb_from_hex(std::uint32_t hex) noexcept {
  return {static_cast<std::uint8_t>(hex >> 16), static_cast<std::uint8_t>(hex >> 8),
          static_cast<std::uint8_t>(hex)};
}

/// 8-bit RGB image. The fields are public (renderers fill `rgb` directly); a consistent image has
/// rgb.size() == width·height·3, which validate() checks and every function taking an Image
/// relies on. The default image is empty (0 × 0).
struct Image {
  int width = 0;                  ///< pixels, 0 (empty) or [1, kMaxImageSide]
  int height = 0;                 ///< pixels, 0 (empty) or [1, kMaxImageSide]
  std::vector<std::uint8_t> rgb;  ///< width·height·3 bytes, row-major, row 0 at the top

  Image() = default;
  /// A width × height image filled with `background`. Throws InvalidInput unless both sides are in
  /// [1, kMaxImageSide] and width·height ≤ kMaxImagePixels.
  Image(int width, int height, Rgb background = {255, 255, 255});

  bool empty() const noexcept { return width == 0 || height == 0; }
  bool contains(int x, int y) const noexcept { return x >= 0 && y >= 0 && x < width && y < height; }
  /// Byte offset of pixel (x, y) in `rgb`; (x, y) must be inside.
  std::size_t offset(int x, int y) const noexcept {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
            static_cast<std::size_t>(x)) *
           3;
  }
  /// The pixel at (x, y). Throws InvalidInput outside the image.
  Rgb at(int x, int y) const;
  /// Sets pixel (x, y); outside the image nothing happens.
  void set(int x, int y, Rgb colour) noexcept {
    if (!contains(x, y)) return;
    std::uint8_t* p = &rgb[offset(x, y)];
    p[0] = colour[0];
    p[1] = colour[1];
    p[2] = colour[2];
  }
  /// Throws InvalidInput when the sizes are out of range or rgb.size() != width·height·3.
  void validate() const;
};

/// Every pixel set to `colour`.
void fill(Image& image, Rgb colour);
/// Mixes `colour` into pixel (x, y): p ← round(p + alpha·(colour − p)), `alpha` clamped to [0, 1]
/// (NaN counts as 0). Outside the image nothing happens.
void blend(Image& image, int x, int y, Rgb colour, double alpha);
/// The pixels x … x + width − 1, y … y + height − 1 set to `colour` (nothing for width or height ≤
/// 0).
void fill_rect(Image& image, int x, int y, int width, int height, Rgb colour);
/// A filled disc: the pixels (px, py) with (px − cx)² + (py − cy)² ≤ radius² (pixel coordinates
/// are the integer indices). Nothing for radius < 0 or non-finite arguments.
void fill_circle(Image& image, double cx, double cy, double radius, Rgb colour);

/// A straight line from (x0, y0) to (x1, y1), pixel coordinates. Sampled at n + 1 evenly spaced
/// points, n = ⌈max(|x1 − x0|, |y1 − y0|)⌉ + 1 (so consecutive samples are less than a pixel apart
/// and the line has no gaps), each rounded to the nearest pixel (halves away from zero) and stamped
/// with a `thickness` × `thickness` square covering offsets −⌊(t − 1)/2⌋ … ⌊t/2⌋ (t = 1: the
/// pixel; 2: it and its right, lower and lower-right neighbours; 3: centred). Throws InvalidInput
/// for thickness outside [1, 16]; lines with an end that is not finite or beyond ±10⁹, or longer
/// than 10⁵ pixels, draw nothing.
void draw_line(Image& image, double x0, double y0, double x1, double y1, Rgb colour,
               int thickness = 1);

/// core::draw_text into an Image: the 3×5 font scaled by `scale`, top-left corner at (x, y).
void draw_text(Image& image, int x, int y, std::string_view text, Rgb colour, int scale = 2);
/// core::draw_text_vertical into an Image (reads bottom to top, baseline running up from (x, y)).
void draw_text_vertical(Image& image, int x, int y, std::string_view text, Rgb colour,
                        int scale = 2);

/// Copies `source` with its top-left corner at (x, y) of `target`; the part outside is clipped.
void blit(Image& target, const Image& source, int x, int y);
/// Tiles equally sized images left to right, top to bottom in `columns` columns (fewer when there
/// are fewer images) with `gap` pixels of `background` around and between them: a contact sheet of
/// columns·w + (columns + 1)·gap by rows·h + (rows + 1)·gap pixels. Throws InvalidInput for no
/// images, images of different sizes, columns < 1 or gap outside [0, 1000].
Image tile(const std::vector<Image>& images, int columns, int gap = 4,
           Rgb background = {255, 255, 255});

/// PNG bytes of a non-empty image (encode_png of png.hpp: with the "Software" stamp and `extra`
/// text chunks). Throws InvalidInput for an empty or inconsistent image.
std::string encode_png(const Image& image, const std::vector<PngText>& extra = {});
/// encode_png + write_file_atomic (IoError if the file cannot be written).
void write_png(const std::string& path, const Image& image, const std::vector<PngText>& extra = {});
/// Decodes PNG bytes: 8-bit greyscale, RGB, grey + alpha or RGBA (alpha dropped), not interlaced,
/// any of the five row filters; every chunk's CRC is checked. Throws FormatError naming `name` for
/// a malformed, truncated or unsupported file (other bit depths, palettes, interlacing, sizes over
/// the Image limits).
Image decode_png(std::string_view bytes, const std::string& name = "<png>");
/// read_file + decode_png.
Image read_png(const std::string& path);

}  // namespace emoface::core
