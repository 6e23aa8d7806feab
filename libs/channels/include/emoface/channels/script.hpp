#pragma once
// The talking head's marked-up input (thesis §4.2) and its turn into a Timeline.
//
// A script is XML: optionally wrapped in <SCRIPT>...</SCRIPT>, a sequence of elements (times and
// durations in seconds, element and attribute names case-insensitive):
//   <PHONEME time="0" text="Oh really?"/>            speech (channel 2), text → phonemes by espeak-ng
//   <VISEME time="0" duration="0.1" name="AA"/>       one explicit lip segment (channel 2)
//   <EMOTIONDISPLAY time="0" duration="2" [onset=".5"] [offset=".5"] Surprise="0.7" .../>
//                                                     felt emotion display (channel 4), intensities
//                                                     in [0,1] of sadness happiness anger fear disgust
//                                                     surprise → muscle targets by an EmotionMapper
//   <EMBLEM ...same attributes.../>                   emotion emblem (channel 4)
//   <SIGNAL time duration [onset] [offset] frontalis_medialis_l="0.6" .../>
//                                                     conversational signal (channel 3), parameters
//                                                     by name (or a muscle name = both sides)
//   <GAZE time duration [onset] [offset] [yaw] [pitch]/>   radians (channel 5)
//   <HEAD time duration [onset] [offset] [yaw] [pitch] [roll]/>   radians (channel 6)
//   <BLINK time [duration=".3"] [onset=".1"] [offset=".2"] [closure="1"]/>  (channel 1)
// Errors are FormatError with the file, line and column of the offending element.
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/channels/channel.hpp"
#include "emoface/channels/dominance.hpp"
#include "emoface/channels/generators.hpp"
#include "emoface/channels/mixer.hpp"

namespace emoface::channels {

/// Position of an element in the script (1-based).
struct ScriptLocation {
  std::size_t line = 0;
  std::size_t column = 0;
};

struct SpeechItem {
  double time = 0.0;
  std::string text;
  ScriptLocation where;
};

struct VisemeItem {
  LipSegment segment;
  ScriptLocation where;
};

/// The ESV order of emoface: sadness, happiness, anger, fear, disgust, surprise.
const std::array<std::string, 6>& emotion_names();

struct EmotionItem {
  bool emblem = false;
  std::array<double, 6> intensities{};  ///< in ESV order, each in [0,1]
  Timing timing;
  int priority = 0;  ///< Movement::priority of the display (0 = channel's)
  ScriptLocation where;
};

struct MovementItem {
  Channel channel = Channel::ConversationalSignal;
  Movement movement;
  ScriptLocation where;
};

struct Script {
  std::string file;
  std::vector<SpeechItem> speech;
  std::vector<VisemeItem> visemes;
  std::vector<EmotionItem> emotions;
  std::vector<MovementItem> movements;  ///< signals, gaze, head, blinks
};

/// Default onset/offset of elements that do not give them (seconds).
struct ScriptDefaults {
  double onset = 0.5;   ///< > 0
  double offset = 0.5;  ///< > 0; if onset + offset exceed a duration both shrink proportionally
};

/// Parses a script; throws FormatError (file:line:column) for malformed XML, unknown elements,
/// attributes, emotions or parameters, bad numbers, negative or inverted times, empty text.
Script parse_script(std::string_view xml, const std::string& file = "<script>", ScriptDefaults defaults = {});
Script read_script(const std::string& path, ScriptDefaults defaults = {});

/// A phoneme with its time span (seconds from the start of its utterance).
struct PhonemeTiming {
  std::string phoneme;
  double start = 0.0;
  double end = 0.0;
};

/// Emotion intensities (ESV order) → parameter targets (e.g. fuzzyexpr's FMCV expanded to sides).
using EmotionMapper = std::function<std::vector<Target>(const std::array<double, 6>&)>;

/// The emotion → display mapper of every pipeline (issue 18): `to_sides` maps an ESV to the 35 side
/// parameters in the order of the one vocabulary (core::side_parameter_names(), e.g.
/// fuzzyexpr::side_parameter_function()); the mapper names each value. Throws InvalidInput if
/// `to_sides` is empty.
using SideParameterFunction = std::function<std::array<double, 35>(const std::array<double, 6>&)>;
EmotionMapper side_parameter_mapper(SideParameterFunction to_sides);

struct TimelineOptions {
  bool blinks = true;
  bool gaze_noise = true;
  bool head_noise = true;
  BlinkOptions blink;
  NoiseOptions gaze = default_gaze_noise();
  NoiseOptions head = default_head_noise();
  /// Silence segments added before and after each utterance, seconds (> 0): the lip track fades to
  /// the silence viseme instead of ending on the last phoneme.
  double silence_pad = 0.2;
  /// Generated blinks/noise keep this distance from explicit movements in their channel, seconds.
  double generated_margin = 0.1;
  /// Seconds the generators run past the last element (>= 0).
  double tail = 0.5;
  void validate() const;
};

/// Turns a script into a Timeline: utterances[i] are the phonemes of script.speech[i] (times
/// relative to its `time`); visemes from `visemes`; emotion items through `mapper`; blinks and
/// gaze/head noise from `seed`. Throws FormatError (with the element's line/column) when two
/// movements of a channel break the order of §4.5.2 or utterances overlap, InvalidInput otherwise.
Timeline build_timeline(const Script& script, const std::vector<std::vector<PhonemeTiming>>& utterances,
                        const VisemeSet& visemes, const EmotionMapper& mapper,
                        const TimelineOptions& options, std::uint64_t seed);

}  // namespace emoface::channels
