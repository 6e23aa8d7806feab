// libFuzzer target for the shared readers of core (issue 18): JsonReader (envelope, unknown-field
// rule, typed getters on every value), CsvTable and the locale-free number parser must turn any
// bytes into values or a FormatError — never a crash, hang, leak or other exception.
//   build-fuzz/tests/fuzz/fuzz_core_readers -max_total_time=60 tests/fuzz/corpus/core_readers
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "emoface/core/csv.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/json_reader.hpp"
#include "emoface/core/text.hpp"

namespace {

namespace core = emoface::core;

// Calls every getter on every value; each may throw FormatError only.
void walk(const core::JsonValue& v, int depth) {
  if (depth > 64) return;
  auto guarded = [](auto&& f) {
    try {
      f();
    } catch (const emoface::FormatError&) {
    }
  };
  guarded([&] { (void)v.string(); });
  guarded([&] { (void)v.number(); });
  guarded([&] { (void)v.number(-1.0, 1.0); });
  guarded([&] { (void)v.integer(-5, 5); });
  guarded([&] { (void)v.index(100); });
  guarded([&] { (void)v.boolean(); });
  guarded([&] { v.only_keys({"a", "b"}); });
  guarded([&] { (void)v.at("a"); });
  guarded([&] { (void)v[0]; });
  if (v.is_object())
    for (const auto& [key, child] : v.members()) {
      if (child.json() != v.json().at(nlohmann::ordered_json::json_pointer(
                              child.pointer().substr(v.pointer().size()))))
        __builtin_trap();  // the escaped pointer must name the child
      walk(child, depth + 1);
    }
  if (v.is_array())
    for (const core::JsonValue& child : v.items()) walk(child, depth + 1);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    core::JsonReader reader(text, "fuzz.json", "thing", {1, 1});
    walk(reader.root(), 0);
  } catch (const emoface::FormatError&) {
  }
  try {
    const core::CsvTable table = core::CsvTable::parse(text, "fuzz.csv");
    for (std::size_t r = 0; r < table.size(); ++r)
      for (std::size_t c = 0; c < table.header().size(); ++c) try {
          (void)table.number(r, c);
        } catch (const emoface::FormatError&) {
        }
  } catch (const emoface::FormatError&) {
  }
  for (const core::Line& line : core::Lines(text)) {
    if (auto v = core::parse_number(line.text)) {
      if (!std::isfinite(*v) || core::parse_number(core::format_number(*v)) != *v) __builtin_trap();
    }
    (void)core::parse_integer(line.text);
  }
  return 0;
}
