// libFuzzer target: the match-script and utterance-rule readers of obie must turn any bytes into a value
// or a FormatError/InvalidInput — never a crash, hang, leak or other exception. What parses must round-trip
// through the writer byte for byte.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/obie/match.hpp"
#include "emoface/obie/utterances.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace ob = emoface::obie;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const ob::MatchScript m = ob::parse_match(text, "fuzz.json");
    const std::string again = ob::write_match(m);
    if (ob::write_match(ob::parse_match(again, "again.json")) != again) __builtin_trap();
  } catch (const emoface::FormatError&) {
  } catch (const emoface::InvalidInput&) {
  }
  try {
    const ob::UtteranceSet u = ob::parse_utterances(text, "fuzz.json");
    const std::string again = ob::write_utterances(u);
    if (ob::write_utterances(ob::parse_utterances(again, "again.json")) != again) __builtin_trap();
  } catch (const emoface::FormatError&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
