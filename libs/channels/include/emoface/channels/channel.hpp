#pragma once
// The six animation channels (thesis §4.2) and the concatenation of the movements inside one
// channel (thesis §4.5.2).
#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "emoface/channels/curves.hpp"

namespace emoface::channels {

/// The six channels of thesis §4.2, in their default priority order (first = highest priority).
enum class Channel {
  Manipulator,           ///< channel 1: eye blinks
  Lip,                   ///< channel 2: lip movements when talking (visemes)
  ConversationalSignal,  ///< channel 3
  EmotionDisplay,        ///< channel 4: emotion displays and emotion emblems
  Gaze,                  ///< channel 5
  Head,                  ///< channel 6
};
inline constexpr std::size_t kChannelCount = 6;

/// "manipulator", "lip", "conversational_signal", "emotion_display", "gaze", "head".
std::string_view to_string(Channel channel) noexcept;
/// Inverse of to_string; throws InvalidInput for an unknown name.
Channel channel_from_string(std::string_view name);

/// One parameter target of a movement: the value PV_p the parameter reaches at the apex.
struct Target {
  std::string parameter;  ///< a parameter name (parameters.hpp)
  double value = 0.0;     ///< contraction in [0,1] or angle in radians
};

/// An atomic movement Γo = ((PV_i), Ts, Te, Do, Dr) (thesis §4.4).
struct Movement {
  std::vector<Target> targets;  ///< parameters not listed have target 0
  Timing timing;
  std::string label;            ///< free text for diagnostics (e.g. "EMOTIONDISPLAY line 3")
  /// §4.1 per-movement priority: 0 = its channel's (MixOptions::priority); otherwise this
  /// movement's own priority while it lasts (Ts ≤ t ≤ Te), smaller = higher — "the smile may also
  /// have higher priority than the visual speech when the subject is too happy". Range [0, 100].
  int priority = 0;
};

/// The movements of one channel, concatenated as in thesis §4.5.2: the activity follows movement k
/// until movement k+1 starts; then, if movement k+1 overlaps movement k, it rises with φ+(·, Do_{k+1})
/// (case 1) or falls with φ+(·, Dr_k) (case 2, seeds README reading) from its current value until it
/// meets the target of movement k+1, and then follows movement k+1. Non-overlapping movements follow
/// their own activity (§4.4). The result is continuous in time for every parameter.
class ConcatenatedChannel {
 public:
  ConcatenatedChannel() = default;
  /// Sorts nothing: `movements` must be in channel order, i.e. Ts_{k+1} > Ts_k and Te_{k+1} > Te_k
  /// (thesis §4.5.2); otherwise throws InvalidInput naming both labels. Each timing is validated.
  explicit ConcatenatedChannel(std::vector<Movement> movements);

  const std::vector<Movement>& movements() const noexcept { return movements_; }
  /// Names of every parameter some movement targets, in first-use order.
  const std::vector<std::string>& parameters() const noexcept { return parameters_; }
  /// Index of `parameter` in parameters(), or -1.
  int parameter_index(std::string_view parameter) const;

  /// Activity of parameters()[p] at time t (seconds).
  double value(std::size_t p, double t) const;
  /// Activity of a named parameter (0 for parameters the channel does not touch).
  double value(std::string_view parameter, double t) const;

  /// Samples parameters()[p] at times t0 + i/fps, i < n, into out[i] (faster than value() in a loop).
  void sample(std::size_t p, double t0, double fps, std::size_t n, double* out) const;

 private:
  double value_in(std::size_t p, std::size_t k, double t) const;

  std::vector<Movement> movements_;
  std::vector<std::string> parameters_;
  std::unordered_map<std::string, std::size_t> index_;
  std::vector<double> targets_;      // movements × parameters, row-major
  std::vector<double> start_value_;  // F_{<k}(Ts_k) per movement × parameter
  std::vector<char> overlaps_;       // movement k starts before movement k−1 ends
};

}  // namespace emoface::channels
