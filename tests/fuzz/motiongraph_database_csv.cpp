// libFuzzer target: the motiongraph database csv reader must reject bad input with an emoface error,
// never crash or hang. Seeds: tests/data/motiongraph/.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)emoface::motiongraph::parse_database_csv(text, "fuzz");
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
