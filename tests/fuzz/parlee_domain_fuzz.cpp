// libFuzzer target for the parlee domain reader (thesis operator format + PPDDL subset) and the
// grounder. Run:
//   build-fuzz/tests/fuzz/fuzz_parlee_domain -max_total_time=300 -max_len=8192 data/parlee
#include <cstddef>
#include <cstdint>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/parlee/domain.hpp"
#include "emoface/parlee/planner.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    emoface::parlee::DomainSpec spec;
    emoface::parlee::parse_domain_text(text, "fuzz", spec);
    emoface::parlee::CompileOptions o;
    o.max_ground_actions = 2000;
    o.max_facts = 2000;
    const emoface::parlee::Domain d(spec, o);
    if (!d.goals().empty()) {
      emoface::parlee::PlanOptions po;
      po.horizon = 2;
      emoface::parlee::Planner planner(d, po);
      planner.goal_probability(0, d.initial_state());
    }
    (void)emoface::parlee::write_domain_text(spec);
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
