#include "emoface/runtime/streaming.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "emoface/channels/curves.hpp"
#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::runtime {

namespace ch = emoface::channels;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

// ------------------------------------------------------------------------------------ channel

StreamingChannel::StreamingChannel(std::vector<std::string> parameters)
    : parameters_(std::move(parameters)) {
  for (std::size_t i = 0; i < parameters_.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (parameters_[i] == parameters_[j])
        throw InvalidInput("StreamingChannel: parameter '" + parameters_[i] + "' repeated");
}

double StreamingChannel::last_start() const noexcept {
  return items_.empty() ? -kInf : items_.back().timing.start;
}
double StreamingChannel::last_end() const noexcept {
  return items_.empty() ? -kInf : items_.back().timing.end;
}

void StreamingChannel::append(const ch::Movement& m) {
  m.timing.validate();
  if (!items_.empty()) {
    const ch::Timing& a = items_.back().timing;
    if (!(m.timing.start > a.start) || !(m.timing.end > a.end))
      throw InvalidInput("StreamingChannel: movement '" + m.label +
                         "' breaks the channel order (need a later start and a later end)");
  }
  Item it;
  it.timing = m.timing;
  it.target.assign(parameters_.size(), 0.0);
  std::vector<char> seen(parameters_.size(), 0);
  for (const ch::Target& tg : m.targets) {
    const auto pos = std::find(parameters_.begin(), parameters_.end(), tg.parameter);
    if (pos == parameters_.end())
      throw InvalidInput("StreamingChannel: movement '" + m.label + "' targets '" + tg.parameter +
                         "', not a parameter of this channel");
    const auto p = static_cast<std::size_t>(pos - parameters_.begin());
    if (seen[p])
      throw InvalidInput("StreamingChannel: movement '" + m.label + "' targets " + tg.parameter +
                         " twice");
    if (!std::isfinite(tg.value))
      throw InvalidInput("StreamingChannel: non-finite target of " + tg.parameter);
    seen[p] = 1;
    it.target[p] = tg.value;
  }
  it.start_value.assign(parameters_.size(), 0.0);
  it.previous_end = -kInf;
  if (!items_.empty()) {
    const Item& prev = items_.back();
    it.overlaps = m.timing.start < prev.timing.end;
    it.previous_offset = prev.timing.offset;
    it.previous_end = prev.timing.end;
    for (std::size_t p = 0; p < parameters_.size(); ++p)
      it.start_value[p] = value_in(p, prev, m.timing.start);
  }
  items_.push_back(std::move(it));
}

// Same arithmetic as ConcatenatedChannel::value_in (channels/src/channel.cpp), so both agree
// exactly.
double StreamingChannel::value_in(std::size_t p, const Item& m, double t) const {
  const double pv = m.target[p];
  const double own = ch::activity(pv, m.timing, t);
  const double s = m.start_value[p];
  if (!m.overlaps && s == 0.0) return own;
  const double x = t - m.timing.start;
  const double goal = t <= m.timing.start + m.timing.onset ? pv : own;
  if (s < pv) return std::min(s + ch::phi_plus(x, m.timing.onset), goal);
  return std::max(s - ch::phi_plus(x, m.previous_offset), goal);
}

double StreamingChannel::value(std::size_t p, double t) const {
  if (p >= parameters_.size())
    throw InvalidInput("StreamingChannel::value: parameter index out of range");
  const auto it = std::lower_bound(items_.begin(), items_.end(), t,
                                   [](const Item& m, double tt) { return m.timing.start < tt; });
  if (it == items_.begin()) return 0.0;
  return value_in(p, *std::prev(it), t);
}

void StreamingChannel::sample(double t, double* out) const {
  const auto it = std::lower_bound(items_.begin(), items_.end(), t,
                                   [](const Item& m, double tt) { return m.timing.start < tt; });
  if (it == items_.begin()) {
    std::fill(out, out + parameters_.size(), 0.0);
    return;
  }
  const Item& m = *std::prev(it);
  for (std::size_t p = 0; p < parameters_.size(); ++p) out[p] = value_in(p, m, t);
}

void StreamingChannel::prune(double t) {
  const auto it = std::lower_bound(items_.begin(), items_.end(), t,
                                   [](const Item& m, double tt) { return m.timing.start < tt; });
  if (it == items_.begin()) return;
  items_.erase(items_.begin(), std::prev(it));
}

void StreamingChannel::restore(std::vector<Item> items) {
  for (std::size_t k = 0; k < items.size(); ++k) {
    items[k].timing.validate();
    if (items[k].target.size() != parameters_.size() ||
        items[k].start_value.size() != parameters_.size())
      throw InvalidInput("StreamingChannel::restore: wrong number of parameters");
    if (k > 0 && !(items[k].timing.start > items[k - 1].timing.start))
      throw InvalidInput("StreamingChannel::restore: movements out of order");
  }
  items_ = std::move(items);
}

// ------------------------------------------------------------------------------------ mixer

StreamingMixer::StreamingMixer(
    std::vector<std::string> parameters,
    std::array<std::vector<std::size_t>, ch::kChannelCount> channel_parameters,
    const ch::ConflictTable& conflicts, const ch::MixOptions& options, double fps,
    std::size_t lookahead_frames)
    : parameters_(std::move(parameters)),
      chan_params_(std::move(channel_parameters)),
      options_(options),
      fps_(fps),
      lookahead_(lookahead_frames) {
  options_.validate();
  if (!(std::isfinite(fps) && fps > 0 && fps <= 10000))
    throw InvalidInput("StreamingMixer: fps must be in (0, 10000]");
  if (lookahead_frames > 100000) throw InvalidInput("StreamingMixer: look-ahead too long");
  const std::size_t np = parameters_.size();
  for (std::size_t c = 0; c < ch::kChannelCount; ++c) {
    offset_[c] = width_;
    for (std::size_t p : chan_params_[c])
      if (p >= np) throw InvalidInput("StreamingMixer: channel parameter index out of range");
    width_ += chan_params_[c].size();
  }
  conflict_ = conflicts.expand(parameters_);
  is_signed_.resize(np);
  for (std::size_t i = 0; i < np; ++i) is_signed_[i] = ch::is_signed_parameter(parameters_[i]);
  has_conflict_.assign(width_, 0);
  for (std::size_t c = 0; c < ch::kChannelCount; ++c)
    for (std::size_t i = 0; i < chan_params_[c].size(); ++i)
      has_conflict_[offset_[c] + i] = !conflict_[chan_params_[c][i]].empty();
  order_.resize(ch::kChannelCount);
  std::iota(order_.begin(), order_.end(), 0);
  prio_.assign(options_.priority.begin(), options_.priority.end());
  std::stable_sort(order_.begin(), order_.end(),
                   [&](std::size_t a, std::size_t b) { return prio_[a] < prio_[b]; });
  const std::size_t w = lookahead_ + 1;
  ring_.assign(w * width_, 0.0);
  mod_.assign(w * width_, 0.0);
  active_.assign(w * np, 0);
  inh_.assign(w, 0);
  group_active_.assign(width_, 0);  // per entry: inhibited at the output frame
  last_inh_.assign(width_, -kInf);
  output_.assign(np, 0.0);
}

std::size_t StreamingMixer::frames_out() const noexcept {
  return frames_in_ > lookahead_ ? frames_in_ - lookahead_ : 0;
}

void StreamingMixer::push(const std::array<const double*, ch::kChannelCount>& raw) {
  const std::size_t w = lookahead_ + 1;
  {
    double* slot = ring_.data() + (frames_in_ % w) * width_;
    for (std::size_t c = 0; c < ch::kChannelCount; ++c) {
      const std::size_t n = chan_params_[c].size();
      if (n == 0) continue;
      if (raw[c]) {
        std::copy(raw[c], raw[c] + n, slot + offset_[c]);
      } else {
        std::fill(slot + offset_[c], slot + offset_[c] + n, 0.0);
      }
    }
  }
  ++frames_in_;
  if (frames_in_ <= lookahead_) return;
  const std::size_t f = frames_in_ - 1 - lookahead_;  // the frame mixed now
  const std::size_t np = parameters_.size();
  std::fill(active_.begin(), active_.end(), 0);
  const double thr = options_.active_threshold;
  // channels in priority order; a group of equal priority sees only strictly higher groups
  for (std::size_t g = 0; g < order_.size();) {
    std::size_t g_end = g;
    while (g_end < order_.size() && prio_[order_[g_end]] == prio_[order_[g]]) ++g_end;
    for (std::size_t oi = g; oi < g_end; ++oi) {
      const std::size_t c = order_[oi];
      for (std::size_t i = 0; i < chan_params_[c].size(); ++i) {
        const std::size_t e = offset_[c] + i;
        const std::size_t p = chan_params_[c][i];
        for (std::size_t j = 0; j < w; ++j)
          mod_[j * width_ + e] = ring_[((f + j) % w) * width_ + e];
        group_active_[e] = 0;
        if (!has_conflict_[e]) continue;
        bool any = false;
        for (std::size_t j = 0; j < w; ++j) {
          char in = 0;
          for (std::size_t q : conflict_[p]) in |= active_[j * np + q];
          inh_[j] = in;
          any |= in != 0;
        }
        double t_last = last_inh_[e];
        if (!any && t_last == -kInf) continue;  // never inhibited: aF = F
        // next inhibited frame after j inside the window (beyond it: unknown, taken as none)
        double t_next = kInf;
        for (std::size_t j = w; j-- > 0;) {
          // Ψ→ for frame j uses the next inhibited frame at or after j (an inhibited frame is 0
          // anyway)
          const double t = static_cast<double>(f + j) / fps_;
          double& v = mod_[j * width_ + e];
          if (inh_[j]) {
            t_next = t;
            v = 0.0;
            continue;
          }
          if (t_next < kInf && t_next - t < options_.dmin_minus)
            v = std::min(v, ch::phi_minus(options_.dmin_minus - (t_next - t), options_.dmin_minus));
        }
        // Ψ← forward through the window (T←: the state, then the window's inhibited frames)
        for (std::size_t j = 0; j < w; ++j) {
          const double t = static_cast<double>(f + j) / fps_;
          if (inh_[j]) {
            t_last = t;
            continue;
          }
          if (t_last > -kInf) {
            double& v = mod_[j * width_ + e];
            v = std::min(v, ch::phi_plus(t - t_last, options_.dmin_plus));
          }
        }
        group_active_[e] = inh_[0];
      }
    }
    // the group's modified activity now inhibits lower-priority channels
    for (std::size_t oi = g; oi < g_end; ++oi) {
      const std::size_t c = order_[oi];
      for (std::size_t i = 0; i < chan_params_[c].size(); ++i) {
        const std::size_t e = offset_[c] + i;
        const std::size_t p = chan_params_[c][i];
        for (std::size_t j = 0; j < w; ++j)
          if (std::abs(mod_[j * width_ + e]) > thr) active_[j * np + p] = 1;
      }
    }
    g = g_end;
  }
  const double tf = static_cast<double>(f) / fps_;
  for (std::size_t e = 0; e < width_; ++e)
    if (group_active_[e]) last_inh_[e] = tf;
  std::fill(output_.begin(), output_.end(), 0.0);
  for (std::size_t c = 0; c < ch::kChannelCount; ++c) {
    for (std::size_t i = 0; i < chan_params_[c].size(); ++i) {
      const std::size_t p = chan_params_[c][i];
      const double v = mod_[offset_[c] + i];
      double& o = output_[p];
      if (is_signed_[p] ? std::abs(v) > std::abs(o) : v > o) o = v;
    }
  }
}

StreamingMixer::State StreamingMixer::state() const {
  return State{frames_in_, ring_, last_inh_, output_};
}

void StreamingMixer::restore(const State& s) {
  if (s.ring.size() != ring_.size() || s.last_inhibited.size() != last_inh_.size() ||
      s.output.size() != output_.size())
    throw InvalidInput("StreamingMixer::restore: state of a different mixer (sizes differ)");
  frames_in_ = s.frames_in;
  ring_ = s.ring;
  last_inh_ = s.last_inhibited;
  output_ = s.output;
}

}  // namespace emoface::runtime
