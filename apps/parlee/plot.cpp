#include "plot.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace emoface::parlee_app {
namespace {

// 3×5 pixel font: each glyph is 5 rows of 3 bits (MSB = left).
struct Glyph {
  char c;
  std::uint8_t rows[5];
};
constexpr Glyph kFont[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}}, {'3', {7, 1, 7, 1, 7}},
    {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}}, {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 1, 1}},
    {'8', {7, 5, 7, 5, 7}}, {'9', {7, 5, 7, 1, 7}}, {'a', {2, 5, 7, 5, 5}}, {'b', {6, 5, 6, 5, 6}},
    {'c', {7, 4, 4, 4, 7}}, {'d', {6, 5, 5, 5, 6}}, {'e', {7, 4, 6, 4, 7}}, {'f', {7, 4, 6, 4, 4}},
    {'g', {7, 4, 5, 5, 7}}, {'h', {5, 5, 7, 5, 5}}, {'i', {7, 2, 2, 2, 7}}, {'j', {1, 1, 1, 5, 7}},
    {'k', {5, 5, 6, 5, 5}}, {'l', {4, 4, 4, 4, 7}}, {'m', {5, 7, 7, 5, 5}}, {'n', {6, 5, 5, 5, 5}},
    {'o', {7, 5, 5, 5, 7}}, {'p', {7, 5, 7, 4, 4}}, {'q', {7, 5, 5, 7, 1}}, {'r', {7, 5, 6, 5, 5}},
    {'s', {7, 4, 7, 1, 7}}, {'t', {7, 2, 2, 2, 2}}, {'u', {5, 5, 5, 5, 7}}, {'v', {5, 5, 5, 5, 2}},
    {'w', {5, 5, 7, 7, 5}}, {'x', {5, 5, 2, 5, 5}}, {'y', {5, 5, 7, 2, 2}}, {'z', {7, 1, 2, 4, 7}},
    {'-', {0, 0, 7, 0, 0}}, {'_', {0, 0, 0, 0, 7}}, {'.', {0, 0, 0, 0, 2}}, {' ', {0, 0, 0, 0, 0}},
};

struct Canvas {
  int w, h;
  std::vector<std::uint8_t> px;
  Canvas(int width, int height) : w(width), h(height), px(static_cast<std::size_t>(width * height * 3), 255) {}
  void put(int x, int y, std::array<std::uint8_t, 3> c) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    const auto i = static_cast<std::size_t>((y * w + x) * 3);
    px[i] = c[0];
    px[i + 1] = c[1];
    px[i + 2] = c[2];
  }
  void line(int x0, int y0, int x1, int y1, std::array<std::uint8_t, 3> c, int thick = 1) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    int err = dx + dy;
    for (;;) {
      for (int a = 0; a < thick; ++a)
        for (int b = 0; b < thick; ++b) put(x0 + a, y0 + b, c);
      if (x0 == x1 && y0 == y1) break;
      const int e2 = 2 * err;
      if (e2 >= dy) { err += dy; x0 += sx; }
      if (e2 <= dx) { err += dx; y0 += sy; }
    }
  }
  void text(int x, int y, const std::string& s, std::array<std::uint8_t, 3> c, int scale = 2) {
    for (char ch : s) {
      const char lc = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      for (const auto& g : kFont) {
        if (g.c != lc) continue;
        for (int r = 0; r < 5; ++r)
          for (int b = 0; b < 3; ++b)
            if (g.rows[r] & (4 >> b))
              for (int a = 0; a < scale; ++a)
                for (int d = 0; d < scale; ++d) put(x + b * scale + a, y + r * scale + d, c);
      }
      x += 4 * scale;
    }
  }
};

void write_cb(png_structp png, png_bytep data, png_size_t len) {
  auto* out = static_cast<std::string*>(png_get_io_ptr(png));
  out->append(reinterpret_cast<const char*>(data), len);
}

}  // namespace

std::string render_chart(const std::vector<Panel>& panels, double x_max, int width, int panel_height) {
  const int left = 40, right = 16, top = 8, gap = 22, bottom = 28;
  const int n = static_cast<int>(panels.size());
  const int height = top + n * panel_height + (n - 1) * gap + bottom;
  Canvas cv(width, height);
  const std::array<std::uint8_t, 3> grid{225, 225, 225}, frame{120, 120, 120}, ink{40, 40, 40};
  const int pw = width - left - right;
  for (int p = 0; p < n; ++p) {
    const int y0 = top + p * (panel_height + gap);
    const Panel& panel = panels[static_cast<std::size_t>(p)];
    auto X = [&](double x) { return left + static_cast<int>(std::lround(x / x_max * pw)); };
    auto Y = [&](double y) {
      const double t = std::clamp(y / panel.y_max, 0.0, 1.0);
      return y0 + panel_height - static_cast<int>(std::lround(t * panel_height));
    };
    for (double gx = 0; gx <= x_max + 1e-9; gx += 10) cv.line(X(gx), y0, X(gx), y0 + panel_height, grid);
    cv.line(left, Y(panel.y_max / 2), left + pw, Y(panel.y_max / 2), grid);
    cv.line(left, y0, left + pw, y0, frame);
    cv.line(left, y0 + panel_height, left + pw, y0 + panel_height, frame);
    cv.line(left, y0, left, y0 + panel_height, frame);
    cv.line(left + pw, y0, left + pw, y0 + panel_height, frame);
    cv.text(4, y0, "1", ink);
    cv.text(4, y0 + panel_height - 10, "0", ink);
    for (const auto& s : panel.series)
      for (std::size_t i = 1; i < s.x.size() && i < s.y.size(); ++i)
        cv.line(X(s.x[i - 1]), Y(s.y[i - 1]), X(s.x[i]), Y(s.y[i]), s.rgb, 2);
    cv.text(left + 6, y0 + 4, panel.title, ink);
  }
  for (double gx = 0; gx <= x_max + 1e-9; gx += 10) {
    const std::string label = std::to_string(static_cast<int>(gx));
    cv.text(left + static_cast<int>(std::lround(gx / x_max * pw)) - 4 * static_cast<int>(label.size()),
            height - bottom + 8, label, ink);
  }
  std::string out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) throw std::runtime_error("libpng: cannot create a writer");
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng: encoding failed");
  }
  png_set_write_fn(png, &out, write_cb, nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) png_write_row(png, &cv.px[static_cast<std::size_t>(y * width * 3)]);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return out;
}

}  // namespace emoface::parlee_app
