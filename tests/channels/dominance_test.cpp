#include "emoface/channels/dominance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::channels {
namespace {

// Two visemes with one parameter, θ← = θ→ = 0.35, c = 1 (Fig. 4.4).
VisemeSet fig44_set() {
  VisemeSet set;
  const Dominance d{1.0, 0.35, 0.35, 1.0, 0.0};
  set.visemes = {{"sil", {}, d, {}}, {"low", {{"masseter", 0.1}}, d, {}}, {"high", {{"masseter", 0.9}}, d, {}}};
  return set;
}

TEST(Dominance, Figure44GradualTransition) {
  const VisemeSet set = fig44_set();
  const Coarticulation lip(set, {{"low", 0.0, 0.1, 0.0, "a"}, {"high", 0.1, 0.2, 0.0, "b"}});
  // centres 0.05 and 0.15 s; τ in centiseconds: at t = 0.05, Δ1 = 1, Δ2 = e^{−0.35·10};
  // the rest term adds 1e-4 (target 0) to the denominator
  const double d2 = std::exp(-3.5), rest = 1e-4;
  EXPECT_NEAR(lip.dominance(1, 0, 0.05), d2, 1e-12);
  EXPECT_NEAR(lip.value("masseter", 0.05), (0.1 + 0.9 * d2) / (1 + d2 + rest), 1e-12);
  const double dm = std::exp(-0.35 * 5);  // symmetric midpoint
  EXPECT_NEAR(lip.value("masseter", 0.10), 0.5 * 2 * dm / (2 * dm + rest), 1e-12);
  EXPECT_NEAR(lip.value("masseter", 0.10), 0.5, 1e-3);
  EXPECT_NEAR(lip.value("masseter", 0.15), (0.1 * d2 + 0.9) / (1 + d2 + rest), 1e-12);
  // gradual, monotone transition between the centres
  double prev = lip.value("masseter", 0.05);
  for (double t = 0.051; t <= 0.15; t += 0.001) {
    const double v = lip.value("masseter", t);
    EXPECT_GT(v, prev);
    EXPECT_LT(v - prev, 0.03);
    prev = v;
  }
}

TEST(Dominance, AnticipatoryAndCarryoverRates) {
  VisemeSet set = fig44_set();
  set.visemes[1].dominance = Dominance{2.0, 0.1, 0.5, 2.0, 0.01};
  const Coarticulation lip(set, {{"low", 0.0, 0.1, 0.0, "a"}});
  // τ = Tc + To − t = 0.06 − t; before the peak (τ >= 0) θ←, after it θ→; τ in units of 0.01 s
  EXPECT_NEAR(lip.dominance(0, 0, 0.02), 2.0 * std::exp(-0.1 * 16.0), 1e-12);
  EXPECT_NEAR(lip.dominance(0, 0, 0.09), 2.0 * std::exp(-0.5 * 9.0), 1e-12);
  EXPECT_NEAR(lip.dominance(0, 0, 0.06), 2.0, 1e-12);
}

TEST(Dominance, ApexKeepsFullDominance) {
  const VisemeSet set = fig44_set();
  const Coarticulation lip(set, {{"low", 0.0, 0.2, 0.1, "a"}});
  EXPECT_NEAR(lip.dominance(0, 0, 0.06), 1.0, 1e-12);
  EXPECT_NEAR(lip.dominance(0, 0, 0.14), 1.0, 1e-12);
  EXPECT_NEAR(lip.dominance(0, 0, 0.16), std::exp(-0.35), 1e-12);
}

TEST(Dominance, WeightedAverageStaysInTargetRangeAndFadesToZero) {
  const VisemeSet set = fig44_set();
  const Coarticulation lip(set, {{"sil", 0.0, 0.1, 0, "s"}, {"high", 0.1, 0.2, 0, "h"},
                                 {"low", 0.2, 0.3, 0, "l"}, {"sil", 0.3, 0.5, 0, "s"}});
  for (double t = 0; t < 2.0; t += 0.0005) {
    const double v = lip.value("masseter", t);
    EXPECT_GE(v, 0.0);
    EXPECT_LE(v, 0.9);
  }
  EXPECT_LT(lip.value("masseter", 0.45), 1e-3);
  EXPECT_EQ(lip.value("masseter", 5.0), 0.0);
}

TEST(Dominance, FadesToRestContinuouslyWhateverTheDecayRates) {
  // a slowly decaying viseme next to a fast silence must not take over far away (no jumps)
  VisemeSet set = fig44_set();
  set.visemes[0].dominance = Dominance{0.6, 0.5, 0.5, 1.0, 0.0};
  set.visemes[2].dominance = Dominance{0.9, 0.1, 0.1, 1.0, 0.0};
  const Coarticulation lip(set, {{"sil", 0.8, 1.0, 0, "s"}, {"high", 1.0, 1.3, 0, "h"}, {"sil", 1.3, 1.5, 0, "s"}});
  double prev = lip.value("masseter", 0.0);
  for (double t = 0.0005; t < 4.0; t += 0.0005) {
    const double v = lip.value("masseter", t);
    ASSERT_LT(std::abs(v - prev), 0.02) << t;
    prev = v;
  }
  EXPECT_GT(lip.value("masseter", 0.0), 0.01);  // a slow viseme reaches far (θ = 0.1)
  EXPECT_LT(lip.value("masseter", 3.5), 1e-3);
}

TEST(Dominance, PhonemeLookup) {
  VisemeSet set = fig44_set();
  set.phoneme_to_viseme = {{"a", "low"}, {"i", "high"}};
  EXPECT_EQ(set.viseme_for_phoneme("a"), "low");
  EXPECT_EQ(set.viseme_for_phoneme("i:"), "high");
  EXPECT_EQ(set.viseme_for_phoneme("zz"), "sil");
  EXPECT_NO_THROW(set.validate());
}

TEST(Dominance, Validation) {
  VisemeSet set = fig44_set();
  set.visemes[1].dominance.alpha = 0;
  EXPECT_THROW(set.validate(), InvalidInput);
  set = fig44_set();
  set.visemes[1].targets.push_back({"no_such", 0.1});
  EXPECT_THROW(set.validate(), InvalidInput);
  set = fig44_set();
  set.visemes[1].targets[0].value = 1.5;
  EXPECT_THROW(set.validate(), InvalidInput);
  set = fig44_set();
  set.phoneme_to_viseme["x"] = "nope";
  EXPECT_THROW(set.validate(), InvalidInput);
  set = fig44_set();
  set.silence = "none";
  EXPECT_THROW(set.validate(), InvalidInput);
  set = fig44_set();
  set.visemes.push_back(set.visemes[1]);
  EXPECT_THROW(set.validate(), InvalidInput);
  set = fig44_set();
  EXPECT_THROW(Coarticulation(set, {{"low", 0.0, 0.2, 0, "a"}, {"high", 0.1, 0.3, 0, "b"}}), InvalidInput);
  EXPECT_THROW(Coarticulation(set, {{"what", 0.0, 0.2, 0, "a"}}), InvalidInput);
  EXPECT_THROW(Coarticulation(set, {{"low", 0.2, 0.1, 0, "a"}}), InvalidInput);
  EXPECT_THROW(Coarticulation(set, {{"low", 0.0, 0.1, 0.2, "a"}}), InvalidInput);
  EXPECT_THROW(Coarticulation(set, {}, CoarticulationOptions{0.0, 1e-7}), InvalidInput);
}

}  // namespace
}  // namespace emoface::channels
