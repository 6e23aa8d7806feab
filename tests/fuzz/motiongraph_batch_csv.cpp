// libFuzzer target: the motiongraph batch readers (synthesis requests, evaluation table; issue 18
// item 4) must reject bad input with an emoface error, never crash or hang; what they accept must
// write back and read again to the same bytes. Seeds: tests/fuzz/corpus/motiongraph_batch.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/batch.hpp"

namespace mg = emoface::motiongraph;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    std::vector<mg::SynthesisRequest> good;
    for (const auto& r : mg::parse_requests_csv(text, "fuzz"))
      if (!r.error) good.push_back(r.request);
    const std::string once = mg::requests_to_csv(good);
    std::vector<mg::SynthesisRequest> again;
    for (const auto& r : mg::parse_requests_csv(once, "fuzz")) {
      if (r.error) std::abort();  // what the writer wrote must read back
      again.push_back(r.request);
    }
    if (mg::requests_to_csv(again) != once) std::abort();
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
  try {
    const auto rows = mg::parse_evaluation_csv(text, "fuzz");
    const std::string once = mg::evaluation_csv(rows);
    if (mg::evaluation_csv(mg::parse_evaluation_csv(once, "fuzz")) != once) std::abort();
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
