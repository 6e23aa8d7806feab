#include "emoface/core/png.hpp"

#include <zlib.h>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/version.hpp"

namespace emoface::core {

namespace {

void put32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((v >> shift) & 0xFFu));
}

// Length, type, data, CRC-32 over type + data (PNG spec §5.3).
void chunk(std::string& out, const char* type, const std::string& data) {
  put32(out, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out += body;
  put32(out, static_cast<std::uint32_t>(
                 crc32(0L, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
}

void check_keyword(const std::string& k) {
  const bool ok_len = !k.empty() && k.size() <= 79 && k.front() != ' ' && k.back() != ' ' &&
                      k.find("  ") == std::string::npos;
  bool ok_chars = true;
  for (unsigned char c : k) ok_chars = ok_chars && ((c >= 32 && c <= 126) || c >= 161);
  if (!ok_len || !ok_chars) throw InvalidInput("encode_png: invalid tEXt keyword '" + k + "'");
}

}  // namespace

std::string encode_png(int width, int height, const std::uint8_t* rgb, std::size_t size,
                       const std::vector<PngText>& extra) {
  if (width < 1 || height < 1 || width > (1 << 24) || height > (1 << 24))
    throw InvalidInput("encode_png: image size " + std::to_string(width) + "x" + std::to_string(height) + " out of range");
  const std::size_t stride = static_cast<std::size_t>(width) * 3;
  if (rgb == nullptr || size != stride * static_cast<std::size_t>(height))
    throw InvalidInput("encode_png: " + std::to_string(size) + " bytes for a " + std::to_string(width) + "x" +
                       std::to_string(height) + " RGB image (expected " + std::to_string(stride * height) + ")");
  std::vector<PngText> texts{{"Software", kGenerator}};
  texts.insert(texts.end(), extra.begin(), extra.end());
  for (const auto& t : texts) {
    check_keyword(t.keyword);
    if (t.text.find('\0') != std::string::npos) throw InvalidInput("encode_png: NUL in tEXt '" + t.keyword + "'");
  }

  // Filter type 1 (Sub) on every row: cheap and much smaller than None on smooth renders.
  std::string raw(static_cast<std::size_t>(height) * (stride + 1), '\0');
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = rgb + static_cast<std::size_t>(y) * stride;
    char* dst = raw.data() + static_cast<std::size_t>(y) * (stride + 1);
    dst[0] = 1;
    for (std::size_t i = 0; i < stride; ++i)
      dst[1 + i] = static_cast<char>(static_cast<std::uint8_t>(row[i] - (i >= 3 ? row[i - 3] : 0)));
  }
  uLongf zsize = compressBound(static_cast<uLong>(raw.size()));
  std::string z(zsize, '\0');
  if (compress2(reinterpret_cast<Bytef*>(z.data()), &zsize, reinterpret_cast<const Bytef*>(raw.data()),
                static_cast<uLong>(raw.size()), 6) != Z_OK)
    throw Error("encode_png: zlib compression failed");
  z.resize(zsize);

  std::string out("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  put32(ihdr, static_cast<std::uint32_t>(width));
  put32(ihdr, static_cast<std::uint32_t>(height));
  ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit, colour type 2 (RGB), deflate, filter 0, no interlace
  chunk(out, "IHDR", ihdr);
  for (const auto& t : texts) chunk(out, "tEXt", t.keyword + std::string(1, '\0') + t.text);
  chunk(out, "IDAT", z);
  chunk(out, "IEND", "");
  return out;
}

void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb,
               const std::vector<PngText>& extra) {
  write_file_atomic(path, encode_png(width, height, rgb, extra));
}

}  // namespace emoface::core
