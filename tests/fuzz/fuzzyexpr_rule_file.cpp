// libFuzzer target: the rule-file reader must turn any bytes into a RuleBase or a FormatError/IoError
// — never a crash, hang, leak or other exception. A parsed rule base must also compile and convert.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fx = emoface::fuzzyexpr;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const fx::RuleBase rules = fx::parse_rule_base(text, "fuzz.json");
    const fx::Engine engine(rules);
    const fx::Fmcv f = engine.convert(fx::Esv{0.1, 0.9, 0.3, 0.0, 0.55, 1.0});
    for (double v : f)
      if (!(v >= 0.0 && v <= 1.0)) __builtin_trap();
    (void)fx::to_fll(rules);
    // Writing and re-reading must give the same rule base.
    if (fx::to_json_text(fx::parse_rule_base(fx::to_json_text(rules), "again")) != fx::to_json_text(rules))
      __builtin_trap();
  } catch (const emoface::FormatError&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
