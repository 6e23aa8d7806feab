#include "emoface/mindmap/mood.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "emoface/core/rng.hpp"

namespace mm = emoface::mindmap;

TEST(Mood, Eq2StimulusMixesAffection) {
  const double emot[2] = {0.8, 0.2}, affect[2] = {0.4, 1.0};
  double out[2];
  mm::perceived_stimulus(emot, affect, 0.25, out, 2);  // 0.75·0.8 + 0.25·0.4, 0.75·0.2 + 0.25·1
  EXPECT_NEAR(out[0], 0.7, 1e-15);
  EXPECT_NEAR(out[1], 0.4, 1e-15);
  mm::perceived_stimulus(emot, nullptr, 0.25, out, 2);
  EXPECT_EQ(out[0], 0.8);
  EXPECT_EQ(out[1], 0.2);
  double in_place[2] = {0.8, 0.2};
  mm::perceived_stimulus(in_place, affect, 1.0, in_place, 2);
  EXPECT_EQ(in_place[0], 0.4);
  EXPECT_EQ(in_place[1], 1.0);
}

TEST(Mood, Eq3AveragesPersonalityAndBackground) {
  const double pers[2] = {0.2, 0.6}, bg[2] = {0.4, 0.0};
  double out[2];
  mm::personality_traits(pers, bg, out, 2);
  EXPECT_NEAR(out[0], 0.3, 1e-15);
  EXPECT_NEAR(out[1], 0.3, 1e-15);
  mm::personality_traits(pers, nullptr, out, 2);
  EXPECT_EQ(out[0], 0.2);
  EXPECT_EQ(out[1], 0.6);
}

TEST(Mood, Eq4SumAndPrintedForms) {
  // drive = β(αS + (1−α)P) = 0.4·(0.6·0.7 + 0.4·0.3) = 0.216; (1−β)·mood = 0.6·0.5 = 0.3
  EXPECT_NEAR(mm::updated_mood(0.5, 0.7, 0.3, 0.6, 0.4, mm::MoodForm::Sum), 0.516, 1e-15);
  EXPECT_NEAR(mm::updated_mood(0.5, 0.7, 0.3, 0.6, 0.4, mm::MoodForm::Printed), 0.084, 1e-15);
  // drive = 0.5·(0.45 + 0.25) = 0.35; (1−β)·mood = 0.05: sum 0.4, printed |0.05 − 0.35| = 0.3
  EXPECT_NEAR(mm::updated_mood(0.1, 0.9, 0.5, 0.5, 0.5, mm::MoodForm::Sum), 0.4, 1e-15);
  EXPECT_NEAR(mm::updated_mood(0.1, 0.9, 0.5, 0.5, 0.5, mm::MoodForm::Printed), 0.3, 1e-15);
  // β = 0: the stimulus does not change the mood; β = 1, α = 1: the mood becomes the stimulus.
  EXPECT_EQ(mm::updated_mood(0.37, 0.9, 0.1, 0.5, 0.0, mm::MoodForm::Sum), 0.37);
  EXPECT_EQ(mm::updated_mood(0.37, 0.9, 0.1, 1.0, 1.0, mm::MoodForm::Sum), 0.9);
  // Clamped to [0, 1] even for inputs outside it.
  EXPECT_EQ(mm::updated_mood(3.0, 3.0, 3.0, 0.5, 0.5, mm::MoodForm::Sum), 1.0);
  EXPECT_EQ(mm::updated_mood(-3.0, -3.0, 0.0, 0.5, 0.5, mm::MoodForm::Sum), 0.0);
}

TEST(Mood, UpdateMoodArrayMatchesScalar) {
  double mood[3] = {0.5, 0.1, 0.9};
  const double s[3] = {0.7, 0.9, 0.0}, p[3] = {0.3, 0.5, 0.2};
  mm::update_mood(mood, s, p, 0.6, 0.4, mm::MoodForm::Sum, 3);
  EXPECT_NEAR(mood[0], 0.516, 1e-15);
  EXPECT_EQ(mood[1], mm::updated_mood(0.1, 0.9, 0.5, 0.6, 0.4, mm::MoodForm::Sum));
  EXPECT_EQ(mood[2], mm::updated_mood(0.9, 0.0, 0.2, 0.6, 0.4, mm::MoodForm::Sum));
}

