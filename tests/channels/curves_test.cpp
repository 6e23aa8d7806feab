#include "emoface/channels/curves.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::channels {
namespace {

TEST(Curves, PhiPlusClosedForm) {
  // φ+(x, D) = 2^{x/D} − 1 (thesis §4.4)
  EXPECT_DOUBLE_EQ(phi_plus(0.0, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(phi_plus(2.0, 2.0), 1.0);
  EXPECT_NEAR(phi_plus(1.0, 2.0), std::sqrt(2.0) - 1.0, 1e-15);
  EXPECT_NEAR(phi_plus(4.0, 2.0), 3.0, 1e-14);
}

TEST(Curves, PhiMinusClosedForm) {
  // φ−(x, D) = 2^{1 − x/D} − 1 (thesis §4.4)
  EXPECT_DOUBLE_EQ(phi_minus(0.0, 3.0), 1.0);
  EXPECT_NEAR(phi_minus(3.0, 3.0), 0.0, 1e-15);
  EXPECT_NEAR(phi_minus(1.5, 3.0), std::sqrt(2.0) - 1.0, 1e-15);
}

TEST(Curves, PhiPlusInverse) {
  for (double y : {0.0, 0.1, 0.5, 1.0, 2.5}) EXPECT_NEAR(phi_plus(phi_plus_inverse(y, 0.7), 0.7), y, 1e-13);
  EXPECT_NEAR(phi_plus_inverse(0.5, 1.0), std::log2(1.5), 1e-15);
}

TEST(Curves, Figure43Activity) {
  // Fig. 4.3: 7 s movement, 2 s onset, 3 s offset.
  const Timing m{0.0, 7.0, 2.0, 3.0};
  EXPECT_EQ(activity(1.0, m, 0.0), 0.0);
  EXPECT_NEAR(activity(1.0, m, 1.0), 0.41421356237309503, 1e-14);
  EXPECT_DOUBLE_EQ(activity(1.0, m, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(activity(1.0, m, 4.0), 1.0);
  EXPECT_NEAR(activity(1.0, m, 5.5), 0.41421356237309503, 1e-14);
  EXPECT_EQ(activity(1.0, m, 7.0), 0.0);
  EXPECT_EQ(activity(1.0, m, 9.0), 0.0);
  EXPECT_NEAR(activity(0.6, m, 1.0), 0.6 * 0.41421356237309503, 1e-14);
}

TEST(Curves, ActivityIsContinuousAndBounded) {
  const Timing m{0.5, 3.0, 0.7, 0.9};
  double prev = activity(0.8, m, 0.0);
  for (int i = 1; i <= 400000; ++i) {
    const double t = i * 1e-5;
    const double v = activity(0.8, m, t);
    EXPECT_LE(std::abs(v - prev), 0.8 * std::log(2.0) * 2.0 / 0.7 * 1e-5 + 1e-12) << t;
    EXPECT_GE(v, 0.0);
    EXPECT_LE(v, 0.8);
    prev = v;
  }
}

TEST(Curves, TimingValidation) {
  EXPECT_NO_THROW((Timing{0, 1, 0.5, 0.5}.validate()));
  EXPECT_THROW((Timing{-1, 1, 0.1, 0.1}.validate()), InvalidInput);
  EXPECT_THROW((Timing{1, 1, 0.1, 0.1}.validate()), InvalidInput);
  EXPECT_THROW((Timing{2, 1, 0.1, 0.1}.validate()), InvalidInput);
  EXPECT_THROW((Timing{0, 1, 0.0, 0.1}.validate()), InvalidInput);
  EXPECT_THROW((Timing{0, 1, 0.1, -0.1}.validate()), InvalidInput);
  EXPECT_THROW((Timing{0, 1, 0.6, 0.5}.validate()), InvalidInput);
  EXPECT_THROW((Timing{0, NAN, 0.1, 0.1}.validate()), InvalidInput);
  EXPECT_THROW((Timing{0, INFINITY, 0.1, 0.1}.validate()), InvalidInput);
}

}  // namespace
}  // namespace emoface::channels
