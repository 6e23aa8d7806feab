#pragma once
// Text → phonemes with timing and synthesized speech, through libespeak-ng (thesis §4.2: text to
// phoneme segments and speech synthesis). espeak-ng keeps global state: calls are serialised, and
// its output depends on what it synthesized before in the same process (the first utterance of a
// process is always the same; later ones vary by a few percent in timing). A fresh process given
// the same script therefore produces byte-identical output, which is what the CLI relies on.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/channels/script.hpp"

namespace emoface::channels {

struct SpeechOptions {
  std::string voice = "en-us";  ///< an espeak-ng voice name
  int rate = 160;               ///< words per minute, in [80, 450]
  int pitch = 50;               ///< espeak-ng pitch, in [0, 99]
  void validate() const;        ///< throws InvalidInput
};

/// One synthesized utterance: 16-bit mono PCM and its phonemes (seconds from the first sample).
struct Utterance {
  int sample_rate = 22050;
  std::vector<std::int16_t> samples;
  std::vector<PhonemeTiming> phonemes;  ///< contiguous; the last ends at samples.size()/sample_rate
  double duration() const noexcept { return static_cast<double>(samples.size()) / sample_rate; }
};

/// Synthesizes `text` (UTF-8). Pauses ("_", "_:") are kept as phonemes (they map to silence).
/// Throws InvalidInput for empty/invalid text or options, Error if espeak-ng fails (e.g. voice or
/// data missing).
Utterance synthesize(std::string_view text, const SpeechOptions& options = {});

/// Places utterances at their start times (seconds) on one silent track of `sample_rate`.
/// Throws InvalidInput if they overlap or rates differ.
std::vector<std::int16_t> place_utterances(const std::vector<Utterance>& utterances,
                                           const std::vector<double>& start_times, int sample_rate,
                                           double min_duration = 0.0);

/// A RIFF/WAVE file (PCM, 16-bit, mono) as bytes.
std::string format_wav(const std::vector<std::int16_t>& samples, int sample_rate);
/// Writes format_wav atomically.
void write_wav(const std::string& path, const std::vector<std::int16_t>& samples, int sample_rate);

}  // namespace emoface::channels
