// libFuzzer target: the per-file parsers of the CK+ reader (landmark files "x y" per line, emotion
// files with one code) must reject bad input with an emoface error, never crash or hang. The
// directory walk is fuzzed by fuzz_motiongraph_ckplus. Seeds: tests/fuzz/corpus/motiongraph_ckplus.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/io.hpp"

namespace mg = emoface::motiongraph;

template <class F>
static void guarded(F&& f) {
  try {
    f();
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  guarded([&] { (void)mg::parse_ck_landmarks(text, "fuzz"); });
  guarded([&] { (void)mg::parse_ck_landmarks(text, "fuzz", 68); });
  guarded([&] { (void)mg::parse_ck_emotion(text, "fuzz"); });
  guarded([&] { (void)mg::parse_ck_numbers(text, "fuzz", 3); });
  return 0;
}
