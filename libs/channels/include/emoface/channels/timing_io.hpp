#pragma once
// Speech timings made outside emoface (any TTS or forced aligner, e.g. Montreal Forced Aligner,
// Gentle, a cloud TTS's viseme events, Rhubarb Lip Sync) for the user's own audio, as lip-channel
// input (speech.hpp, ExternalSpeech). Formats (docs/formats.md, "Speech timings"):
//
//  * emoface timing TSV: optional "# ..." stamp lines, a header "start<TAB>end<TAB>phoneme" (or
//    "...<TAB>viseme"), then one segment per line, seconds.
//  * emoface timing JSON: {"format": "emoface.speech_timing", "version": "1.0", "generator": ...,
//    "kind": "phoneme"|"viseme", "segments": [{"start": 0, "end": 0.12, "name": "h"}, ...]}.
//  * Rhubarb Lip Sync TSV (`-f tsv`): "<start><TAB><shape>" per line; each cue lasts until the
//  next,
//    the last one marks the end. JSON (`-f json`): {"metadata": {"soundFile", "duration"},
//    "mouthCues": [{"start", "end", "value"}, ...]}. Shapes A–H and X (Rhubarb's README).
//
// Segments are sorted, do not overlap and have end > start; gaps are silence.
#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/channels/script.hpp"
#include "emoface/channels/speech.hpp"

namespace emoface::channels {

enum class TimingKind { Phoneme, Viseme };
std::string_view to_string(TimingKind kind) noexcept;       ///< "phoneme", "viseme"
TimingKind timing_kind_from_string(std::string_view name);  ///< throws InvalidInput

struct SpeechTiming {
  TimingKind kind = TimingKind::Phoneme;
  std::vector<PhonemeTiming> segments;  ///< names: phoneme mnemonics or viseme names
  /// Throws InvalidInput unless every name is non-empty without tabs or newlines, times are finite,
  /// >= 0, end > start, sorted and not overlapping, and there are at most kMaxTimingSegments.
  void validate() const;
};
inline constexpr std::size_t kMaxTimingSegments = 1000000;

/// Readers throw FormatError naming `file` and the line (TSV) or JSON pointer of the bad field.
SpeechTiming parse_timing_tsv(std::string_view text, const std::string& file = "<timing>");
std::string format_timing_tsv(const SpeechTiming& timing);  ///< with the version stamp line
SpeechTiming parse_timing_json(std::string_view text, const std::string& file = "<timing>");
std::string format_timing_json(const SpeechTiming& timing);
/// By content: a document starting with '{' is JSON (emoface's or Rhubarb's, told by its fields),
/// otherwise TSV (emoface's when its first non-comment line is a header, else Rhubarb's). Rhubarb
/// shapes are turned into visemes by rhubarb_to_visemes with the default table.
SpeechTiming read_timing_file(const std::string& path);

/// Rhubarb Lip Sync's mouth cues (shape letters), read and written in its TSV and JSON formats.
struct RhubarbCues {
  std::vector<PhonemeTiming> cues;  ///< phoneme = the shape letter, one of A B C D E F G H X
  std::string sound_file;           ///< JSON metadata (may be empty)
  void validate() const;            ///< as SpeechTiming::validate plus known shapes, contiguous
};
RhubarbCues parse_rhubarb_tsv(std::string_view text, const std::string& file = "<rhubarb>");
std::string format_rhubarb_tsv(const RhubarbCues& cues);
RhubarbCues parse_rhubarb_json(std::string_view text, const std::string& file = "<rhubarb>");
std::string format_rhubarb_json(const RhubarbCues& cues);

/// Rhubarb shape → emoface viseme (default_viseme_set names), after the shapes in Rhubarb Lip
/// Sync's README: A closed (P B M) → PBM; B slightly open, clenched teeth (K S T EE) → SZ; C open
/// (EH AE) → EH; D wide open (AA) → AA; E slightly rounded (AO ER) → OH; F puckered (UW OW W) → UW;
/// G upper teeth on the lower lip (F V) → FV; H tongue raised (L) → TDNL; X idle → sil.
const std::map<std::string, std::string>& default_rhubarb_visemes();
/// Throws InvalidInput for a shape missing from `table`.
SpeechTiming rhubarb_to_visemes(
    const RhubarbCues& cues,
    const std::map<std::string, std::string>& table = default_rhubarb_visemes());

/// An utterance for ExternalSpeech: the timing's segments made contiguous from 0 (gaps become the
/// pause "_"), with `audio` (empty samples: silence as long as the timing, at 22050 Hz). Throws
/// InvalidInput if the segments end after the audio.
Utterance external_utterance(const SpeechTiming& timing, const WavAudio& audio = {});

}  // namespace emoface::channels
