#pragma once
// Visual speech by the Cohen–Massaro dominance model (thesis §4.5.1): every viseme segment has,
// per parameter, a dominance Δ(τ) = α·exp(−θ·|τ|^c) around its centre; the activity is the
// dominance-weighted average of the viseme targets.
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "emoface/channels/channel.hpp"

namespace emoface::channels {

/// Dominance parameters of one parameter in one viseme (thesis §4.5.1).
struct Dominance {
  double alpha = 1.0;               ///< magnitude α > 0
  double theta_anticipatory = 0.35; ///< θ← > 0, rate before the peak (τ >= 0), per time unit
  double theta_carryover = 0.35;    ///< θ→ > 0, rate after the peak (τ < 0), per time unit
  double c = 1.0;                   ///< exponent c > 0
  double peak_offset = 0.0;         ///< To, seconds: peak of dominance relative to the segment centre
  void validate() const;            ///< throws InvalidInput for non-finite or out-of-range values
};

/// A viseme: target values for the lip parameters and their dominance functions.
struct Viseme {
  std::string name;
  std::vector<Target> targets;                        ///< parameters not listed have target 0
  Dominance dominance;                                ///< default for every parameter
  std::map<std::string, Dominance> per_parameter;     ///< overrides for single parameters
  const Dominance& dominance_of(std::string_view parameter) const;
  double target_of(std::string_view parameter) const;
};

/// The viseme inventory plus the phoneme → viseme table (data/channels/visemes.json).
struct VisemeSet {
  std::vector<Viseme> visemes;
  std::map<std::string, std::string> phoneme_to_viseme;  ///< espeak-ng phoneme mnemonic → viseme name
  std::string silence = "sil";                           ///< viseme used for pauses and unknown phonemes

  /// Throws InvalidInput if names repeat, the silence viseme or a mapped viseme is missing,
  /// a target is unknown / not finite, or a dominance is invalid.
  void validate() const;
  /// The viseme with this name, or nullptr.
  const Viseme* find(std::string_view name) const;
  /// Viseme name of a phoneme: exact match in phoneme_to_viseme, then a viseme of that name
  /// (viseme-level timings), then the phoneme without trailing length/stress marks (":", ";", "#"),
  /// then `silence`.
  const std::string& viseme_for_phoneme(std::string_view phoneme) const;
  /// Union of all viseme target parameters, in first-use order.
  std::vector<std::string> parameters() const;
};

/// The built-in viseme set (same content as data/channels/visemes.json): 15 visemes (silence plus
/// 14 classes of English espeak-ng phonemes) with hand-set targets and dominance parameters; see
/// docs/channels.md for where the numbers come from.
VisemeSet default_viseme_set();

/// A lip movement Γl = ((PV_i), Ts, Te, Da) (thesis §4.4): one viseme segment.
struct LipSegment {
  std::string viseme;   ///< a name in the VisemeSet
  double start = 0.0;   ///< Ts, seconds
  double end = 0.1;     ///< Te > Ts, seconds
  double apex = 0.0;    ///< Da, seconds, in [0, Te − Ts]: the dominance stays at α for Da around the peak
  std::string label;    ///< diagnostics, e.g. the phoneme
};

struct CoarticulationOptions {
  /// Seconds per unit of τ in Δ(τ) = α·exp(−θ|τ|^c) (default 0.01 s, > 0). The thesis does not give
  /// the unit; with centiseconds its Fig. 4.4 values (θ = 0.35, c = 1, 100 ms segments) give the
  /// gradual transition it shows (see docs/channels.md).
  double time_unit = 0.01;
  /// Dominance of the rest position (target 0 for every parameter, constant in time), in (0, 0.01]
  /// (default 1e-4). Not in the thesis: with it the lips return smoothly to rest far from any
  /// segment, where otherwise the slowest-decaying viseme would take over; inside speech it biases
  /// the average by at most rest_dominance/α.
  double rest_dominance = 1e-4;
  /// A segment is ignored where its dominance is below cutoff·rest_dominance, in (0, 0.1]
  /// (default 1e-3); bounds the cost per sample, the error it makes is below cutoff·|target|.
  double cutoff = 1e-3;
  void validate() const;
};

/// The lip channel of an utterance: dominance-weighted average of viseme targets (thesis §4.5.1),
/// plus the rest position (CoarticulationOptions::rest_dominance), so the activity fades to 0 away
/// from the segments.
class Coarticulation {
 public:
  Coarticulation() = default;
  /// Segments must be sorted by start, not overlap (Ts_{k+1} >= Te_k − 1e-9) and name visemes of
  /// `visemes`; otherwise throws InvalidInput.
  Coarticulation(const VisemeSet& visemes, std::vector<LipSegment> segments,
                 CoarticulationOptions options = {});

  const std::vector<std::string>& parameters() const noexcept { return parameters_; }
  const std::vector<LipSegment>& segments() const noexcept { return segments_; }
  int parameter_index(std::string_view parameter) const;

  /// Dominance Δ^m_p(t) of segment m for parameters()[p] (thesis §4.5.1).
  double dominance(std::size_t m, std::size_t p, double t) const;
  /// F_p(t) = Σ Δ^m_p(t)·PV^m_p / (Σ Δ^m_p(t) + rest_dominance) over the segments in reach
  /// (thesis §4.5.1, plus the rest term).
  double value(std::size_t p, double t) const;
  double value(std::string_view parameter, double t) const;
  /// Samples parameters()[p] at t0 + i/fps, i < n.
  void sample(std::size_t p, double t0, double fps, std::size_t n, double* out) const;

 private:
  struct Slot {  // per segment × parameter
    double target, log_alpha, theta_ant, theta_carry, c, peak, half_apex, reach;
  };
  double average(std::size_t p, double t, std::size_t lo, std::size_t hi, std::vector<double>& ld) const;

  std::vector<LipSegment> segments_;
  std::vector<std::string> parameters_;
  std::unordered_map<std::string, std::size_t> index_;
  std::vector<Slot> slots_;           // segments × parameters
  std::vector<double> max_reach_;     // per parameter, seconds
  CoarticulationOptions options_;
};

}  // namespace emoface::channels
