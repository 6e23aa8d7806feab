#pragma once
// PNG encoding shared by every library and app that writes pictures (faces, charts, plots, landmark
// renders): 8-bit RGB, deflate (zlib), one `tEXt` chunk "Software" = "emoface x.y.z" so every picture
// carries the version that made it, plus any extra text chunks (PNG spec §11.3.4.3).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace emoface::core {

struct PngText {
  std::string keyword;  ///< 1–79 Latin-1 printable characters, no leading/trailing/double spaces
  std::string text;     ///< Latin-1, no NUL
};

/// `rgb` holds width * height * 3 bytes, row-major, top row first. Throws InvalidInput for bad sizes or
/// keywords. `extra` chunks follow the "Software" one.
std::string encode_png(int width, int height, const std::uint8_t* rgb, std::size_t size,
                       const std::vector<PngText>& extra = {});
inline std::string encode_png(int width, int height, const std::vector<std::uint8_t>& rgb,
                              const std::vector<PngText>& extra = {}) {
  return encode_png(width, height, rgb.data(), rgb.size(), extra);
}

/// encode_png + write_file_atomic.
void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb,
               const std::vector<PngText>& extra = {});

}  // namespace emoface::core
