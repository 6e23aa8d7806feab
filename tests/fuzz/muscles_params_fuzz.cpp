// libFuzzer target for the parameter-frame readers (CSV, NDJSON, JSON): FormatError or a valid frame
// list, nothing else.
#include <cstddef>
#include <cstdint>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/muscles/io.hpp"
#include "emoface/muscles/parameters.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  namespace mu = emoface::muscles;
  const auto format = static_cast<mu::FrameFormat>(data[0] % 3);
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    for (const auto& f : mu::parse_parameter_frames(text, format, "fuzz")) mu::validate_parameter_vector(f.values);
  } catch (const emoface::FormatError&) {
  }
  return 0;
}
