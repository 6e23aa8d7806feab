#include "emoface/channels/channel.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::channels {
namespace {

Movement smile(double value, double ts, double te, double d_on, double d_off, const char* label = "m") {
  return Movement{{{"zygomatic_major_l", value}}, Timing{ts, te, d_on, d_off}, label};
}

// Largest jump between samples dt apart over [t0, t1], for every parameter.
double max_jump(const ConcatenatedChannel& ch, double t0, double t1, double dt) {
  double worst = 0.0;
  for (std::size_t p = 0; p < ch.parameters().size(); ++p) {
    double prev = ch.value(p, t0);
    for (double t = t0 + dt; t <= t1; t += dt) {
      const double v = ch.value(p, t);
      worst = std::max(worst, std::abs(v - prev));
      prev = v;
    }
  }
  return worst;
}

TEST(Channel, ChannelNamesRoundTrip) {
  for (std::size_t i = 0; i < kChannelCount; ++i) {
    const auto c = static_cast<Channel>(i);
    EXPECT_EQ(channel_from_string(to_string(c)), c);
  }
  EXPECT_THROW(channel_from_string("lips"), InvalidInput);
}

TEST(Channel, SingleMovementFollowsActivity) {
  const ConcatenatedChannel ch({smile(0.8, 1.0, 4.0, 1.0, 1.0)});
  for (double t : {0.5, 1.2, 2.0, 3.0, 3.5, 4.5})
    EXPECT_DOUBLE_EQ(ch.value("zygomatic_major_l", t), activity(0.8, Timing{1, 4, 1, 1}, t)) << t;
  EXPECT_EQ(ch.value("masseter", 2.0), 0.0);
}

TEST(Channel, Figure46FullThenHalfSmile) {
  // Fig. 4.6: smile 1.0 at 0–2 s then smile 0.5 at 1–3 s (onset/offset 0.5 s, our choice).
  const ConcatenatedChannel ch({smile(1.0, 0, 2, 0.5, 0.5), smile(0.5, 1, 3, 0.5, 0.5)});
  EXPECT_DOUBLE_EQ(ch.value(0, 0.9), 1.0);
  EXPECT_DOUBLE_EQ(ch.value(0, 1.0), 1.0);
  // case 2: F1(Ts2) − φ+(t − Ts2, Dr1) = 1 − (2^{0.1/0.5} − 1)
  EXPECT_NEAR(ch.value(0, 1.1), 2.0 - std::pow(2.0, 0.2), 1e-12);
  const double xi = 0.5 * std::log2(1.5);  // φ+(ξ, Dr1) = 1 − 0.5
  EXPECT_NEAR(ch.value(0, 1.0 + xi), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(ch.value(0, 1.0 + xi + 0.01), 0.5);
  EXPECT_DOUBLE_EQ(ch.value(0, 2.2), 0.5);
  // then the second movement's offset
  EXPECT_NEAR(ch.value(0, 2.7), 0.5 * (std::pow(2.0, 0.6) - 1.0), 1e-12);
  EXPECT_EQ(ch.value(0, 3.0), 0.0);
  EXPECT_LT(max_jump(ch, 0, 3.5, 1e-4), 5e-4);
}

TEST(Channel, IncreasingCase) {
  // case 1 (§4.5.2): F1(Ts2) + φ+(t − Ts2, Do2) until PV2.
  const ConcatenatedChannel ch({smile(0.3, 0, 3, 0.5, 0.5), smile(0.9, 2, 5, 0.8, 0.5)});
  EXPECT_DOUBLE_EQ(ch.value(0, 2.0), 0.3);
  EXPECT_NEAR(ch.value(0, 2.2), 0.3 + std::pow(2.0, 0.2 / 0.8) - 1.0, 1e-12);
  const double xi = 0.8 * std::log2(1.6);  // φ+(ξ, Do2) = 0.9 − 0.3
  EXPECT_NEAR(ch.value(0, 2.0 + xi), 0.9, 1e-12);
  EXPECT_DOUBLE_EQ(ch.value(0, 2.75), 0.9);
  EXPECT_DOUBLE_EQ(ch.value(0, 4.0), 0.9);
  EXPECT_LT(max_jump(ch, 0, 5.5, 1e-4), 5e-4);
}

TEST(Channel, DecreasingCaseLongerThanOnsetStaysContinuous) {
  // ξ (from Dr1 = 2) is longer than Do2 = 0.2: the fall continues onto F2.
  const ConcatenatedChannel ch({smile(1.0, 0, 4, 0.5, 2.0), smile(0.1, 3, 4.5, 0.2, 0.5)});
  EXPECT_NEAR(ch.value(0, 3.3), std::sqrt(2.0) - 1.0 - (std::pow(2.0, 0.15) - 1.0), 1e-12);
  EXPECT_LT(max_jump(ch, 0, 5, 1e-4), 5e-4);
  EXPECT_EQ(ch.value(0, 4.6), 0.0);
}

TEST(Channel, NonOverlappingMovementsAreIndependent) {
  const ConcatenatedChannel ch({smile(0.5, 0, 1, 0.3, 0.3), smile(0.7, 2, 3, 0.3, 0.3)});
  EXPECT_EQ(ch.value(0, 1.5), 0.0);
  EXPECT_DOUBLE_EQ(ch.value(0, 2.1), activity(0.7, Timing{2, 3, 0.3, 0.3}, 2.1));
}

TEST(Channel, ThreeMovementsAndMissingTargets) {
  // the second movement does not name the parameter: its target is 0 (decreasing case).
  std::vector<Movement> ms{smile(0.8, 0, 2, 0.4, 0.4, "a"),
                           Movement{{{"masseter", 0.5}}, Timing{1, 3, 0.4, 0.4}, "b"},
                           smile(0.6, 1.2, 4, 0.4, 0.4, "c")};
  const ConcatenatedChannel ch(ms);
  ASSERT_EQ(ch.parameters().size(), 2u);
  EXPECT_LT(ch.value("zygomatic_major_l", 1.15), 0.8);
  EXPECT_NEAR(ch.value("zygomatic_major_l", 2.5), 0.6, 1e-12);
  EXPECT_LT(max_jump(ch, 0, 4.5, 1e-4), 3e-4);
}

TEST(Channel, RandomSequencesAreContinuous) {
  // property: any valid chain of overlapping movements, with signed targets, is continuous.
  core::Rng rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Movement> ms;
    double ts = 0.0, te = 0.0;
    for (int k = 0; k < 5; ++k) {
      ts += rng.uniform(0.2, 1.0);
      te = std::max(te + 0.05, ts + rng.uniform(0.6, 2.0));
      const double d = te - ts;
      ms.push_back(Movement{{{"head_yaw", rng.uniform(-0.5, 0.5)}, {"masseter", rng.uniform()}},
                            Timing{ts, te, d * rng.uniform(0.05, 0.5), d * rng.uniform(0.05, 0.45)},
                            "r" + std::to_string(k)});
    }
    const ConcatenatedChannel ch(ms);
    // the steepest slope is ln2·(1 + |v|)/min(D) where the exponential runs past φ+ = 1
    EXPECT_LT(max_jump(ch, 0, te + 0.5, 1e-4), 0.02) << trial;
  }
}

TEST(Channel, RejectsBadOrder) {
  EXPECT_THROW(ConcatenatedChannel({smile(1, 1, 3, 0.5, 0.5), smile(1, 1, 4, 0.5, 0.5)}), InvalidInput);
  EXPECT_THROW(ConcatenatedChannel({smile(1, 1, 3, 0.5, 0.5), smile(1, 0.5, 4, 0.5, 0.5)}), InvalidInput);
  EXPECT_THROW(ConcatenatedChannel({smile(1, 0, 3, 0.5, 0.5), smile(1, 1, 2, 0.5, 0.5)}), InvalidInput);
  EXPECT_THROW(ConcatenatedChannel({smile(1, 0, 1, 0.6, 0.5)}), InvalidInput);
  EXPECT_THROW(ConcatenatedChannel({smile(NAN, 0, 1, 0.3, 0.5)}), InvalidInput);
  Movement twice{{{"masseter", 0.1}, {"masseter", 0.2}}, Timing{0, 1, 0.2, 0.2}, "x"};
  EXPECT_THROW(ConcatenatedChannel({twice}), InvalidInput);
  const ConcatenatedChannel ok({smile(1, 0, 1, 0.2, 0.2)});
  EXPECT_THROW(ok.value(std::size_t{5}, 0.0), InvalidInput);
}

}  // namespace
}  // namespace emoface::channels
