#include "emoface/parlee/emotion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"

namespace emoface::parlee {
namespace {

constexpr std::array<std::string_view, kEmotionCount> kEmotionNames{
    "joy",          "distress", "happy_for",   "sorry_for",  "resentment",   "gloating",
    "hope",         "fear",     "satisfaction", "fears_confirmed", "relief", "disappointment",
    "pride",        "shame",    "appreciation", "reproach",   "anger",        "gratitude",
    "gratification", "remorse", "surprise"};

constexpr std::array<std::string_view, kTraitCount> kTraitNames{
    "perceiving_level",  "perceiving_focus",  "reasoning_level", "reasoning_focus",
    "learning_level",    "learning_focus",    "deciding_level",  "deciding_focus",
    "acting_level",      "acting_focus",      "interacting_level", "interacting_focus",
    "revealing_level",   "revealing_focus",   "feeling_level",   "feeling_focus"};

void check_unit(double v, const std::string& what) {
  if (!(v >= 0.0 && v <= 1.0)) throw InvalidInput(what + " must be in [0,1]");
}

}  // namespace

std::string_view to_string(Emotion e) { return kEmotionNames.at(index(e)); }

Emotion emotion_from_string(std::string_view name) {
  for (std::size_t i = 0; i < kEmotionCount; ++i)
    if (kEmotionNames[i] == name) return static_cast<Emotion>(i);
  throw InvalidInput("unknown emotion '" + std::string(name) + "'");
}

Valence valence(Emotion e) {
  switch (e) {
    case Emotion::Joy: case Emotion::HappyFor: case Emotion::Gloating: case Emotion::Hope:
    case Emotion::Satisfaction: case Emotion::Relief: case Emotion::Pride: case Emotion::Appreciation:
    case Emotion::Gratitude: case Emotion::Gratification:
      return Valence::Positive;
    case Emotion::Surprise:
      return Valence::Neutral;
    default:
      return Valence::Negative;
  }
}

std::string_view to_string(Trait t) { return kTraitNames.at(static_cast<std::size_t>(t)); }

Trait trait_from_string(std::string_view name) {
  for (std::size_t i = 0; i < kTraitCount; ++i)
    if (kTraitNames[i] == name) return static_cast<Trait>(i);
  throw InvalidInput("unknown personality dimension '" + std::string(name) + "'");
}

void Personality::validate() const {
  for (std::size_t i = 0; i < kTraitCount; ++i) check_unit(values[i], "personality " + std::string(kTraitNames[i]));
}

// thesis §5.6.5 (powers, seeds/README): newExpectation = Expectation^(perceivingFocus+0.5)
double perceive_probability(const Personality& p, double probability) {
  return std::pow(std::clamp(probability, 0.0, 1.0), p[Trait::PerceivingFocus] + 0.5);
}

// thesis §5.6.5: newImpact = −(−impact)^(reasoningFocus+0.5) if impact < 0, impact^(1.5−reasoningFocus)
double reason_impact(const Personality& p, double impact) {
  impact = std::clamp(impact, -1.0, 1.0);
  if (impact < 0.0) return -std::pow(-impact, p[Trait::ReasoningFocus] + 0.5);
  return std::pow(impact, 1.5 - p[Trait::ReasoningFocus]);
}

// thesis §5.6.5: newImpulse = impulse^(1.5−feelingLevel)
double feel_impulse(const Personality& p, double impulse) {
  return impulse <= 0.0 ? 0.0 : std::pow(impulse, 1.5 - p[Trait::FeelingLevel]);
}

std::array<double, 6> revealed_emotions(const std::array<double, 6>& felt, const Personality& p) {
  p.validate();
  const double power = 1.5 - p[Trait::RevealingLevel];  // thesis §5.6.5, read as a power
  std::array<double, 6> out{};
  for (std::size_t k = 0; k < 6; ++k) {
    if (!(felt[k] >= 0.0 && felt[k] <= 1.0))
      throw InvalidInput("revealed_emotions: intensities must be in [0,1]");
    out[k] = felt[k] <= 0.0 ? 0.0 : std::pow(felt[k], power);
  }
  return out;
}

// thesis §5.6.5: newDesire-other impulse = Desire-other impulse · feelingFocus
double desire_other_factor(const Personality& p) { return p[Trait::FeelingFocus]; }

std::string_view to_string(DecayModel m) { return m == DecayModel::Power ? "power" : "product"; }

DecayModel decay_model_from_string(std::string_view s) {
  if (s == "power") return DecayModel::Power;
  if (s == "product") return DecayModel::Product;
  throw InvalidInput("unknown decay model '" + std::string(s) + "' (power, product)");
}

EmotionParams EmotionParams::defaults() {
  EmotionParams p;
  p.alpha.fill(0.1);
  p.omega.fill(1.0);
  p.decay.fill(0.9);
  p.decay[index(Emotion::Hope)] = 0.85;
  p.decay[index(Emotion::Fear)] = 0.85;
  p.decay[index(Emotion::Distress)] = 0.97;  // §7.4: sadness decays very slowly
  p.decay[index(Emotion::Surprise)] = 0.3;   // §7.4: surprise decays very fast
  auto m = [&](Emotion from, Emotion to, double v) { p.effect[index(from)][index(to)] = v; };
  // Cathexis-style interactions (thesis §5.3.1, §5.6.4 example "happiness reduces the effect of an
  // undesirable event"): values are ours.
  m(Emotion::Joy, Emotion::Distress, 0.3);
  m(Emotion::Distress, Emotion::Joy, 0.3);
  m(Emotion::Fear, Emotion::Joy, 0.2);
  m(Emotion::Fear, Emotion::Hope, 0.2);
  m(Emotion::Hope, Emotion::Fear, 0.2);
  return p;
}

void EmotionParams::validate() const {
  if (!(step_seconds > 0.0 && step_seconds <= 1e9))
    throw InvalidInput("step_seconds must be in (0, 1e9] seconds");
  check_unit(low_intensity_rate, "low_intensity_rate");
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    const std::string name(kEmotionNames[i]);
    if (!(omega[i] > 0.0 && std::isfinite(omega[i]))) throw InvalidInput("omega of " + name + " must be > 0");
    if (!(alpha[i] >= 0.0 && alpha[i] <= omega[i])) throw InvalidInput("alpha of " + name + " must be in [0, omega]");
    check_unit(decay[i], "decay of " + name);
    double col = 0.0;
    for (std::size_t j = 0; j < kEmotionCount; ++j) {
      const double v = effect[j][i];
      if (!(v >= 0.0 && v <= 1.0))
        throw InvalidInput("M[" + std::string(kEmotionNames[j]) + "][" + name + "] must be in [0,1]");
      col += v;
    }
    // thesis §5.6.4: for all i, 0 ≤ Σ_j M_{j,i} ≤ 1
    if (col > 1.0 + 1e-12) throw InvalidInput("column " + name + " of M sums to " + std::to_string(col) + " > 1");
  }
}

