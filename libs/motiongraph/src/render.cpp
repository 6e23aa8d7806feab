#include "emoface/motiongraph/render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <zlib.h>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {

namespace {
const std::uint32_t kPalette[] = {0x1f77b4, 0xd62728, 0x2ca02c, 0x9467bd, 0xff7f0e,
                                  0x8c564b, 0xe377c2, 0x17becf, 0x7f7f7f, 0xbcbd22};
std::uint32_t palette(int i) { return kPalette[static_cast<std::size_t>(std::abs(i)) % 10]; }

void disc(Image& img, double cx, double cy, double r, std::uint32_t colour) {
  for (int y = static_cast<int>(std::floor(cy - r)); y <= static_cast<int>(std::ceil(cy + r)); ++y)
    for (int x = static_cast<int>(std::floor(cx - r)); x <= static_cast<int>(std::ceil(cx + r)); ++x)
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) img.set(x, y, colour);
}

void line(Image& img, double x0, double y0, double x1, double y1, std::uint32_t colour) {
  const int steps = static_cast<int>(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
  if (steps > 100000) return;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::lround(x0 + t * (x1 - x0)));
    const int y = static_cast<int>(std::lround(y0 + t * (y1 - y0)));
    img.set(x, y, colour);
    img.set(x + 1, y, colour);
    img.set(x, y + 1, colour);
  }
}
}  // namespace

Image::Image(int w, int h, std::uint8_t grey) : width(w), height(h) {
  if (w < 1 || h < 1 || static_cast<long long>(w) * h > (1LL << 28)) throw InvalidInput("image: bad size");
  rgb.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, grey);
}

void Image::set(int x, int y, std::uint32_t c) {
  if (x < 0 || y < 0 || x >= width || y >= height) return;
  const std::size_t o = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  rgb[o] = static_cast<std::uint8_t>(c >> 16);
  rgb[o + 1] = static_cast<std::uint8_t>(c >> 8);
  rgb[o + 2] = static_cast<std::uint8_t>(c);
}

void RenderOptions::validate() const {
  if (width < 16 || height < 16 || width > 8192 || height > 8192) throw InvalidInput("render: size must be in [16, 8192]");
  if (!(scale > 0.0) || !std::isfinite(scale)) throw InvalidInput("render: scale must be > 0");
  if (!(dot_radius > 0.0) || !std::isfinite(dot_radius)) throw InvalidInput("render: dot_radius must be > 0");
}

void draw_pose(Image& image, const Pose& pose, const std::vector<int>& groups, const RenderOptions& options,
               int offset_x, int offset_y, double extra_scale) {
  options.validate();
  if (pose.cols() < 2) throw InvalidInput("render: poses need at least 2 columns");
  const double s = options.scale * extra_scale;
  for (Eigen::Index i = 0; i < pose.rows(); ++i) {
    const int g = static_cast<std::size_t>(i) < groups.size() ? groups[static_cast<std::size_t>(i)] : 0;
    if (!std::isfinite(pose(i, 0)) || !std::isfinite(pose(i, 1))) continue;
    disc(image, offset_x + pose(i, 0) * s, offset_y + pose(i, 1) * s,
         std::max(1.0, options.dot_radius * extra_scale), palette(g));
  }
}

Image contact_sheet(const std::vector<Pose>& frames, const std::vector<int>& groups, int columns,
                    double cell_scale, const RenderOptions& options) {
  options.validate();
  if (frames.empty() || columns < 1 || !(cell_scale > 0.0)) throw InvalidInput("contact sheet: bad arguments");
  const int cw = std::max(8, static_cast<int>(options.width * cell_scale));
  const int ch = std::max(8, static_cast<int>(options.height * cell_scale));
  const int cols = std::min<int>(columns, static_cast<int>(frames.size()));
  const int rows = static_cast<int>((frames.size() + static_cast<std::size_t>(cols) - 1) / static_cast<std::size_t>(cols));
  Image img(cols * cw, rows * ch);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const int cx = static_cast<int>(f % static_cast<std::size_t>(cols)) * cw;
    const int cy = static_cast<int>(f / static_cast<std::size_t>(cols)) * ch;
    for (int x = cx; x < cx + cw; ++x) img.set(x, cy, 0xcccccc);
    for (int y = cy; y < cy + ch; ++y) img.set(cx, y, 0xcccccc);
    draw_pose(img, frames[f], groups, options, cx, cy, cell_scale);
  }
  return img;
}

Image plot_series(const std::vector<std::vector<double>>& series, int width, int height) {
  Image img(width, height);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  std::size_t n = 0;
  for (const auto& s : series) {
    n = std::max(n, s.size());
    for (double v : s)
      if (std::isfinite(v)) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  }
  const int m = 20;
  for (int x = m; x < width - m; ++x) img.set(x, height - m, 0x000000), img.set(x, m, 0x999999);
  for (int y = m; y <= height - m; ++y) img.set(m, y, 0x000000), img.set(width - m, y, 0x999999);
  if (n < 2 || !(hi > lo)) return img;
  const double pad = 0.05 * (hi - lo);
  lo -= pad;
  hi += pad;
  auto px = [&](std::size_t i) { return m + (width - 2.0 * m) * static_cast<double>(i) / static_cast<double>(n - 1); };
  auto py = [&](double v) { return height - m - (height - 2.0 * m) * (v - lo) / (hi - lo); };
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 5; ++k) img.set(static_cast<int>(px(i)), height - m + k, 0x000000);
  for (std::size_t k = 0; k < series.size(); ++k)
    for (std::size_t i = 1; i < series[k].size(); ++i)
      line(img, px(i - 1), py(series[k][i - 1]), px(i), py(series[k][i]), palette(static_cast<int>(k)));
  return img;
}

namespace {
void put32(std::string& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<char>((v >> s) & 0xff));
}
void chunk(std::string& out, const char* type, const std::string& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out += body;
  put32(out, static_cast<std::uint32_t>(crc32(0L, reinterpret_cast<const Bytef*>(body.data()),
                                              static_cast<uInt>(body.size()))));
}
}  // namespace

std::string encode_png(const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3)
    throw InvalidInput("encode_png: inconsistent image");
  std::string raw;
  raw.reserve(image.rgb.size() + static_cast<std::size_t>(image.height));
  const std::size_t stride = static_cast<std::size_t>(image.width) * 3;
  for (int y = 0; y < image.height; ++y) {
    raw.push_back('\0');  // filter: none
    raw.append(reinterpret_cast<const char*>(image.rgb.data()) + static_cast<std::size_t>(y) * stride, stride);
  }
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string z(size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(z.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
                static_cast<uLong>(raw.size()), 9) != Z_OK)
    throw Error("encode_png: zlib compression failed");
  z.resize(size);
  std::string out("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put32(ihdr, static_cast<std::uint32_t>(image.width));
  put32(ihdr, static_cast<std::uint32_t>(image.height));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB, deflate, no filter, no interlace
  chunk(out, "IHDR", ihdr);
  chunk(out, "IDAT", z);
  chunk(out, "IEND", "");
  return out;
}

}  // namespace emoface::motiongraph
