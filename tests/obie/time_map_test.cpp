#include "emoface/obie/time_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::obie {
namespace {

TEST(TimeMap, HandComputedKnots) {
  // events at 1, 2, 40, 40.5, 41 with 1 s/min, gap 1 s, lead-in 1 s, tail 3.5 s:
  // knots (0,1) (1,2) (2,3) (40,41) (40.5,42: stretched from 41.5) (41,43: stretched from 42.5)
  const TimeMap map({1, 2, 40, 40.5, 40.5, 41}, 90, TimeMapOptions{});
  EXPECT_EQ(map.knot_minutes(), (std::vector<double>{0, 1, 2, 40, 40.5, 41}));
  EXPECT_EQ(map.knot_seconds(), (std::vector<double>{1, 2, 3, 41, 42, 43}));
  EXPECT_DOUBLE_EQ(map.seconds(0), 1);
  EXPECT_DOUBLE_EQ(map.seconds(-5), 1);
  EXPECT_DOUBLE_EQ(map.seconds(20), 21);
  EXPECT_DOUBLE_EQ(map.seconds(40.25), 41.5);
  EXPECT_DOUBLE_EQ(map.seconds(40.75), 42.5);
  EXPECT_DOUBLE_EQ(map.seconds(90), 92);  // 43 + 49 beyond the last knot
  EXPECT_DOUBLE_EQ(map.duration(), 95.5);
  EXPECT_DOUBLE_EQ(map.minute(41.5), 40.25);
  EXPECT_DOUBLE_EQ(map.minute(92), 90);
  EXPECT_DOUBLE_EQ(map.minute(0.5), 0);
}

TEST(TimeMap, CompressionWithoutGap) {
  TimeMapOptions o;
  o.seconds_per_minute = 0.5;
  o.min_event_gap = 0;
  o.lead_in = 0;
  o.tail = 0;
  const TimeMap map({10, 20, 20.2}, 30, o);
  EXPECT_DOUBLE_EQ(map.seconds(10), 5);
  EXPECT_DOUBLE_EQ(map.seconds(20), 10);
  EXPECT_NEAR(map.seconds(20.2), 10.1, 1e-12);
  EXPECT_NEAR(map.duration(), 15, 1e-12);
  EXPECT_DOUBLE_EQ(map.minute(7.5), 15);
}

TEST(TimeMap, MonotoneAndInverse) {
  const TimeMap map({0, 0.1, 0.2, 5, 5, 7.5, 60}, 90, TimeMapOptions{});
  double prev = -1;
  for (double m = 0; m <= 90; m += 0.05) {
    const double s = map.seconds(m);
    EXPECT_GT(s, prev);
    EXPECT_NEAR(map.minute(s), m, 1e-9);
    prev = s;
  }
}

TEST(TimeMap, RejectsBadInput) {
  EXPECT_THROW(TimeMap({3, 2}, 90, TimeMapOptions{}), InvalidInput);
  EXPECT_THROW(TimeMap({std::nan("")}, 90, TimeMapOptions{}), InvalidInput);
  EXPECT_THROW(TimeMap({-1}, 90, TimeMapOptions{}), InvalidInput);
  EXPECT_THROW(TimeMap({1}, INFINITY, TimeMapOptions{}), InvalidInput);
  TimeMapOptions o;
  o.seconds_per_minute = 0;
  EXPECT_THROW(o.validate(), InvalidInput);
  o = {};
  o.min_event_gap = -1;
  EXPECT_THROW(o.validate(), InvalidInput);
  o = {};
  o.tail = std::nan("");
  EXPECT_THROW(o.validate(), InvalidInput);
  o = {};
  o.lead_in = 100;
  EXPECT_THROW(o.validate(), InvalidInput);
}

}  // namespace
}  // namespace emoface::obie
