#include "emoface/channels/mixer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <unordered_map>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::channels {

int Tracks::column(std::string_view name) const {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<int>(i);
  return -1;
}

std::vector<double> Tracks::series(std::string_view name) const {
  const int c = column(name);
  if (c < 0) throw InvalidInput("tracks have no column '" + std::string(name) + "'");
  std::vector<double> out(frames());
  for (std::size_t f = 0; f < out.size(); ++f) out[f] = at(f, static_cast<std::size_t>(c));
  return out;
}

void Tracks::validate() const {
  if (!(std::isfinite(fps) && fps > 0)) throw InvalidInput("tracks: fps must be finite and > 0");
  std::set<std::string> seen;
  for (const auto& n : names) {
    if (n.empty()) throw InvalidInput("tracks: empty column name");
    if (n == "time") throw InvalidInput("tracks: 'time' is reserved for the time column");
    if (!seen.insert(n).second) throw InvalidInput("tracks: column '" + n + "' repeated");
  }
  if (names.empty() ? !values.empty() : values.size() % names.size() != 0)
    throw InvalidInput("tracks: value count is not a multiple of the column count");
  for (double v : values)
    if (!std::isfinite(v)) throw InvalidInput("tracks: non-finite value");
}

void MixOptions::validate() const {
  if (!(std::isfinite(dmin_plus) && dmin_plus > 0)) throw InvalidInput("mix: dmin_plus must be > 0");
  if (!(std::isfinite(dmin_minus) && dmin_minus > 0)) throw InvalidInput("mix: dmin_minus must be > 0");
  if (!(active_threshold > 0 && active_threshold < 1))
    throw InvalidInput("mix: active_threshold must be in (0, 1)");
}

namespace {

// §4.6 for one parameter track v (F on entry, aF on exit) given its inhibited frames.
void apply_inhibition(double* v, const std::vector<char>& inhibited, std::size_t frames, double fps,
                      const MixOptions& options, std::vector<double>& last,
                      std::vector<double>& next) {
  const double inf = std::numeric_limits<double>::infinity();
  double t_last = -inf;
  for (std::size_t f = 0; f < frames; ++f) {
    if (inhibited[f]) t_last = static_cast<double>(f) / fps;
    last[f] = t_last;
  }
  double t_next = inf;
  for (std::size_t f = frames; f-- > 0;) {
    if (inhibited[f]) t_next = static_cast<double>(f) / fps;
    next[f] = t_next;
  }
  for (std::size_t f = 0; f < frames; ++f) {
    if (inhibited[f]) {
      v[f] = 0.0;
      continue;
    }
    const double t = static_cast<double>(f) / fps;
    double cap = inf;
    if (last[f] > -inf) cap = std::min(cap, phi_plus(t - last[f], options.dmin_plus));  // Ψ←
    if (next[f] < inf && next[f] - t < options.dmin_minus)                              // Ψ→
      cap = std::min(cap, phi_minus(options.dmin_minus - (next[f] - t), options.dmin_minus));
    v[f] = std::min(v[f], cap);
  }
}

}  // namespace

