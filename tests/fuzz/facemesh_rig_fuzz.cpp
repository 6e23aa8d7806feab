// libFuzzer target for the emoface.rig reader: any input either parses into a rig that passes
// validate_rig and round-trips, or throws FormatError — never crashes, hangs or throws anything else.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/facemesh/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto rig = emoface::facemesh::parse_rig(text, "fuzz.rig");
    const auto again = emoface::facemesh::parse_rig(emoface::facemesh::format_rig(rig), "again.rig");
    if (emoface::facemesh::format_rig(again) != emoface::facemesh::format_rig(rig)) std::abort();
  } catch (const emoface::FormatError&) {
  }
  return 0;
}
