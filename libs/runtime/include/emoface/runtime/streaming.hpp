#pragma once
// Streaming forms of the channel machinery of thesis ch. 4, for a character updated frame by frame:
//
//  * StreamingChannel — the in-channel concatenation of §4.5.2 (channels::ConcatenatedChannel) with
//    movements appended while time runs and old ones pruned; for the same movements it gives the
//    same values as ConcatenatedChannel, bit for bit (tested).
//  * StreamingMixer — the cross-channel combination of §4.6 (channels::mix) with a bounded
//  look-ahead:
//    the offline mixer's Ψ→ looks at the next inhibited frame T→, which is only ever needed within
//    Dmin− of t (Ψ→ = 1 beyond it), so a mixer that knows the raw channel activities L frames ahead
//    produces frame f once frame f + L is in: a fixed latency of L/fps seconds. With L/fps ≥ Dmin−
//    (default 0.3 s) it equals the offline mixer whenever the inhibiting (higher-priority) channels
//    are not themselves inhibited near the horizon — true for the thesis examples (blinks and lips
//    inhibit the emotion display; tested frame by frame against channels::mix). Ψ← needs only the
//    time of the last inhibited frame, kept as state.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "emoface/channels/channel.hpp"
#include "emoface/channels/conflicts.hpp"
#include "emoface/channels/mixer.hpp"

namespace emoface::runtime {

/// §4.5.2 concatenation over a growing list of movements (channel order: each appended movement
/// starts and ends later than the previous one).
class StreamingChannel {
 public:
  StreamingChannel() = default;
  /// The parameters the channel may target (unique names).
  explicit StreamingChannel(std::vector<std::string> parameters);

  const std::vector<std::string>& parameters() const noexcept { return parameters_; }
  /// Appends a movement. Throws InvalidInput if it breaks the channel order, targets a parameter
  /// not in parameters() (or one twice), has a non-finite target or an invalid timing.
  void append(const channels::Movement& movement);
  /// Activity of parameters()[p] at t (0 before the first movement), as ConcatenatedChannel::value.
  double value(std::size_t p, double t) const;
  /// All parameters at t into out[0 .. parameters().size()).
  void sample(double t, double* out) const;
  /// Forgets movements that no time >= t needs (the last one is always kept).
  void prune(double t);
  std::size_t size() const noexcept { return items_.size(); }
  /// Start time of the last movement (−inf when empty).
  double last_start() const noexcept;
  /// End time of the last movement (−inf when empty).
  double last_end() const noexcept;

  /// One kept movement with what value() needs from the movements before it.
  struct Item {
    channels::Timing timing;
    std::vector<double> target;       ///< per parameter
    std::vector<double> start_value;  ///< F_{<k}(Ts_k) per parameter
    bool overlaps = false;            ///< starts before the previous movement ended
    double previous_offset = 0.0;     ///< Dr of the previous movement
    double previous_end = 0.0;        ///< Te of the previous movement (−inf: none)
  };
  const std::vector<Item>& items() const noexcept { return items_; }
  /// Rebuilds from items() of another StreamingChannel with the same parameters (snapshots).
  void restore(std::vector<Item> items);

 private:
  double value_in(std::size_t p, const Item& m, double t) const;
  std::vector<std::string> parameters_;
  std::vector<Item> items_;
};

/// Cross-channel combination with a fixed look-ahead (see the top of this header).
class StreamingMixer {
 public:
  StreamingMixer() = default;
  /// `parameters`: output columns; `channel_parameters[c]`: indices into `parameters` that channel
  /// c may drive (others are absent, as in channels::mix). lookahead_frames ≥ 0.
  StreamingMixer(std::vector<std::string> parameters,
                 std::array<std::vector<std::size_t>, channels::kChannelCount> channel_parameters,
                 const channels::ConflictTable& conflicts, const channels::MixOptions& options,
                 double fps, std::size_t lookahead_frames);

  /// Feeds raw frame n = frames_in() (time n/fps): raw[c][i] is channel c's activity of
  /// channel_parameters[c][i]. Once n ≥ lookahead, frame n − lookahead is mixed into output().
  void push(const std::array<const double*, channels::kChannelCount>& raw);
  std::size_t frames_in() const noexcept { return frames_in_; }
  /// Frames mixed so far (= max(0, frames_in − lookahead)).
  std::size_t frames_out() const noexcept;
  /// The last mixed frame (parameters().size() values; zeros before the first one).
  const std::vector<double>& output() const noexcept { return output_; }
  const std::vector<std::string>& parameters() const noexcept { return parameters_; }
  std::size_t lookahead() const noexcept { return lookahead_; }
  double fps() const noexcept { return fps_; }

  /// The state a snapshot needs: the raw ring (frames not yet mixed), T← per channel parameter
  /// (−inf = never inhibited) and the counters; restore() takes it back.
  struct State {
    std::size_t frames_in = 0;
    std::vector<double> ring;  ///< (lookahead+1) frames × all channel parameters
    std::vector<double> last_inhibited;
    std::vector<double> output;
  };
  State state() const;
  void restore(const State& state);  ///< throws InvalidInput on wrong sizes

 private:
  std::vector<std::string> parameters_;
  std::array<std::vector<std::size_t>, channels::kChannelCount> chan_params_;
  std::array<std::size_t, channels::kChannelCount> offset_{};  // of each channel's block in a frame
  std::size_t width_ = 0;                                      // values per raw frame
  std::vector<std::size_t> order_;                             // channels by priority
  std::vector<int> prio_;
  std::vector<std::vector<std::size_t>> conflict_;  // per output parameter
  std::vector<char> is_signed_;
  std::vector<char> has_conflict_;  // per (channel block) entry
  channels::MixOptions options_;
  double fps_ = 60.0;
  std::size_t lookahead_ = 0;
  std::size_t frames_in_ = 0;
  std::vector<double> ring_;      // (lookahead+1) × width_
  std::vector<double> last_inh_;  // per width_ entry
  std::vector<double> output_;
  // scratch (allocation-free push)
  std::vector<double> mod_;   // (lookahead+1) × width_: modified activity in the window
  std::vector<char> active_;  // (lookahead+1) × parameters: activated by higher groups
  std::vector<char> group_active_;
  std::vector<char> inh_;
};

}  // namespace emoface::runtime
