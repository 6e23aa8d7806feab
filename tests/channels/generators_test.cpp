#include "emoface/channels/generators.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::channels {
namespace {

TEST(Blinks, SeededAndWellFormed) {
  core::Rng a(7), b(7), c(8);
  const auto x = generate_blinks(0, 600, BlinkOptions{}, a);
  const auto y = generate_blinks(0, 600, BlinkOptions{}, b);
  const auto z = generate_blinks(0, 600, BlinkOptions{}, c);
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_EQ(x[i].timing.start, y[i].timing.start);
  EXPECT_NE(x.size() == z.size() ? x[0].timing.start : -1.0, z[0].timing.start);
  EXPECT_NO_THROW(ConcatenatedChannel{x});
  for (std::size_t i = 1; i < x.size(); ++i) EXPECT_GE(x[i].timing.start - x[i - 1].timing.start, 1.0);
}

TEST(Blinks, IntervalDistributionMean) {
  core::Rng rng(3);
  BlinkOptions o;
  const auto x = generate_blinks(0, 20000, o, rng);
  // shifted exponential: mean 4 s, sd 3 s; ~5000 intervals → standard error ≈ 0.04 s
  const double mean = (x.back().timing.start - x.front().timing.start) / static_cast<double>(x.size() - 1);
  EXPECT_NEAR(mean, o.mean_interval, 0.2);
}

TEST(Blinks, Validation) {
  core::Rng rng(1);
  BlinkOptions o;
  o.min_interval = 0.1;  // shorter than a blink
  EXPECT_THROW(generate_blinks(0, 10, o, rng), InvalidInput);
  o = BlinkOptions{};
  o.mean_interval = 0.5;
  EXPECT_THROW(generate_blinks(0, 10, o, rng), InvalidInput);
  EXPECT_THROW(generate_blinks(5, 1, BlinkOptions{}, rng), InvalidInput);
}

TEST(Noise, ChannelOrderAmplitudeAndContinuity) {
  core::Rng rng(11);
  const NoiseOptions o = default_gaze_noise();
  const auto ms = generate_noise(0, 300, {"eye_gaze_yaw", "eye_gaze_pitch"}, o, rng);
  ASSERT_GT(ms.size(), 100u);
  const ConcatenatedChannel ch(ms);  // throws if the order is broken
  double sum2 = 0;
  for (const auto& m : ms) sum2 += m.targets[0].value * m.targets[0].value;
  EXPECT_NEAR(std::sqrt(sum2 / ms.size()), o.amplitude, 0.2 * o.amplitude);
  double prev = ch.value(std::size_t{0}, 0.0);
  for (double t = 0.001; t < 300; t += 0.001) {
    const double v = ch.value(std::size_t{0}, t);
    ASSERT_LT(std::abs(v - prev), 0.02) << t;
    prev = v;
  }
}

TEST(Noise, MergeKeepsExplicitMovements) {
  core::Rng rng(5);
  const auto noise = generate_noise(0, 20, {"head_yaw"}, default_head_noise(), rng);
  std::vector<Movement> expl{{{{"head_yaw", 0.4}}, Timing{5, 8, 0.5, 0.5}, "explicit"}};
  const auto merged = merge_generated(expl, noise, 0.1);
  EXPECT_NO_THROW(ConcatenatedChannel{merged});
  int n_explicit = 0;
  for (const auto& m : merged) {
    if (m.label == "explicit") ++n_explicit;
    else EXPECT_TRUE(m.timing.end + 0.1 <= 5 || m.timing.start >= 8.1);
  }
  EXPECT_EQ(n_explicit, 1);
  EXPECT_GT(merged.size(), 3u);
}

}  // namespace
}  // namespace emoface::channels