// thesis §5.6.3: Ψ(E_{i,t+1}) = Φ(E_i, personality)·E_{i,t}; Φ = decayFactor(E_i)·feelingLevel as
// printed (Product), or decayFactor^(1.5−feelingLevel) (Power, default; docs/parlee.md).
EmotionVector decay_multipliers(const EmotionParams& params, const Personality& p) {
  EmotionVector out{};
  const double fl = p[Trait::FeelingLevel];
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    out[i] = params.decay_model == DecayModel::Power ? std::pow(params.decay[i], 1.5 - fl)
                                                     : std::min(1.0, params.decay[i] * fl);
  }
  return out;
}

EmotionVector decay_rates(const EmotionParams& params, const EmotionVector& decay_multiplier) {
  EmotionVector k{};
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    const double phi = decay_multiplier[i];
    k[i] = phi <= 0.0 ? std::numeric_limits<double>::infinity()
                      : (phi >= 1.0 ? 0.0 : -std::log(phi) / params.step_seconds);
  }
  return k;
}

// thesis §5.6.3 read per second with the intensity dependence it states (docs/parlee.md, "Decay per
// second"): dE/dt = −aE − bE², a = r·k, b = (1 − r)·k/ω. With u = 1/E, du/dt = a·u + b, so
// u(t) = (u0 + b/a)·e^(at) − b/a, i.e. E(t) = E0·e^(−at) / (1 + (b·E0/a)·(1 − e^(−at))).
EmotionVector decayed(const EmotionVector& e, const EmotionParams& params,
                      const EmotionVector& decay_multiplier, double dt_seconds) {
  if (!(dt_seconds >= 0.0) || !std::isfinite(dt_seconds))
    throw InvalidInput("decayed: elapsed time must be finite and >= 0 seconds");
  EmotionVector out{};
  const double r = params.low_intensity_rate;
  const double steps = dt_seconds / params.step_seconds;
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    const double e0 = e[i], phi = decay_multiplier[i];
    if (e0 <= 0.0 || dt_seconds == 0.0 || phi >= 1.0) {
      out[i] = std::max(0.0, e0);
      continue;
    }
    if (phi <= 0.0) {  // no persistence at all: gone after any positive time
      out[i] = 0.0;
      continue;
    }
    const double ln_phi = std::log(phi);  // = −k·step_seconds
    // e^(−aΔt) = Φ^(r·Δt/step); r = 1 keeps pow(Φ, steps) exactly (one step: Φ·E)
    const double fall = r == 1.0 ? std::pow(phi, steps) : std::exp(r * ln_phi * steps);
    if (r == 1.0) {
      out[i] = e0 * fall;
      continue;
    }
    // in steps (the result then depends on Δt/step_seconds only): (1 − e^(−aΔt))/a → Δt as a → 0
    const double a = -r * ln_phi;
    const double g = r > 0.0 ? -std::expm1(r * ln_phi * steps) / a : steps;
    const double b = -(1.0 - r) * ln_phi / params.omega[i];
    out[i] = e0 * fall / (1.0 + b * e0 * g);
  }
  return out;
}

