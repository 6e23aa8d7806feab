// libFuzzer target for core's PNG reader (issue 18 item 3, image.hpp): decode_png must turn any
// bytes into an Image or a FormatError — never a crash, hang, leak or other exception. Random bytes
// rarely pass the chunk CRCs, so each input is also decoded with its CRCs repaired (reaching IHDR,
// the inflater and the row filters), and encoded as pixels, which must decode back to the same
// pixels.
//   build-fuzz/tests/fuzz/fuzz_core_png -max_total_time=60
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/core/image.hpp"

namespace {

namespace core = emoface::core;

void decode(std::string_view bytes) {
  try {
    const core::Image image = core::decode_png(bytes, "fuzz.png");
    image.validate();  // a decoded image is always consistent
  } catch (const emoface::FormatError&) {
  }
}

// The input with every chunk's CRC recomputed (chunks read as length, type, data, CRC after the
// 8-byte signature, which is forced).
std::string repaired(std::string_view in) {
  std::string s("\x89PNG\r\n\x1a\n", 8);
  s.append(in.substr(std::min<std::size_t>(in.size(), 8)));
  for (std::size_t at = 8; s.size() - at >= 12;) {
    std::uint32_t n = 0;
    for (int k = 0; k < 4; ++k)
      n = n << 8 | static_cast<std::uint8_t>(s[at + static_cast<std::size_t>(k)]);
    if (n > s.size() - at - 12) break;
    const auto crc = static_cast<std::uint32_t>(
        crc32(0, reinterpret_cast<const Bytef*>(s.data() + at + 4), static_cast<uInt>(n + 4)));
    for (int k = 0; k < 4; ++k)
      s[at + 8 + n + static_cast<std::size_t>(k)] = static_cast<char>(crc >> (24 - 8 * k));
    at += 12 + n;
  }
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  decode(bytes);
  decode(repaired(bytes));
  if (size >= 4) {  // width from the first byte, the rest as pixels: a round trip
    const int width = 1 + data[0] % 16;
    const int height = static_cast<int>((size - 1) / 3 / static_cast<std::size_t>(width));
    if (height >= 1) {
      core::Image image(width, height);
      image.rgb.assign(data + 1, data + 1 + image.rgb.size());
      if (core::decode_png(core::encode_png(image)).rgb != image.rgb) __builtin_trap();
    }
  }
  return 0;
}
