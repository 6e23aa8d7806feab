#pragma once
// Mood update (paper §6, eqs. 2–4) and mood decay towards the personality (§6). Plain functions on
// arrays with one entry per emotion node; all values are in [0, 1]. Allocation-free: these are the hot
// path of a crowd simulation (tests/bench/mindmap_bench.cpp).
#include <cstddef>
#include <optional>
#include <string_view>

#include "emoface/mindmap/mind_map.hpp"

namespace emoface::mindmap {

/// Eq. 4 comes in two readings (../shared/seeds/README.md): the text calls the update "a simple sum of
/// all properties", the printed formula takes the absolute value of a difference.
enum class MoodForm {
  Sum,      ///< mood' = clamp((1−β)·mood + β·(α·Stimulus + (1−α)·PTraits), 0, 1)  (default)
  Printed,  ///< mood' = clamp(|(1−β)·mood − β·(α·Stimulus + (1−α)·PTraits)|, 0, 1)
};
std::string_view to_string(MoodForm form);
/// "sum" | "printed"; nullopt otherwise.
std::optional<MoodForm> mood_form_from_string(std::string_view name);

/// Eq. 2: Stimulus = (1−λ)·ActionEmot + λ·Affect. `affect` may be null (no affection row towards the
/// source, or a world stimulus): then Stimulus = ActionEmot. `out` may alias `action_emot`.
void perceived_stimulus(const double* action_emot, const double* affect, double lambda, double* out,
                        std::size_t n) noexcept;

/// Eq. 3: PTraits = (Personality + BGContext) / 2. `background` may be null (no background context):
/// then PTraits = Personality.
void personality_traits(const double* personality, const double* background, double* out,
                        std::size_t n) noexcept;

/// Eq. 4 for one emotion node (see MoodForm).
double updated_mood(double mood, double stimulus, double ptraits, double alpha, double beta,
                    MoodForm form) noexcept;

/// Eq. 4 for all nodes: mood[i] = updated_mood(mood[i], stimulus[i], ptraits[i], α, β, form).
void update_mood(double* mood, const double* stimulus, const double* ptraits, double alpha,
                 double beta, MoodForm form, std::size_t n) noexcept;

/// Fraction of the way from the mood after an update to the personality, as a function of the
/// normalised elapsed time s = elapsed / duration (clamped to [0, 1]); 0 at s = 0, 1 at s = 1,
/// monotone. Linear: s. Quadratic: s². Sigmoid: the logistic 1/(1+e^{−k(s−½)}) rescaled so that it
/// passes through (0, 0) and (1, 1); k = `steepness` (> 0).
double decay_fraction(DecayCurve curve, double s, double steepness = 10.0) noexcept;

/// mood(t) = start + (target − start)·decay_fraction(curve, elapsed/duration) for each node.
/// `elapsed` ≥ 0 seconds since the update, `duration` > 0 seconds.
void decayed_mood(const double* start, const double* target, double elapsed, double duration,
                  DecayCurve curve, double steepness, double* out, std::size_t n) noexcept;

}  // namespace emoface::mindmap