// thesis §5.6.4
void update_decayed_emotions(EmotionVector& e, const EmotionVector& decayed,
                             const EmotionVector& impulse, const EmotionParams& params,
                             const EmotionVector& alpha) {
  EmotionVector s_over_omega{};
  bool any_active = false;
  for (std::size_t j = 0; j < kEmotionCount; ++j) {
    if (e[j] >= alpha[j] && e[j] > 0.0) {
      s_over_omega[j] = e[j] / params.omega[j];
      any_active = true;
    }
  }
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    double damp = 0.0;
    if (any_active && impulse[i] > 0.0)
      for (std::size_t j = 0; j < kEmotionCount; ++j) damp += s_over_omega[j] * params.effect[j][i];
    const double in = impulse[i] > 0.0 ? impulse[i] * (1.0 - std::min(1.0, damp)) : 0.0;
    e[i] = std::min(params.omega[i], std::max(0.0, decayed[i] + in));
  }
}

void update_emotions(EmotionVector& e, const EmotionVector& impulse, const EmotionParams& params,
                     const EmotionVector& alpha, const EmotionVector& decay_multiplier) {
  EmotionVector psi{};
  for (std::size_t i = 0; i < kEmotionCount; ++i) psi[i] = decay_multiplier[i] * e[i];
  update_decayed_emotions(e, psi, impulse, params, alpha);
}

std::array<bool, kEmotionCount> active(const EmotionVector& e, const EmotionVector& alpha) {
  std::array<bool, kEmotionCount> out{};
  for (std::size_t i = 0; i < kEmotionCount; ++i) out[i] = e[i] >= alpha[i] && e[i] > 0.0;
  return out;
}

void MotivationalState::validate() const {
  check_unit(hunger, "hunger");
  check_unit(fatigue, "fatigue");
  check_unit(thirst, "thirst");
  check_unit(pain, "pain");
}

void MotivationOptions::validate() const {
  check_unit(fatigue_gain, "MotivationOptions::fatigue_gain");
  check_unit(pain_gain, "MotivationOptions::pain_gain");
  if (!(hunger_gain >= 0.0 && hunger_gain <= 4.0)) throw InvalidInput("MotivationOptions::hunger_gain must be in [0,4]");
  if (!(thirst_gain >= 0.0 && thirst_gain <= 4.0)) throw InvalidInput("MotivationOptions::thirst_gain must be in [0,4]");
  check_unit(action_cost, "MotivationOptions::action_cost");
  check_unit(hit_pain, "MotivationOptions::hit_pain");
}

// thesis §5.5.4
EmotionVector motivated_alpha(const EmotionParams& params, const MotivationalState& m,
                              const MotivationOptions& o) {
  EmotionVector out{};
  for (std::size_t i = 0; i < kEmotionCount; ++i) {
    const auto e = static_cast<Emotion>(i);
    double f = 1.0 + o.hunger_gain * m.hunger + o.thirst_gain * m.thirst;
    const Valence v = valence(e);
    if (v == Valence::Negative) f -= o.fatigue_gain * m.fatigue;
    if (v == Valence::Positive) f += o.fatigue_gain * m.fatigue;
    if (e == Emotion::Fear) f -= o.pain_gain * m.pain;
    out[i] = std::clamp(params.alpha[i] * std::max(0.0, f), 0.0, params.omega[i]);
  }
  return out;
}

