#include "emoface/channels/dominance.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::channels {

void Dominance::validate() const {
  if (!(std::isfinite(alpha) && alpha > 0)) throw InvalidInput("dominance: alpha must be finite and > 0");
  if (!(std::isfinite(theta_anticipatory) && theta_anticipatory > 0) ||
      !(std::isfinite(theta_carryover) && theta_carryover > 0))
    throw InvalidInput("dominance: theta must be finite and > 0");
  if (!(std::isfinite(c) && c > 0 && c <= 10)) throw InvalidInput("dominance: c must be in (0, 10]");
  if (!(std::isfinite(peak_offset) && std::abs(peak_offset) <= 10))
    throw InvalidInput("dominance: peak_offset must be finite, |To| <= 10 s");
}

const Dominance& Viseme::dominance_of(std::string_view parameter) const {
  const auto it = per_parameter.find(std::string(parameter));
  return it == per_parameter.end() ? dominance : it->second;
}

double Viseme::target_of(std::string_view parameter) const {
  for (const Target& t : targets)
    if (t.parameter == parameter) return t.value;
  return 0.0;
}

void VisemeSet::validate() const {
  std::set<std::string> names;
  for (const Viseme& v : visemes) {
    if (v.name.empty()) throw InvalidInput("viseme with an empty name");
    if (!names.insert(v.name).second) throw InvalidInput("viseme '" + v.name + "' defined twice");
    v.dominance.validate();
    std::set<std::string> seen;
    for (const Target& t : v.targets) {
      if (!is_known_parameter(t.parameter))
        throw InvalidInput("viseme '" + v.name + "': unknown parameter '" + t.parameter + "'");
      if (!seen.insert(t.parameter).second)
        throw InvalidInput("viseme '" + v.name + "': parameter '" + t.parameter + "' twice");
      if (!std::isfinite(t.value) || (!is_signed_parameter(t.parameter) && (t.value < 0 || t.value > 1)))
        throw InvalidInput("viseme '" + v.name + "': target of '" + t.parameter + "' out of range");
    }
    for (const auto& [p, d] : v.per_parameter) {
      if (!is_known_parameter(p))
        throw InvalidInput("viseme '" + v.name + "': dominance for unknown parameter '" + p + "'");
      d.validate();
    }
  }
  if (!find(silence)) throw InvalidInput("viseme set has no silence viseme '" + silence + "'");
  for (const auto& [ph, v] : phoneme_to_viseme)
    if (!find(v)) throw InvalidInput("phoneme '" + ph + "' maps to unknown viseme '" + v + "'");
}

const Viseme* VisemeSet::find(std::string_view name) const {
  for (const Viseme& v : visemes)
    if (v.name == name) return &v;
  return nullptr;
}

const std::string& VisemeSet::viseme_for_phoneme(std::string_view phoneme) const {
  auto it = phoneme_to_viseme.find(std::string(phoneme));
  if (it != phoneme_to_viseme.end()) return it->second;
  if (const Viseme* v = find(phoneme)) return v->name;  // viseme-level timings (e.g. Rhubarb cues)
  std::string stripped(phoneme);
  while (!stripped.empty() && (stripped.back() == ':' || stripped.back() == ';' || stripped.back() == '#'))
    stripped.pop_back();
  it = phoneme_to_viseme.find(stripped);
  if (it != phoneme_to_viseme.end()) return it->second;
  return silence;
}

std::vector<std::string> VisemeSet::parameters() const {
  std::vector<std::string> out;
  for (const Viseme& v : visemes)
    for (const Target& t : v.targets)
      if (std::find(out.begin(), out.end(), t.parameter) == out.end()) out.push_back(t.parameter);
  return out;
}

void CoarticulationOptions::validate() const {
  if (!(std::isfinite(time_unit) && time_unit > 0)) throw InvalidInput("coarticulation: time_unit must be > 0");
  if (!(rest_dominance > 0 && rest_dominance <= 0.01))
    throw InvalidInput("coarticulation: rest_dominance must be in (0, 0.01]");
  if (!(cutoff > 0 && cutoff <= 0.1)) throw InvalidInput("coarticulation: cutoff must be in (0, 0.1]");
}

