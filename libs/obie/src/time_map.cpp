#include "emoface/obie/time_map.hpp"

#include <algorithm>
#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::obie {

namespace {
bool in(double x, double lo, double hi) { return std::isfinite(x) && x >= lo && x <= hi; }
}  // namespace

void TimeMapOptions::validate() const {
  if (!(in(seconds_per_minute, 0, 60) && seconds_per_minute > 0))
    throw InvalidInput("time map: seconds_per_minute must be in (0, 60]");
  if (!in(min_event_gap, 0, 60)) throw InvalidInput("time map: min_event_gap must be in [0, 60] s");
  if (!in(lead_in, 0, 60)) throw InvalidInput("time map: lead_in must be in [0, 60] s");
  if (!in(tail, 0, 60)) throw InvalidInput("time map: tail must be in [0, 60] s");
}

TimeMap::TimeMap(const std::vector<double>& event_minutes, double match_end, const TimeMapOptions& options) {
  options.validate();
  if (!std::isfinite(match_end) || match_end < 0) throw InvalidInput("time map: match end must be finite and >= 0");
  slope_ = options.seconds_per_minute;
  minutes_ = {0.0};
  seconds_ = {options.lead_in};
  double prev = 0.0;
  for (double m : event_minutes) {
    if (!std::isfinite(m) || m < 0) throw InvalidInput("time map: event minutes must be finite and >= 0");
    if (m < prev) throw InvalidInput("time map: event minutes must not decrease");
    prev = m;
    if (m <= minutes_.back()) continue;
    const double step = std::max(slope_ * (m - minutes_.back()), options.min_event_gap);
    seconds_.push_back(seconds_.back() + step);
    minutes_.push_back(m);
  }
  duration_ = seconds(std::max(match_end, minutes_.back())) + options.tail;
}

double TimeMap::seconds(double minute) const noexcept {
  if (!(minute > 0)) return seconds_.front();
  if (minute >= minutes_.back()) return seconds_.back() + slope_ * (minute - minutes_.back());
  const auto it = std::upper_bound(minutes_.begin(), minutes_.end(), minute);
  const std::size_t k = static_cast<std::size_t>(it - minutes_.begin());  // minutes_[k-1] <= minute < minutes_[k]
  const double u = (minute - minutes_[k - 1]) / (minutes_[k] - minutes_[k - 1]);
  return seconds_[k - 1] + u * (seconds_[k] - seconds_[k - 1]);
}

double TimeMap::minute(double s) const noexcept {
  if (!(s > seconds_.front())) return 0.0;
  if (s >= seconds_.back()) return minutes_.back() + (std::min(s, duration_) - seconds_.back()) / slope_;
  const auto it = std::upper_bound(seconds_.begin(), seconds_.end(), s);
  const std::size_t k = static_cast<std::size_t>(it - seconds_.begin());
  const double u = (s - seconds_[k - 1]) / (seconds_[k] - seconds_[k - 1]);
  return minutes_[k - 1] + u * (minutes_[k] - minutes_[k - 1]);
}

}  // namespace emoface::obie
