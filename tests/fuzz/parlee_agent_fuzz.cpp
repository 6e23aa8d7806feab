// libFuzzer target for the parlee agent file (JSON) and event stream (NDJSON) readers. Run:
//   build-fuzz/tests/fuzz/fuzz_parlee_agent -max_total_time=300 data/parlee/agents
#include <cstddef>
#include <cstdint>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/parlee/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)emoface::parlee::write_agent(emoface::parlee::parse_agent(text, "fuzz"));
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
  try {
    (void)emoface::parlee::write_events(emoface::parlee::parse_events(text, "fuzz"));
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
