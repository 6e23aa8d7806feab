#include "emoface/channels/channel.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::channels {

namespace {
constexpr std::array<std::string_view, kChannelCount> kChannelNames = {
    "manipulator", "lip", "conversational_signal", "emotion_display", "gaze", "head"};
}

std::string_view to_string(Channel channel) noexcept {
  return kChannelNames[static_cast<std::size_t>(channel)];
}

Channel channel_from_string(std::string_view name) {
  for (std::size_t i = 0; i < kChannelCount; ++i)
    if (kChannelNames[i] == name) return static_cast<Channel>(i);
  throw InvalidInput("unknown channel '" + std::string(name) + "'");
}

ConcatenatedChannel::ConcatenatedChannel(std::vector<Movement> movements)
    : movements_(std::move(movements)) {
  for (std::size_t k = 0; k < movements_.size(); ++k) {
    const Movement& m = movements_[k];
    m.timing.validate();
    if (k > 0) {
      // thesis §4.5.2: movements of one channel are sequential: Ts2 > Ts1 and Te2 > Te1.
      const Timing& a = movements_[k - 1].timing;
      if (!(m.timing.start > a.start) || !(m.timing.end > a.end))
        throw InvalidInput("movements '" + movements_[k - 1].label + "' and '" + m.label +
                           "' break the channel order (need a later start and a later end)");
    }
    for (const Target& tg : m.targets) {
      if (!std::isfinite(tg.value))
        throw InvalidInput("movement '" + m.label + "': target of " + tg.parameter + " is not finite");
      if (index_.emplace(tg.parameter, parameters_.size()).second) parameters_.push_back(tg.parameter);
    }
  }
  const std::size_t np = parameters_.size(), nm = movements_.size();
  targets_.assign(nm * np, 0.0);
  for (std::size_t k = 0; k < nm; ++k) {
    std::vector<char> seen(np, 0);
    for (const Target& tg : movements_[k].targets) {
      const std::size_t p = index_.at(tg.parameter);
      if (seen[p])
        throw InvalidInput("movement '" + movements_[k].label + "' targets " + tg.parameter + " twice");
      seen[p] = 1;
      targets_[k * np + p] = tg.value;
    }
  }
  // F_{<k}(Ts_k), computed in order: the combined activity of the movements before k at the start
  // of movement k ("the combined movement ... is further combined with the next", §4.5.2).
  start_value_.assign(nm * np, 0.0);
  overlaps_.assign(nm, 0);
  for (std::size_t k = 1; k < nm; ++k) {
    overlaps_[k] = movements_[k].timing.start < movements_[k - 1].timing.end;
    for (std::size_t p = 0; p < np; ++p)
      start_value_[k * np + p] = value_in(p, k - 1, movements_[k].timing.start);
  }
}

int ConcatenatedChannel::parameter_index(std::string_view parameter) const {
  const auto it = index_.find(std::string(parameter));
  return it == index_.end() ? -1 : static_cast<int>(it->second);
}

// Activity while movement k is the latest one started (Ts_k < t <= Ts_{k+1}).
double ConcatenatedChannel::value_in(std::size_t p, std::size_t k, double t) const {
  const std::size_t np = parameters_.size();
  const Movement& m = movements_[k];
  const double pv = targets_[k * np + p];
  const double own = activity(pv, m.timing, t);
  const double s = start_value_[k * np + p];
  // §4.4: a movement on its own (no overlap and nothing left of the previous transition).
  if (!overlaps_[k] && s == 0.0) return own;
  const double x = t - m.timing.start;
  // After the onset the thesis follows F2 (§4.5.2, last case); during the onset window the
  // transition aims at PV2 itself.
  const double goal = t <= m.timing.start + m.timing.onset ? pv : own;
  if (s < pv) {
    // case 1 (§4.5.2): F1(Ts2) + φ+(t − Ts2, Do2), capped by PV2 (reached at Ts2 + ξ).
    return std::min(s + phi_plus(x, m.timing.onset), goal);
  }
  // case 2 (seeds README reading): F1(Ts2) − φ+(t − Ts2, Dr1) down to PV2 at Ts2 + ξ. If ξ outlasts
  // the onset window the fall continues onto F2 (max keeps it continuous).
  const double dr_prev = movements_[k - 1].timing.offset;
  return std::max(s - phi_plus(x, dr_prev), goal);
}

double ConcatenatedChannel::value(std::size_t p, double t) const {
  if (p >= parameters_.size()) throw InvalidInput("ConcatenatedChannel::value: parameter index out of range");
  // last movement with Ts_k < t
  const auto it = std::lower_bound(movements_.begin(), movements_.end(), t,
                                   [](const Movement& m, double tt) { return m.timing.start < tt; });
  if (it == movements_.begin()) return 0.0;
  return value_in(p, static_cast<std::size_t>(it - movements_.begin()) - 1, t);
}

double ConcatenatedChannel::value(std::string_view parameter, double t) const {
  const int p = parameter_index(parameter);
  return p < 0 ? 0.0 : value(static_cast<std::size_t>(p), t);
}

void ConcatenatedChannel::sample(std::size_t p, double t0, double fps, std::size_t n, double* out) const {
  if (p >= parameters_.size()) throw InvalidInput("ConcatenatedChannel::sample: parameter index out of range");
  std::size_t k = 0;  // number of movements with Ts < t
  for (std::size_t i = 0; i < n; ++i) {
    const double t = t0 + static_cast<double>(i) / fps;
    while (k < movements_.size() && movements_[k].timing.start < t) ++k;
    out[i] = k == 0 ? 0.0 : value_in(p, k - 1, t);
  }
}

}  // namespace emoface::channels
