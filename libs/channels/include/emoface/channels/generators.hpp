#pragma once
// Seeded generators of the "lively" movements (thesis §4.2): random eye blinks (channel 1) and
// subtle gaze (channel 5) and head (channel 6) noise. Same options + same Rng state = same output.
#include <string>
#include <vector>

#include "emoface/channels/channel.hpp"
#include "emoface/core/rng.hpp"

namespace emoface::channels {

/// Random eye blinks. The thesis (§4.2) follows Itti et al. (2003) without giving the distribution;
/// we draw inter-blink intervals (start to start) from a shifted exponential,
/// IBI = min_interval + Exp(mean = mean_interval − min_interval): a refractory period, then a
/// constant blink hazard. The default mean of 4 s is about 15 blinks/min, the spontaneous rate of
/// adults in conversation. Each blink closes the eyelids (eye_blink_l/_r, FACS AU45) fast
/// and reopens them more slowly.
struct BlinkOptions {
  double mean_interval = 4.0;  ///< mean inter-blink interval, seconds, > min_interval
  double min_interval = 1.0;   ///< refractory minimum, seconds, >= duration
  double duration = 0.3;       ///< whole blink Te − Ts, seconds, > 0
  double onset = 0.1;          ///< closing time Do, seconds, > 0
  double offset = 0.2;         ///< reopening time Dr, seconds, > 0, onset + offset <= duration
  double closure = 1.0;        ///< eye_blink level at the peak, in (0, 1]
  void validate() const;
};

/// Blinks starting in [begin, end) (a blink may end after `end`); the first starts after one
/// interval drawn from the distribution. Channel order holds (starts and ends increase).
std::vector<Movement> generate_blinks(double begin, double end, const BlinkOptions& options,
                                      core::Rng& rng);

/// Random small fixation shifts of one group of angle parameters, as a chain of overlapping
/// atomic movements (concatenated in the channel, §4.5.2): hold times h = min_hold + Exp(mean_hold
/// − min_hold); each movement moves every parameter to N(0, amplitude²) within `transition`.
struct NoiseOptions {
  double amplitude = 0.02;   ///< standard deviation of the targets, radians, >= 0, <= 0.5
  double mean_hold = 1.5;    ///< mean time between shifts, seconds, > min_hold
  double min_hold = 0.3;     ///< seconds, >= transition
  double transition = 0.08;  ///< onset/offset of each shift, seconds, > 0
  void validate() const;
};

/// Default gaze noise: saccade-like shifts of eye_gaze_yaw/pitch (small amplitude, fast).
NoiseOptions default_gaze_noise();
/// Default head noise: slow drifts of head_yaw/pitch/roll.
NoiseOptions default_head_noise();

/// Noise movements for `parameters` covering [begin, end].
std::vector<Movement> generate_noise(double begin, double end, const std::vector<std::string>& parameters,
                                     const NoiseOptions& options, core::Rng& rng,
                                     const std::string& label = "noise");

/// Adds the generated movements to `explicit_movements` (both in channel order): a generated
/// movement is kept only if it does not overlap any explicit one (with `margin` seconds around
/// it). Returns the merged list in channel order.
std::vector<Movement> merge_generated(std::vector<Movement> explicit_movements,
                                      const std::vector<Movement>& generated, double margin);

}  // namespace emoface::channels