Tracks mix(const std::vector<ChannelSamples>& channels, const std::vector<std::string>& parameters,
           double fps, std::size_t frames, const ConflictTable& conflicts, const MixOptions& options,
           std::vector<ChannelSamples>* modified) {
  options.validate();
  if (!(std::isfinite(fps) && fps > 0)) throw InvalidInput("mix: fps must be > 0");
  const std::size_t np = parameters.size();
  std::unordered_map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < np; ++i) index.emplace(parameters[i], i);
  const auto conflict = conflicts.expand(parameters);
  std::vector<char> is_signed(np);
  for (std::size_t i = 0; i < np; ++i) is_signed[i] = is_signed_parameter(parameters[i]);

  Tracks out;
  out.fps = fps;
  out.names = parameters;
  out.values.assign(frames * np, 0.0);

  for (const ChannelSamples& c : channels) {
    if (c.values.size() != c.parameters.size() * frames)
      throw InvalidInput("mix: channel '" + std::string(to_string(c.channel)) + "' has the wrong sample count");
    for (const auto& p : c.parameters)
      if (!index.count(p))
        throw InvalidInput("mix: channel '" + std::string(to_string(c.channel)) + "' uses unknown parameter '" + p + "'");
  }
  bool per_frame = false;
  for (const ChannelSamples& c : channels) {
    if (c.frame_priority.empty()) continue;
    if (c.frame_priority.size() != frames)
      throw InvalidInput("mix: channel '" + std::string(to_string(c.channel)) +
                         "' needs one priority per frame");
    per_frame = true;
  }
  std::vector<ChannelSamples> mod(channels.size());
  std::vector<char> inhibited(frames);
  std::vector<double> last(frames), next(frames);
  if (per_frame) {  // §4.1 per-movement priority: who dominates is decided frame by frame
    auto prio_at = [&](std::size_t c, std::size_t f) {
      if (!channels[c].frame_priority.empty()) return channels[c].frame_priority[f];
      return options.priority[static_cast<std::size_t>(channels[c].channel)];
    };
    // act[c][q·frames + f]: parameter q activated in channel c (previous pass), per frame
    std::vector<std::vector<char>> act(channels.size(), std::vector<char>(np * frames, 0));
    for (std::size_t c = 0; c < channels.size(); ++c) mod[c] = channels[c];
    for (std::size_t pass = 0; pass < 2 * channels.size() + 1; ++pass) {
      bool changed = false;
      for (std::size_t c = 0; c < channels.size(); ++c) {
        std::fill(act[c].begin(), act[c].end(), 0);
        for (std::size_t cp = 0; cp < mod[c].parameters.size(); ++cp) {
          const std::size_t p = index.at(mod[c].parameters[cp]);
          for (std::size_t f = 0; f < frames; ++f)
            if (std::abs(mod[c].values[cp * frames + f]) > options.active_threshold)
              act[c][p * frames + f] = 1;
        }
      }
      for (std::size_t c = 0; c < channels.size(); ++c) {
        std::vector<double> values = channels[c].values;
        for (std::size_t cp = 0; cp < channels[c].parameters.size(); ++cp) {
          const std::size_t p = index.at(channels[c].parameters[cp]);
          if (conflict[p].empty()) continue;
          bool any = false;
          for (std::size_t f = 0; f < frames; ++f) {
            char in = 0;
            const int mine = prio_at(c, f);
            for (std::size_t d = 0; d < channels.size() && !in; ++d) {
              if (d == c || prio_at(d, f) >= mine) continue;  // only strictly higher priority
              for (std::size_t q : conflict[p]) in |= act[d][q * frames + f];
            }
            inhibited[f] = in;
            any |= in != 0;
          }
          if (any)
            apply_inhibition(values.data() + cp * frames, inhibited, frames, fps, options, last,
                             next);
        }
        if (values != mod[c].values) {
          mod[c].values = std::move(values);
          changed = true;
        }
      }
      if (!changed) break;
    }
    for (auto& m : mod) m.frame_priority.clear();
  }
  // channel indices sorted by priority (stable: equal priorities keep input order)
  std::vector<std::size_t> order(channels.size());
  std::iota(order.begin(), order.end(), 0);
  const auto prio = [&](std::size_t i) { return options.priority[static_cast<std::size_t>(channels[i].channel)]; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return prio(a) < prio(b); });

  std::vector<char> active(np * frames, 0);  // activated in a strictly higher-priority channel

  for (std::size_t g = 0; !per_frame && g < order.size();) {  // fixed channel priorities
    std::size_t g_end = g;
    while (g_end < order.size() && prio(order[g_end]) == prio(order[g])) ++g_end;
    for (std::size_t oi = g; oi < g_end; ++oi) {
      const ChannelSamples& c = channels[order[oi]];
      ChannelSamples& m = mod[order[oi]];
      m.channel = c.channel;
      m.parameters = c.parameters;
      m.values = c.values;
      for (std::size_t cp = 0; cp < c.parameters.size(); ++cp) {
        const std::size_t p = index.at(c.parameters[cp]);
        if (conflict[p].empty()) continue;
        double* v = m.values.data() + cp * frames;
        bool any = false;
        for (std::size_t f = 0; f < frames; ++f) {
          char in = 0;
          for (std::size_t q : conflict[p]) in |= active[q * frames + f];
          inhibited[f] = in;
          any |= in != 0;
        }
        if (!any) continue;
        apply_inhibition(v, inhibited, frames, fps, options, last, next);  // T←, T→, Ψ←, Ψ→ (§4.6)
      }
    }
    // the group's modified activity now inhibits lower-priority channels
    for (std::size_t oi = g; oi < g_end; ++oi) {
      const ChannelSamples& m = mod[order[oi]];
      for (std::size_t cp = 0; cp < m.parameters.size(); ++cp) {
        const std::size_t p = index.at(m.parameters[cp]);
        for (std::size_t f = 0; f < frames; ++f)
          if (std::abs(m.values[cp * frames + f]) > options.active_threshold) active[p * frames + f] = 1;
      }
    }
    g = g_end;
  }
  // final value: max over channels (§4.6); signed angles: largest magnitude
  for (const ChannelSamples& m : mod) {
    for (std::size_t cp = 0; cp < m.parameters.size(); ++cp) {
      const std::size_t p = index.at(m.parameters[cp]);
      for (std::size_t f = 0; f < frames; ++f) {
        const double v = m.values[cp * frames + f];
        double& o = out.values[f * np + p];
        if (is_signed[p] ? std::abs(v) > std::abs(o) : v > o) o = v;
      }
    }
  }
  if (modified) *modified = std::move(mod);
  return out;
}