Coarticulation::Coarticulation(const VisemeSet& visemes, std::vector<LipSegment> segments,
                               CoarticulationOptions options)
    : segments_(std::move(segments)), parameters_(visemes.parameters()), options_(options) {
  options_.validate();
  for (std::size_t p = 0; p < parameters_.size(); ++p) index_.emplace(parameters_[p], p);
  const std::size_t np = parameters_.size();
  slots_.resize(segments_.size() * np);
  max_reach_.assign(np, 0.0);
  const double log_floor = std::log(options_.cutoff * options_.rest_dominance);
  for (std::size_t m = 0; m < segments_.size(); ++m) {
    const LipSegment& s = segments_[m];
    if (!std::isfinite(s.start) || !std::isfinite(s.end) || s.start < 0 || !(s.end > s.start))
      throw InvalidInput("lip segment '" + s.label + "': needs 0 <= start < end");
    if (!std::isfinite(s.apex) || s.apex < 0 || s.apex > s.end - s.start + 1e-9)
      throw InvalidInput("lip segment '" + s.label + "': apex must be in [0, end − start]");
    if (m > 0 && s.start < segments_[m - 1].end - 1e-9)
      throw InvalidInput("lip segments '" + segments_[m - 1].label + "' and '" + s.label +
                         "' overlap or are out of order");
    const Viseme* v = visemes.find(s.viseme);
    if (!v) throw InvalidInput("lip segment '" + s.label + "': unknown viseme '" + s.viseme + "'");
    for (std::size_t p = 0; p < np; ++p) {
      const Dominance& d = v->dominance_of(parameters_[p]);
      d.validate();
      Slot& sl = slots_[m * np + p];
      sl.target = v->target_of(parameters_[p]);
      sl.log_alpha = std::log(d.alpha);
      sl.theta_ant = d.theta_anticipatory;
      sl.theta_carry = d.theta_carryover;
      sl.c = d.c;
      sl.peak = s.start + 0.5 * (s.end - s.start) + d.peak_offset;  // Tc + To (§4.5.1)
      sl.half_apex = 0.5 * s.apex;
      // |τ| (in units) beyond which Δ < cutoff·rest_dominance on the slower side.
      const double tau = std::pow(std::max(0.0, std::log(d.alpha) - log_floor) /
                                      std::min(d.theta_anticipatory, d.theta_carryover), 1.0 / d.c);
      sl.reach = sl.half_apex + tau * options_.time_unit;
      max_reach_[p] = std::max(max_reach_[p], sl.reach + std::abs(d.peak_offset) + 0.5 * (s.end - s.start));
    }
  }
}

int Coarticulation::parameter_index(std::string_view parameter) const {
  const auto it = index_.find(std::string(parameter));
  return it == index_.end() ? -1 : static_cast<int>(it->second);
}

namespace {
// log Δ(τ): τ = Tc + To − t (seconds) (§4.5.1); τ >= 0 uses θ←, τ < 0 uses θ→. The apex keeps Δ at α
// for |τ| <= Da/2.
template <class Slot>
double log_dominance(const Slot& s, double t, double unit) {
  const double tau = s.peak - t;
  const double mag = std::max(0.0, std::abs(tau) - s.half_apex) / unit;
  const double theta = tau >= 0 ? s.theta_ant : s.theta_carry;
  return s.log_alpha - theta * (s.c == 1.0 ? mag : std::pow(mag, s.c));
}
}  // namespace

double Coarticulation::dominance(std::size_t m, std::size_t p, double t) const {
  if (m >= segments_.size() || p >= parameters_.size())
    throw InvalidInput("Coarticulation::dominance: index out of range");
  return std::exp(log_dominance(slots_[m * parameters_.size() + p], t, options_.time_unit));
}

// F_p(t) over segments [lo, hi): the weighted average of §4.5.1, computed relative to the largest
// log-dominance so nothing underflows. `ld` is scratch space.
double Coarticulation::average(std::size_t p, double t, std::size_t lo, std::size_t hi, std::vector<double>& ld) const {
  const std::size_t np = parameters_.size();
  ld.resize(hi - lo);
  const double log_rest = std::log(options_.rest_dominance);
  double best = log_rest;
  for (std::size_t m = lo; m < hi; ++m) {
    const Slot& s = slots_[m * np + p];
    double& l = ld[m - lo];
    l = std::abs(s.peak - t) > s.reach ? -HUGE_VAL : log_dominance(s, t, options_.time_unit);
    best = std::max(best, l);
  }
  double num = 0.0, den = std::exp(log_rest - best);  // the rest position: target 0
  for (std::size_t m = lo; m < hi; ++m) {
    if (ld[m - lo] == -HUGE_VAL) continue;
    const double w = std::exp(ld[m - lo] - best);
    num += w * slots_[m * np + p].target;
    den += w;
  }
  return num / den;
}

double Coarticulation::value(std::size_t p, double t) const {
  if (p >= parameters_.size()) throw InvalidInput("Coarticulation::value: parameter index out of range");
  const double r = max_reach_[p];
  // segments with end >= t − r and start <= t + r
  const auto first = std::lower_bound(segments_.begin(), segments_.end(), t - r,
                                      [](const LipSegment& s, double x) { return s.end < x; });
  std::size_t lo = static_cast<std::size_t>(first - segments_.begin()), hi = lo;
  while (hi < segments_.size() && segments_[hi].start <= t + r) ++hi;
  std::vector<double> ld;
  return average(p, t, lo, hi, ld);
}

double Coarticulation::value(std::string_view parameter, double t) const {
  const int p = parameter_index(parameter);
  return p < 0 ? 0.0 : value(static_cast<std::size_t>(p), t);
}

void Coarticulation::sample(std::size_t p, double t0, double fps, std::size_t n, double* out) const {
  if (p >= parameters_.size()) throw InvalidInput("Coarticulation::sample: parameter index out of range");
  const double r = max_reach_[p];
  std::vector<double> ld;
  std::size_t lo = 0, hi = 0;  // sliding window of segments in reach, times increase
  for (std::size_t i = 0; i < n; ++i) {
    const double t = t0 + static_cast<double>(i) / fps;
    while (lo < segments_.size() && segments_[lo].end < t - r) ++lo;
    hi = std::max(hi, lo);
    while (hi < segments_.size() && segments_[hi].start <= t + r) ++hi;
    out[i] = average(p, t, lo, hi, ld);
  }
}

}  // namespace emoface::channels
