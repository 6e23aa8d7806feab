#pragma once
// Match time → animation time. A 90-minute match cannot be a 90-minute video, and events that the
// script puts half a minute apart (the §7.4 free-kick at 40' and the goal at 40.5') must stay far
// enough apart on screen for each reaction to be seen. The mapping is piecewise linear and strictly
// increasing through knots (match minute m_k, animation second s_k):
//
//   s_0 = lead_in at m_0 = 0;
//   for each distinct event minute m_k > m_{k−1}:  s_k = s_{k−1} + max(seconds_per_minute·(m_k − m_{k−1}), min_event_gap)
//   after the last knot the slope is seconds_per_minute; the animation ends `tail` seconds after the
//   match end (the later of the match duration and the last event).
//
// With the defaults (1 s per minute, events ≥ 1 s apart) the §7.4 match becomes a 95.5-second video.
#include <vector>

namespace emoface::obie {

struct TimeMapOptions {
  double seconds_per_minute = 1.0;  ///< animation seconds per match minute, (0, 60]
  double min_event_gap = 1.0;       ///< animation seconds between events at different minutes, at least, [0, 60]
  double lead_in = 1.0;             ///< animation seconds before minute 0 (a neutral face), [0, 60]
  double tail = 3.5;                ///< animation seconds after the match end, [0, 60]
  void validate() const;            ///< throws InvalidInput
};

class TimeMap {
 public:
  TimeMap() = default;
  /// `event_minutes` must be finite, ≥ 0 and non-decreasing; `match_end` ≥ 0 (minutes).
  /// Throws InvalidInput otherwise.
  TimeMap(const std::vector<double>& event_minutes, double match_end, const TimeMapOptions& options);

  /// Animation seconds of a match minute (minutes < 0 clamp to 0; beyond the last knot: linear).
  double seconds(double minute) const noexcept;
  /// Inverse of seconds() on [lead_in, duration()] (clamped outside).
  double minute(double seconds) const noexcept;
  /// Seconds of animation in total: seconds(match end) + tail.
  double duration() const noexcept { return duration_; }
  const std::vector<double>& knot_minutes() const noexcept { return minutes_; }
  const std::vector<double>& knot_seconds() const noexcept { return seconds_; }

 private:
  std::vector<double> minutes_{0.0};
  std::vector<double> seconds_{0.0};
  double slope_ = 1.0;
  double duration_ = 0.0;
};

}  // namespace emoface::obie