TEST(Mood, PropertyOutputsStayInUnitInterval) {
  emoface::core::Rng rng(7);
  for (int i = 0; i < 20000; ++i) {
    const double m = rng.uniform(), s = rng.uniform(), p = rng.uniform(), a = rng.uniform(), b = rng.uniform();
    for (auto form : {mm::MoodForm::Sum, mm::MoodForm::Printed}) {
      const double v = mm::updated_mood(m, s, p, a, b, form);
      ASSERT_GE(v, 0.0);
      ASSERT_LE(v, 1.0);
    }
    // The sum form is a convex combination: it lies between min and max of its inputs.
    const double v = mm::updated_mood(m, s, p, a, b, mm::MoodForm::Sum);
    ASSERT_GE(v, std::min({m, s, p}) - 1e-12);
    ASSERT_LE(v, std::max({m, s, p}) + 1e-12);
  }
}

TEST(Mood, DecayCurvesByHand) {
  using mm::DecayCurve;
  EXPECT_EQ(mm::decay_fraction(DecayCurve::Linear, 0.25), 0.25);
  EXPECT_EQ(mm::decay_fraction(DecayCurve::Quadratic, 0.5), 0.25);
  // Rescaled logistic, k = 10 (values from python3: (σ(k(s−½)) − σ(−k/2)) / (σ(k/2) − σ(−k/2)))
  EXPECT_NEAR(mm::decay_fraction(DecayCurve::Sigmoid, 0.25), 0.07010371654510815, 1e-14);
  EXPECT_NEAR(mm::decay_fraction(DecayCurve::Sigmoid, 0.1), 0.011446579538697649, 1e-14);
  EXPECT_NEAR(mm::decay_fraction(DecayCurve::Sigmoid, 0.75), 0.929896283454892, 1e-14);
  EXPECT_NEAR(mm::decay_fraction(DecayCurve::Sigmoid, 0.5), 0.5, 1e-15);
  for (auto c : {DecayCurve::Linear, DecayCurve::Quadratic, DecayCurve::Sigmoid}) {
    EXPECT_EQ(mm::decay_fraction(c, 0.0), 0.0);
    EXPECT_EQ(mm::decay_fraction(c, 1.0), 1.0);
    EXPECT_EQ(mm::decay_fraction(c, -2.0), 0.0);
    EXPECT_EQ(mm::decay_fraction(c, 7.0), 1.0);
    EXPECT_EQ(mm::decay_fraction(c, std::nan("")), 0.0);
    double prev = 0.0;
    for (int i = 1; i <= 1000; ++i) {  // monotone and bounded
      const double f = mm::decay_fraction(c, i / 1000.0, 6.0);
      ASSERT_GE(f, prev);
      ASSERT_LE(f, 1.0);
      prev = f;
    }
  }
}

TEST(Mood, DecayedMoodInterpolatesTowardsPersonality) {
  const double start[2] = {1.0, 0.0}, target[2] = {0.2, 0.6};
  double out[2];
  mm::decayed_mood(start, target, 2.0, 4.0, mm::DecayCurve::Linear, 10.0, out, 2);
  EXPECT_NEAR(out[0], 0.6, 1e-15);
  EXPECT_NEAR(out[1], 0.3, 1e-15);
  mm::decayed_mood(start, target, 2.0, 4.0, mm::DecayCurve::Quadratic, 10.0, out, 2);
  EXPECT_NEAR(out[0], 0.8, 1e-15);  // 1 + (0.2 − 1)·0.25
  mm::decayed_mood(start, target, 9.0, 4.0, mm::DecayCurve::Sigmoid, 10.0, out, 2);
  EXPECT_EQ(out[0], 0.2);
  EXPECT_EQ(out[1], 0.6);
}

TEST(Mood, EnumStringRoundTrips) {
  for (auto f : {mm::MoodForm::Sum, mm::MoodForm::Printed})
    EXPECT_EQ(mm::mood_form_from_string(mm::to_string(f)), f);
  EXPECT_FALSE(mm::mood_form_from_string("abs"));
  for (auto c : {mm::DecayCurve::Linear, mm::DecayCurve::Quadratic, mm::DecayCurve::Sigmoid})
    EXPECT_EQ(mm::decay_curve_from_string(mm::to_string(c)), c);
  EXPECT_FALSE(mm::decay_curve_from_string("Linear"));
}
