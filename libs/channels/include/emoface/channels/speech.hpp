#pragma once
// Speech for the lip channel (thesis §4.2, Fig. 4.1: text → phoneme segments with timing + speech
// audio) behind an interface, so that no emoface library links a speech engine:
//
//  * EspeakProgram runs the `espeak-ng` *program* (GPL-3.0) as a separate process, never the
//    library: `espeak-ng -q -x` prints the phoneme mnemonics (one line per clause) and
//    `espeak-ng -z --stdout` the 16-bit PCM speech. Debian's espeak-ng 1.51 prints no phoneme
//    timing for its own voices (`--pho` needs an MBROLA voice, which Debian does not ship), so the
//    phonemes are placed on the audio by align_phonemes(): espeak-ng writes exact digital silence
//    for pauses and stop closures, which anchor the pauses and the stops; the rest is spread by
//    nominal phoneme durations (docs/channels.md, "Speech backends", has the measured error).
//    A fresh process per utterance: the same text and options always give the same output.
//  * ExternalSpeech takes phoneme or viseme timings from any TTS or aligner, with the user's own
//    audio (timing_io.hpp reads emoface's TSV/JSON timing files and Rhubarb Lip Sync's TSV/JSON).
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/channels/script.hpp"

namespace emoface::channels {

struct SpeechOptions {
  std::string voice = "en-us";        ///< an espeak-ng voice name
  int rate = 160;                     ///< words per minute, in [80, 450]
  int pitch = 50;                     ///< espeak-ng pitch, in [0, 99]
  std::string program = "espeak-ng";  ///< the espeak-ng executable (looked up on PATH)
  void validate() const;              ///< throws InvalidInput
};

/// One utterance: 16-bit mono PCM and its phonemes (seconds from the first sample).
struct Utterance {
  int sample_rate = 22050;
  std::vector<std::int16_t> samples;
  std::vector<PhonemeTiming> phonemes;  ///< contiguous; the last ends at samples.size()/sample_rate
  double duration() const noexcept { return static_cast<double>(samples.size()) / sample_rate; }
};

/// Where speech comes from. Implementations are safe to call from several threads at once.
class SpeechSynthesizer {
 public:
  virtual ~SpeechSynthesizer() = default;
  /// The speech and phoneme timing of `text` (UTF-8). Throws InvalidInput for text it cannot speak.
  virtual Utterance synthesize(std::string_view text) const = 0;
};

/// The espeak-ng program in a separate process (see the top of this header).
class EspeakProgram final : public SpeechSynthesizer {
 public:
  explicit EspeakProgram(SpeechOptions options = {});  ///< validates the options
  /// Throws InvalidInput for empty/invalid text or an unknown voice, IoError if the program cannot
  /// be run (install Debian's `espeak-ng` package) or fails.
  Utterance synthesize(std::string_view text) const override;
  const SpeechOptions& options() const noexcept { return options_; }

 private:
  SpeechOptions options_;
};

/// Timings made elsewhere (any TTS or forced aligner) with the user's own audio, looked up by text.
class ExternalSpeech final : public SpeechSynthesizer {
 public:
  /// Registers the utterance for `text`. Its phonemes must be contiguous from 0 and end at or
  /// before the audio's end (an utterance without samples gets silence of the phonemes' length at
  /// `sample_rate`). Phoneme names may be espeak-ng mnemonics or viseme names
  /// (VisemeSet::viseme_for_phoneme). Throws InvalidInput otherwise.
  void add(std::string text, Utterance utterance);
  /// Throws InvalidInput if `text` was not added.
  Utterance synthesize(std::string_view text) const override;
  std::size_t size() const noexcept { return utterances_.size(); }

 private:
  std::map<std::string, Utterance, std::less<>> utterances_;
};

/// EspeakProgram(options).synthesize(text).
Utterance synthesize(std::string_view text, const SpeechOptions& options = {});

/// The clauses of `espeak-ng -x --sep=' '` output: one line per clause, phonemes separated by
/// spaces, stress marks (' , % =) dropped. Pauses inside a clause ("_:", "_") are kept.
std::vector<std::vector<std::string>> parse_espeak_phonemes(std::string_view text);

struct AlignOptions {
  int silence_level = 4;      ///< |sample| <= this counts as silence, [0, 32767]
  double min_silence = 0.02;  ///< shortest run of silence used as an anchor, s, (0, 1]
  double stop_tolerance =
      0.08;  ///< a closure anchors a stop expected at most this far away, s, > 0
  void validate() const;
};

/// Places the phonemes of `clauses` (parse_espeak_phonemes) on `samples`: a pause phoneme "_:" is
/// appended to every clause; pauses take the longest runs of silence (in order), a stop (p b t d k
/// g tS dZ) starts where a shorter run of silence (its closure) ends, and the phonemes between
/// anchors share the time in proportion to nominal durations (vowels and diphthongs long, stops
/// short). The result is contiguous from 0 to samples.size()/sample_rate (zero-length phonemes
/// dropped).
std::vector<PhonemeTiming> align_phonemes(const std::vector<std::vector<std::string>>& clauses,
                                          const std::vector<std::int16_t>& samples, int sample_rate,
                                          const AlignOptions& options = {});

/// Places utterances at their start times (seconds) on one silent track of `sample_rate`.
/// Throws InvalidInput if they overlap or rates differ.
std::vector<std::int16_t> place_utterances(const std::vector<Utterance>& utterances,
                                           const std::vector<double>& start_times, int sample_rate,
                                           double min_duration = 0.0);

/// A RIFF/WAVE file (PCM, 16-bit, mono) as bytes.
std::string format_wav(const std::vector<std::int16_t>& samples, int sample_rate);
/// Writes format_wav atomically.
void write_wav(const std::string& path, const std::vector<std::int16_t>& samples, int sample_rate);

/// Audio read from a WAV file: 16-bit PCM, mono or stereo (averaged to mono), any sample rate.
struct WavAudio {
  int sample_rate = 0;
  std::vector<std::int16_t> samples;
};
/// Parses WAV bytes. A data chunk size of 0 or 0xFFFFFFFF-ish beyond the end (as written by
/// programs streaming to a pipe) means "to the end of the bytes". Throws FormatError naming `name`
/// for anything else than RIFF/WAVE PCM 16-bit with 1 or 2 channels, truncated chunks, or a
/// sample rate outside [1000, 384000].
WavAudio parse_wav(std::string_view bytes, const std::string& name = "<wav>");
WavAudio read_wav(const std::string& path);

}  // namespace emoface::channels
