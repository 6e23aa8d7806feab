#pragma once
// The whole talking-head pipeline of thesis Fig. 4.1: marked-up text → phonemes (a SpeechSynthesizer:
// the espeak-ng program by default, or external timings with the user's audio) →
// visemes → channels → combined parameter tracks, plus the synthesized speech on the same clock.
#include <cstdint>
#include <memory>
#include <vector>

#include "emoface/channels/conflicts.hpp"
#include "emoface/channels/dominance.hpp"
#include "emoface/channels/mixer.hpp"
#include "emoface/channels/script.hpp"
#include "emoface/channels/speech.hpp"

namespace emoface::channels {

struct TalkingHeadOptions {
  SpeechOptions speech;      ///< the espeak-ng program's voice, rate, pitch (when no synthesizer)
  /// Where speech comes from; null = EspeakProgram(speech).
  std::shared_ptr<const SpeechSynthesizer> synthesizer;
  TimelineOptions timeline;
  RenderOptions render;      ///< fps, output parameters, mixing and coarticulation options
  std::uint64_t seed = 0;    ///< seeds blinks and gaze/head noise
  void validate() const;
};

struct TalkingHead {
  Timeline timeline;
  Tracks tracks;
  int sample_rate = 22050;
  /// Mono 16-bit speech, exactly round(duration·sample_rate) samples where duration is the time of
  /// the last frame, so audio and tracks end together (silence where nothing is said).
  std::vector<std::int16_t> audio;
};

/// Runs the pipeline. Script errors are FormatError with line/column.
TalkingHead run_talking_head(const Script& script, const VisemeSet& visemes, const ConflictTable& conflicts,
                             const EmotionMapper& mapper, const TalkingHeadOptions& options);

}  // namespace emoface::channels
