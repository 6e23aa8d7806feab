// The console summary of `mindmap simulate` (mindmotion/outputs.hpp), against hand-written text.
#include "emoface/mindmotion/outputs.hpp"

#include <gtest/gtest.h>

namespace emoface::mindmotion {
namespace {

TEST(SimulationSummary, LearntStimuliThenTheTotals) {
  mindmap::SimulationResult r;
  r.copied.push_back({1.5, "ana", "gift", "world", 2});
  r.copied.push_back({0.25, "ben", "wave", "ana", 1});
  r.actions.resize(3);
  r.duration = 12.5;
  EXPECT_EQ(simulation_summary(r, 2, 7, "sim"),
            "ana learnt \"gift\" from world at 1.5 s\n"
            "ben learnt \"wave\" from ana at 0.25 s\n"
            "3 action(s) by 2 character(s) over 12.5 s; wrote 7 file(s) to sim\n");
  EXPECT_EQ(simulation_summary({}, 0, 0, "x"),
            "0 action(s) by 0 character(s) over 0 s; wrote 0 file(s) to x\n");
}

}  // namespace
}  // namespace emoface::mindmotion
