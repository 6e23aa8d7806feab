#include "emoface/channels/generators.hpp"

#include <algorithm>
#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::channels {

void BlinkOptions::validate() const {
  Timing{0.0, duration, onset, offset}.validate();
  if (!(std::isfinite(min_interval) && min_interval >= duration))
    throw InvalidInput("blinks: min_interval must be >= duration");
  if (!(std::isfinite(mean_interval) && mean_interval > min_interval && mean_interval < 3600))
    throw InvalidInput("blinks: mean_interval must be in (min_interval, 3600) s");
  if (!(closure > 0 && closure <= 1)) throw InvalidInput("blinks: closure must be in (0, 1]");
}

std::vector<Movement> generate_blinks(double begin, double end, const BlinkOptions& o, core::Rng& rng) {
  o.validate();
  if (!(std::isfinite(begin) && std::isfinite(end) && begin >= 0 && end >= begin))
    throw InvalidInput("blinks: need 0 <= begin <= end");
  std::vector<Movement> out;
  const double rate = 1.0 / (o.mean_interval - o.min_interval);
  for (double t = begin + o.min_interval + rng.exponential(rate); t < end;
       t += o.min_interval + rng.exponential(rate)) {
    Movement m;
    m.targets = {{"eye_blink_l", o.closure}, {"eye_blink_r", o.closure}};
    m.timing = Timing{t, t + o.duration, o.onset, o.offset};
    m.label = "blink";
    out.push_back(std::move(m));
  }
  return out;
}

void NoiseOptions::validate() const {
  if (!(std::isfinite(amplitude) && amplitude >= 0 && amplitude <= 0.5))
    throw InvalidInput("noise: amplitude must be in [0, 0.5] rad");
  if (!(std::isfinite(transition) && transition > 0)) throw InvalidInput("noise: transition must be > 0");
  if (!(std::isfinite(min_hold) && min_hold >= transition))
    throw InvalidInput("noise: min_hold must be >= transition");
  if (!(std::isfinite(mean_hold) && mean_hold > min_hold && mean_hold < 3600))
    throw InvalidInput("noise: mean_hold must be in (min_hold, 3600) s");
}

NoiseOptions default_gaze_noise() { return NoiseOptions{0.03, 1.2, 0.25, 0.05}; }
NoiseOptions default_head_noise() { return NoiseOptions{0.02, 2.5, 0.8, 0.5}; }

std::vector<Movement> generate_noise(double begin, double end, const std::vector<std::string>& parameters,
                                     const NoiseOptions& o, core::Rng& rng, const std::string& label) {
  o.validate();
  if (!(std::isfinite(begin) && std::isfinite(end) && begin >= 0 && end >= begin))
    throw InvalidInput("noise: need 0 <= begin <= end");
  std::vector<Movement> out;
  if (parameters.empty() || end - begin < 2 * o.transition) return out;
  const double rate = 1.0 / (o.mean_hold - o.min_hold);
  double t = begin;
  while (t < end - 2 * o.transition) {
    const double next = std::min(t + o.min_hold + rng.exponential(rate), end);
    Movement m;
    for (const auto& p : parameters) m.targets.push_back({p, rng.normal(0.0, o.amplitude)});
    // ends one transition after the next shift starts, so consecutive shifts overlap and the channel
    // concatenation (§4.5.2) carries the angle from one fixation to the next.
    const double stop = next >= end ? end : next + o.transition;
    m.timing = Timing{t, stop, o.transition, o.transition};
    if (stop - t < 2 * o.transition) break;
    m.label = label;
    out.push_back(std::move(m));
    t = next;
  }
  return out;
}

std::vector<Movement> merge_generated(std::vector<Movement> explicit_movements,
                                      const std::vector<Movement>& generated, double margin) {
  const std::size_t n_explicit = explicit_movements.size();
  for (const Movement& g : generated) {
    const auto e_end = explicit_movements.begin() + static_cast<std::ptrdiff_t>(n_explicit);
    const bool clash = std::any_of(explicit_movements.begin(), e_end, [&](const Movement& e) {
      return g.timing.start < e.timing.end + margin && e.timing.start < g.timing.end + margin;
    });
    if (!clash) explicit_movements.push_back(g);
  }
  std::stable_sort(explicit_movements.begin(), explicit_movements.end(),
                   [](const Movement& a, const Movement& b) { return a.timing.start < b.timing.start; });
  return explicit_movements;
}

}  // namespace emoface::channels
