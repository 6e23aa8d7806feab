#pragma once
// Parameter tracks and the combination of movements from different channels (thesis §4.6).
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/channels/channel.hpp"
#include "emoface/channels/conflicts.hpp"
#include "emoface/channels/dominance.hpp"

namespace emoface::channels {

/// Parameter values sampled at a fixed frame rate: frame f is at time f / fps seconds.
struct Tracks {
  double fps = 100.0;              ///< frames per second, > 0
  std::vector<std::string> names;  ///< one per column, unique
  std::vector<double> values;      ///< frames × names.size(), row-major

  std::size_t frames() const noexcept { return names.empty() ? 0 : values.size() / names.size(); }
  double time(std::size_t frame) const noexcept { return static_cast<double>(frame) / fps; }
  double at(std::size_t frame, std::size_t column) const { return values[frame * names.size() + column]; }
  /// Column of `name`, or -1.
  int column(std::string_view name) const;
  /// The column of `name` as a vector over frames; throws InvalidInput for an unknown name.
  std::vector<double> series(std::string_view name) const;
  /// Throws InvalidInput unless fps > 0 and finite, names are unique and non-empty, values.size()
  /// is a multiple of names.size() and every value is finite.
  void validate() const;
};

struct MixOptions {
  /// Dmin+ (§4.6): minimum onset duration for a parameter to activate completely after an
  /// inhibition, seconds, > 0 (default 0.5; the thesis gives no value).
  double dmin_plus = 0.5;
  /// Dmin− (§4.6): minimum offset duration for a parameter to release completely before an
  /// inhibition, seconds, > 0 (default 0.3; Fig. 4.8 releases ~4 frames before the conflict).
  double dmin_minus = 0.3;
  /// A parameter counts as "activated" when |activity| exceeds this, in (0, 1) (default 0.05: the
  /// dominance-weighted lip tracks never reach exactly 0, their tails stay below it).
  double active_threshold = 0.05;
  /// Priority per channel (index = Channel), smaller = higher priority (default thesis order 1..6).
  std::array<int, kChannelCount> priority = {1, 2, 3, 4, 5, 6};
  void validate() const;
};

/// The sampled activity of one channel: values are parameters × frames, row-major.
struct ChannelSamples {
  Channel channel = Channel::EmotionDisplay;
  std::vector<std::string> parameters;
  std::vector<double> values;
  /// Optional, one per frame: the channel's priority at that frame (per-movement priority, §4.1),
  /// smaller = higher; empty = MixOptions::priority of the channel at every frame.
  std::vector<int> frame_priority;
};

/// Cross-channel combination (thesis §4.6). For each parameter p of each channel c (taken in
/// priority order): p is inhibited (aF = 0) at frames where a parameter conflicting with p is
/// activated in a higher-priority channel (using that channel's already modified activity);
/// elsewhere aF = min(F, Ψ←, Ψ→) with Ψ←(t) = φ+(t − T←, Dmin+) after the last inhibited frame T←
/// and Ψ→(t) = φ−(Dmin− − (T→ − t), Dmin−) before the next one T→. The output is the maximum over
/// channels (for the signed gaze/head angles: the value of largest magnitude). Every channel
/// parameter must be in `parameters`; every channel has `frames` samples per parameter.
/// If `modified` is given it receives the aF of every channel (same layout as `channels`).
/// With per-frame priorities (ChannelSamples::frame_priority) "higher priority" is decided frame by
/// frame; the inhibitions are then found by fixed-point iteration (each pass uses the previous
/// pass's aF of the other channels; at most 2·channels passes), which gives the plain result when
/// the per-frame priorities equal the channels' priorities.
Tracks mix(const std::vector<ChannelSamples>& channels, const std::vector<std::string>& parameters,
           double fps, std::size_t frames, const ConflictTable& conflicts, const MixOptions& options,
           std::vector<ChannelSamples>* modified = nullptr);

/// Everything the face does over time, before sampling.
struct Timeline {
  /// Atomic movements per channel (index = Channel), each list in channel order (§4.5.2).
  /// movements[Lip] must be empty: lip movements are `lip` segments.
  std::array<std::vector<Movement>, kChannelCount> movements;
  std::vector<LipSegment> lip;  ///< viseme segments, sorted, not overlapping
  /// Latest end time of any movement or segment, seconds (0 if empty).
  double end_time() const;
};

struct RenderOptions {
  double fps = 100.0;       ///< frames per second, in (0, 10000]
  double duration = 0.0;    ///< seconds of output; 0 = Timeline::end_time() (>= 0)
  std::vector<std::string> parameters;  ///< output columns; empty = default_parameter_names()
  MixOptions mix;
  CoarticulationOptions coarticulation;
  void validate() const;
};

/// Samples every channel (§4.5.1 for the lip channel, §4.5.2 for the others) and mixes them (§4.6).
/// Frames cover [0, duration] (floor(duration·fps) + 1 frames).
Tracks render(const Timeline& timeline, const VisemeSet& visemes, const ConflictTable& conflicts,
              const RenderOptions& options);

}  // namespace emoface::channels
