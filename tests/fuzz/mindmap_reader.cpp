// libFuzzer target: the mind-map and events readers must turn any bytes into a value or a
// FormatError/InvalidInput — never a crash, hang, leak or other exception. A parsed map must
// round-trip and simulate.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/mindmap/io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace mm = emoface::mindmap;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const mm::MindMap m = mm::parse_mind_map(text, "fuzz.json");
    const std::string again = mm::to_json_text(m);
    if (mm::to_json_text(mm::parse_mind_map(again, "again")) != again) __builtin_trap();
    mm::SimulationOptions o;
    o.duration = 2.0;
    std::vector<mm::Event> events;
    for (const auto& a : m.actions)
      if (a.receivable) events.push_back({0.5, m.character, a.name, {}, {}, 0});
    const auto r = mm::simulate({m}, events, o);
    for (double v : r.mood[0])
      if (!(v >= 0.0 && v <= 1.0)) __builtin_trap();
  } catch (const emoface::FormatError&) {
  } catch (const emoface::InvalidInput&) {
  }
  try {
    (void)mm::parse_events(text, "fuzz.ndjson");
  } catch (const emoface::FormatError&) {
  }
  return 0;
}