std::string_view to_string(BodyEvent e) {
  static constexpr std::array<std::string_view, 5> kNames{"action", "eat", "drink", "rest", "hit"};
  return kNames.at(static_cast<std::size_t>(e));
}

std::string_view to_string(Need n) {
  switch (n) {
    case Need::Hunger:
      return "hunger";
    case Need::Fatigue:
      return "fatigue";
    case Need::Thirst:
      return "thirst";
    case Need::Pain:
      return "pain";
  }
  return "hunger";
}

Need need_from_string(std::string_view s) {
  for (Need n : {Need::Hunger, Need::Fatigue, Need::Thirst, Need::Pain})
    if (to_string(n) == s) return n;
  throw InvalidInput("unknown motivational variable '" + std::string(s) +
                     "' (hunger, fatigue, thirst, pain)");
}

double level(const MotivationalState& m, Need n) {
  switch (n) {
    case Need::Hunger:
      return m.hunger;
    case Need::Fatigue:
      return m.fatigue;
    case Need::Thirst:
      return m.thirst;
    case Need::Pain:
      return m.pain;
  }
  return 0.0;
}

BodyEvent body_event_from_string(std::string_view s) {
  for (auto e : {BodyEvent::Action, BodyEvent::Eat, BodyEvent::Drink, BodyEvent::Rest, BodyEvent::Hit})
    if (to_string(e) == s) return e;
  throw InvalidInput("unknown body event '" + std::string(s) + "' (action, eat, drink, rest, hit)");
}

void update_motivation(MotivationalState& m, BodyEvent event, const MotivationOptions& o) {
  auto up = [](double& v, double d) { v = std::clamp(v + d, 0.0, 1.0); };
  switch (event) {
    case BodyEvent::Action:
      up(m.hunger, o.action_cost);
      up(m.fatigue, o.action_cost);
      up(m.thirst, o.action_cost);
      break;
    case BodyEvent::Eat: m.hunger = 0.0; break;
    case BodyEvent::Drink: m.thirst = 0.0; break;
    case BodyEvent::Rest: m.fatigue = 0.0; m.pain = 0.0; break;
    case BodyEvent::Hit: up(m.pain, o.hit_pain); break;
  }
}

std::array<double, 6> basic_emotions(const EmotionVector& e, const EmotionParams& params) {
  struct Contribution {
    std::size_t basic;
    Emotion emotion;
    double weight;
  };
  // docs/parlee.md "Mapping to the six basic emotions": OCC types grouped by Ekman category.
  static constexpr Contribution kMap[] = {
      {0, Emotion::Distress, 1.0},      {0, Emotion::Disappointment, 1.0}, {0, Emotion::SorryFor, 0.8},
      {0, Emotion::FearsConfirmed, 0.8}, {0, Emotion::Remorse, 0.7},       {0, Emotion::Shame, 0.6},
      {1, Emotion::Joy, 1.0},           {1, Emotion::Satisfaction, 1.0},   {1, Emotion::Gratification, 1.0},
      {1, Emotion::Relief, 0.8},        {1, Emotion::HappyFor, 0.8},       {1, Emotion::Gratitude, 0.8},
      {1, Emotion::Pride, 0.7},         {1, Emotion::Gloating, 0.6},       {1, Emotion::Appreciation, 0.5},  {2, Emotion::Anger, 1.0},          {2, Emotion::Resentment, 0.8},
      {2, Emotion::Reproach, 0.7},      {3, Emotion::Fear, 1.0},           {3, Emotion::FearsConfirmed, 0.5},
      {4, Emotion::Reproach, 0.5},      {4, Emotion::Resentment, 0.5},     {5, Emotion::Surprise, 1.0},
  };
  std::array<double, 6> out{};
  for (const auto& c : kMap) {
    const std::size_t i = index(c.emotion);
    // only the part above the activation threshold shows (moods do not, §5.5.2)
    const double span = params.omega[i] - params.alpha[i];
    const double x = span > 0.0 ? (e[i] - params.alpha[i]) / span : (e[i] >= params.omega[i] ? 1.0 : 0.0);
    out[c.basic] = std::max(out[c.basic], std::clamp(c.weight * x, 0.0, 1.0));
  }
  return out;
}

}  // namespace emoface::parlee
