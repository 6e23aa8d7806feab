// libFuzzer target for the user landmarks reader (emoface.landmarks, core::JsonReader): any input
// either parses into 68 points that write and read back unchanged, or throws FormatError — never
// crashes, hangs or throws anything else.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/retarget/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace rt = emoface::retarget;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const rt::UserLandmarks lm = rt::parse_landmarks(text, "fuzz.json");
    if (lm.points.size() != 68) std::abort();
    const std::string written = rt::format_landmarks(lm);
    if (rt::format_landmarks(rt::parse_landmarks(written, "again.json")) != written) std::abort();
  } catch (const emoface::FormatError&) {
  }
  return 0;
}
