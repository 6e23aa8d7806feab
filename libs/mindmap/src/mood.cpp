#include "emoface/mindmap/mood.hpp"

#include <algorithm>
#include <cmath>

namespace emoface::mindmap {

std::string_view to_string(MoodForm form) { return form == MoodForm::Printed ? "printed" : "sum"; }

std::optional<MoodForm> mood_form_from_string(std::string_view name) {
  if (name == "sum") return MoodForm::Sum;
  if (name == "printed") return MoodForm::Printed;
  return std::nullopt;
}

// paper §6, eq. 2: Stimulus = (1 − λ)·ActionEmot + λ·Affect
void perceived_stimulus(const double* action_emot, const double* affect, double lambda, double* out,
                        std::size_t n) noexcept {
  if (!affect) {
    if (out != action_emot) std::copy(action_emot, action_emot + n, out);
    return;
  }
  for (std::size_t i = 0; i < n; ++i) out[i] = (1.0 - lambda) * action_emot[i] + lambda * affect[i];
}

// paper §6, eq. 3: PTraits = (Personality + BGContext) / 2
void personality_traits(const double* personality, const double* background, double* out,
                        std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i)
    out[i] = background ? 0.5 * (personality[i] + background[i]) : personality[i];
}

// paper §6, eq. 4, in the reading of ../shared/seeds/README.md (sum by default, printed |…| optional)
double updated_mood(double mood, double stimulus, double ptraits, double alpha, double beta,
                    MoodForm form) noexcept {
  const double drive = beta * (alpha * stimulus + (1.0 - alpha) * ptraits);
  const double v = form == MoodForm::Sum ? (1.0 - beta) * mood + drive
                                         : std::fabs((1.0 - beta) * mood - drive);
  return std::clamp(v, 0.0, 1.0);
}

void update_mood(double* mood, const double* stimulus, const double* ptraits, double alpha,
                 double beta, MoodForm form, std::size_t n) noexcept {
  for (std::size_t i = 0; i < n; ++i)
    mood[i] = updated_mood(mood[i], stimulus[i], ptraits[i], alpha, beta, form);
}

// paper §6: "the dynamics of the variation are controlled by a curve that can be e.g. linear,
// quadratic or sigmoid" — the curve shapes are ours (docs/mindmap.md).
double decay_fraction(DecayCurve curve, double s, double steepness) noexcept {
  if (!(s > 0.0)) return 0.0;
  if (s >= 1.0) return 1.0;
  switch (curve) {
    case DecayCurve::Linear: return s;
    case DecayCurve::Quadratic: return s * s;
    case DecayCurve::Sigmoid: {
      const double lo = 1.0 / (1.0 + std::exp(0.5 * steepness));
      const double hi = 1.0 - lo;
      const double v = 1.0 / (1.0 + std::exp(-steepness * (s - 0.5)));
      return std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
    }
  }
  return s;
}

void decayed_mood(const double* start, const double* target, double elapsed, double duration,
                  DecayCurve curve, double steepness, double* out, std::size_t n) noexcept {
  const double f = decay_fraction(curve, elapsed / duration, steepness);
  if (f >= 1.0) {
    std::copy(target, target + n, out);  // exactly the personality once the decay is over
    return;
  }
  for (std::size_t i = 0; i < n; ++i) out[i] = start[i] + (target[i] - start[i]) * f;
}

}  // namespace emoface::mindmap