double Timeline::end_time() const {
  double e = 0.0;
  for (const auto& ch : movements)
    for (const Movement& m : ch) e = std::max(e, m.timing.end);
  for (const LipSegment& s : lip) e = std::max(e, s.end);
  return e;
}

void RenderOptions::validate() const {
  if (!(std::isfinite(fps) && fps > 0 && fps <= 10000)) throw InvalidInput("render: fps must be in (0, 10000]");
  if (!(std::isfinite(duration) && duration >= 0 && duration <= 24 * 3600))
    throw InvalidInput("render: duration must be in [0, 86400] s");
  for (const auto& p : parameters)
    if (p.empty() || p == "time") throw InvalidInput("render: bad parameter name '" + p + "'");
  mix.validate();
  coarticulation.validate();
}

Tracks render(const Timeline& timeline, const VisemeSet& visemes, const ConflictTable& conflicts,
              const RenderOptions& options) {
  options.validate();
  if (!timeline.movements[static_cast<std::size_t>(Channel::Lip)].empty())
    throw InvalidInput("render: lip movements must be given as viseme segments");
  const std::vector<std::string>& params =
      options.parameters.empty() ? default_parameter_names() : options.parameters;
  const double duration = options.duration > 0 ? options.duration : timeline.end_time();
  const auto frames = static_cast<std::size_t>(std::floor(duration * options.fps + 1e-9)) + 1;
  if (frames * params.size() > (std::size_t{1} << 28)) throw InvalidInput("render: output too large");

  std::vector<ChannelSamples> samples;
  for (std::size_t c = 0; c < kChannelCount; ++c) {
    const auto channel = static_cast<Channel>(c);
    ChannelSamples s;
    s.channel = channel;
    if (channel == Channel::Lip) {
      if (timeline.lip.empty()) continue;
      const Coarticulation lip(visemes, timeline.lip, options.coarticulation);
      s.parameters = lip.parameters();
      s.values.resize(s.parameters.size() * frames);
      for (std::size_t p = 0; p < s.parameters.size(); ++p)
        lip.sample(p, 0.0, options.fps, frames, s.values.data() + p * frames);
    } else {
      if (timeline.movements[c].empty()) continue;
      const ConcatenatedChannel ch(timeline.movements[c]);
      s.parameters = ch.parameters();
      s.values.resize(s.parameters.size() * frames);
      for (std::size_t p = 0; p < s.parameters.size(); ++p)
        ch.sample(p, 0.0, options.fps, frames, s.values.data() + p * frames);
      // §4.1 per-movement priority: while a movement with its own priority lasts, the channel has
      // it (the highest of overlapping ones)
      for (const Movement& m : timeline.movements[c]) {
        if (m.priority < 0 || m.priority > 100)
          throw InvalidInput("render: movement priority must be in [0, 100]");
        if (m.priority == 0) continue;
        if (s.frame_priority.empty()) s.frame_priority.assign(frames, options.mix.priority[c]);
        const double first = std::ceil(m.timing.start * options.fps - 1e-9);
        const auto f0 = static_cast<std::size_t>(std::max(0.0, first));
        for (std::size_t f = f0;
             f < frames && static_cast<double>(f) / options.fps <= m.timing.end + 1e-12; ++f)
          s.frame_priority[f] = std::min(s.frame_priority[f], m.priority);
      }
    }
    samples.push_back(std::move(s));
  }
  return mix(samples, params, options.fps, frames, conflicts, options.mix);
}

}  // namespace emoface::channels
