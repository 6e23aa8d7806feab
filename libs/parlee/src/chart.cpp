#include "emoface/parlee/chart.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/core/png.hpp"

namespace emoface::parlee {
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
    {':', {0, 2, 0, 2, 0}}, {'\'', {2, 2, 0, 0, 0}}, {'!', {2, 2, 2, 0, 2}}, {',', {0, 0, 0, 2, 4}},
    {'/', {1, 1, 2, 4, 4}}, {'+', {0, 2, 7, 2, 0}}, {'(', {1, 2, 2, 2, 1}}, {')', {4, 2, 2, 2, 4}},
};

const Glyph* glyph(char ch) {
  const char lc = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (const auto& g : kFont)
    if (g.c == lc) return &g;
  return nullptr;
}

void put(RgbImage& im, int x, int y, std::array<std::uint8_t, 3> c) {
  if (x < 0 || y < 0 || x >= im.width || y >= im.height) return;
  const auto i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(im.width) + static_cast<std::size_t>(x)) * 3;
  im.rgb[i] = c[0];
  im.rgb[i + 1] = c[1];
  im.rgb[i + 2] = c[2];
}

void line(RgbImage& im, int x0, int y0, int x1, int y1, std::array<std::uint8_t, 3> c, int thick = 1) {
  const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
  const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    for (int a = 0; a < thick; ++a)
      for (int b = 0; b < thick; ++b) put(im, x0 + a, y0 + b, c);
    if (x0 == x1 && y0 == y1) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      x0 += sx;
    }
    if (e2 <= dx) {
      err += dx;
      y0 += sy;
    }
  }
}

}  // namespace

void ChartOptions::validate() const {
  if (width < 200 || width > 8192) throw InvalidInput("chart: width must be in [200, 8192] pixels");
  if (panel_height < 40 || panel_height > 2048) throw InvalidInput("chart: panel_height must be in [40, 2048] pixels");
  if (!(x_max >= 0) || !std::isfinite(x_max)) throw InvalidInput("chart: x_max must be finite and >= 0");
  for (const auto& m : markers)
    if (!std::isfinite(m.x)) throw InvalidInput("chart: marker positions must be finite");
}

int text_width(std::string_view text, int scale) noexcept { return static_cast<int>(text.size()) * 4 * scale; }

void draw_text(RgbImage& image, int x, int y, std::string_view text, std::array<std::uint8_t, 3> rgb, int scale) {
  scale = std::max(scale, 1);
  for (char ch : text) {
    if (const Glyph* g = glyph(ch)) {
      for (int r = 0; r < 5; ++r)
        for (int b = 0; b < 3; ++b)
          if (g->rows[r] & (4 >> b))
            for (int a = 0; a < scale; ++a)
              for (int d = 0; d < scale; ++d) put(image, x + b * scale + a, y + r * scale + d, rgb);
    }
    x += 4 * scale;
  }
}

RgbImage draw_chart(const std::vector<ChartPanel>& panels, const ChartOptions& options) {
  options.validate();
  if (panels.empty()) throw InvalidInput("chart: no panels");
  double x_max = options.x_max;
  if (x_max <= 0) {
    x_max = 10;
    for (const auto& p : panels)
      for (const auto& s : p.series)
        for (double x : s.x)
          if (std::isfinite(x)) x_max = std::max(x_max, x);
    x_max = std::ceil(x_max / 10) * 10;
  }
  const int left = 40, right = 16, top = 8, gap = 22;
  const int bottom = options.markers.empty() ? 28 : 44;
  const int n = static_cast<int>(panels.size());
  const int panel_height = options.panel_height;
  const int width = options.width;
  const int height = top + n * panel_height + (n - 1) * gap + bottom;
  RgbImage cv{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height * 3, 255)};
  const std::array<std::uint8_t, 3> grid{225, 225, 225}, frame{120, 120, 120}, ink{40, 40, 40};
  const int pw = width - left - right;
  auto X = [&](double x) { return left + static_cast<int>(std::lround(std::clamp(x / x_max, 0.0, 1.0) * pw)); };
  for (int p = 0; p < n; ++p) {
    const int y0 = top + p * (panel_height + gap);
    const ChartPanel& panel = panels[static_cast<std::size_t>(p)];
    if (!(panel.y_max > 0) || !std::isfinite(panel.y_max)) throw InvalidInput("chart: panel y_max must be > 0");
    auto Y = [&](double y) {
      const double t = std::isfinite(y) ? std::clamp(y / panel.y_max, 0.0, 1.0) : 0.0;
      return y0 + panel_height - static_cast<int>(std::lround(t * panel_height));
    };
    for (double gx = 0; gx <= x_max + 1e-9; gx += 10) line(cv, X(gx), y0, X(gx), y0 + panel_height, grid);
    line(cv, left, Y(panel.y_max / 2), left + pw, Y(panel.y_max / 2), grid);
    for (const auto& m : options.markers) line(cv, X(m.x), y0, X(m.x), y0 + panel_height, m.rgb);
    line(cv, left, y0, left + pw, y0, frame);
    line(cv, left, y0 + panel_height, left + pw, y0 + panel_height, frame);
    line(cv, left, y0, left, y0 + panel_height, frame);
    line(cv, left + pw, y0, left + pw, y0 + panel_height, frame);
    draw_text(cv, 4, y0, "1", ink);
    draw_text(cv, 4, y0 + panel_height - 10, "0", ink);
    for (const auto& s : panel.series)
      for (std::size_t i = 1; i < s.x.size() && i < s.y.size(); ++i)
        line(cv, X(s.x[i - 1]), Y(s.y[i - 1]), X(s.x[i]), Y(s.y[i]), s.rgb, 2);
    draw_text(cv, left + 6, y0 + 4, panel.title, ink);
  }
  for (double gx = 0; gx <= x_max + 1e-9; gx += 10) {
    const std::string label = std::to_string(static_cast<int>(gx));
    draw_text(cv, X(gx) - 4 * static_cast<int>(label.size()), height - bottom + 8, label, ink);
  }
  for (const auto& m : options.markers)
    draw_text(cv, X(m.x) - text_width(m.label) / 2, height - bottom + 26, m.label, m.rgb);
  return cv;
}

std::string encode_png(const RgbImage& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3)
    throw InvalidInput("encode_png: image size does not match its pixels");
  return core::encode_png(image.width, image.height, image.rgb);  // with the tEXt "Software" stamp
}

std::string render_chart(const std::vector<ChartPanel>& panels, const ChartOptions& options) {
  return encode_png(draw_chart(panels, options));
}

const std::vector<ChartEmotion>& chart_emotions() {
  static const std::vector<ChartEmotion> kEmotions = {{"fear", 3, {130, 40, 160}},
                                                      {"happiness", 1, {230, 140, 0}},
                                                      {"surprise", 5, {0, 140, 200}},
                                                      {"sadness", 0, {30, 60, 200}}};
  return kEmotions;
}

std::vector<ChartPanel> emotion_panels(const std::string& name, const std::vector<StepRecord>& run) {
  std::vector<ChartPanel> panels;
  for (const auto& c : chart_emotions()) {
    ChartSeries s;
    s.rgb = c.rgb;
    for (const auto& r : run) {
      s.x.push_back(r.time);
      s.y.push_back(r.basic[c.basic]);
    }
    panels.push_back({name + " " + c.name, {std::move(s)}, 1.0});
  }
  return panels;
}

}  // namespace emoface::parlee
