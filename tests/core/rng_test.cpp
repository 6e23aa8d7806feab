#include "emoface/core/rng.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace emoface::core {
namespace {

TEST(SplitMix64, MatchesReferenceSequence) {
  // Reference values of Vigna's splitmix64.c seeded with 1234567.
  std::uint64_t state = 1234567;
  EXPECT_EQ(splitmix64(state), 6457827717110365317ULL);
  EXPECT_EQ(splitmix64(state), 3203168211198807973ULL);
  EXPECT_EQ(splitmix64(state), 9817491932198370423ULL);
}

TEST(Rng, SameSeedSameSequenceDifferentStreamsDiffer) {
  Rng a(42, 7), b(42, 7), c(42, 8), d(43, 7);
  for (int i = 0; i < 100; ++i) {
    auto x = a.next_u64();
    EXPECT_EQ(x, b.next_u64());
    EXPECT_NE(x, c.next_u64());
    EXPECT_NE(x, d.next_u64());
  }
}

TEST(Rng, UniformMomentsAndRange) {
  Rng r(1);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12.0, 0.002);
}

TEST(Rng, UniformIntIsUnbiasedAndInRange) {
  Rng r(2);
  std::vector<int> counts(6, 0);
  for (int i = 0; i < 60000; ++i) {
    auto k = r.uniform_int(6);
    ASSERT_LT(k, 6u);
    ++counts[k];
  }
  for (int c : counts) EXPECT_NEAR(c, 10000, 400);
}

TEST(Rng, NormalAndExponentialMoments) {
  Rng r(3);
  const int n = 200000;
  double s = 0, s2 = 0, e = 0;
  for (int i = 0; i < n; ++i) {
    double z = r.normal();
    s += z;
    s2 += z * z;
    e += r.exponential(2.0);
  }
  EXPECT_NEAR(s / n, 0.0, 0.01);
  EXPECT_NEAR(s2 / n, 1.0, 0.015);
  EXPECT_NEAR(e / n, 0.5, 0.01);
}

}  // namespace
}  // namespace emoface::core
