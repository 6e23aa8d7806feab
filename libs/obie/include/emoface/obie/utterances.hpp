#pragma once
// Short utterances chosen from the emotions (thesis §7.2: "a simple mapping between emotions and
// text, e.g., the emotion fear is mapped with the sentence 'Oh no!'"), as editable data:
// `emoface.obie.utterances` 1.0 (JSON, data/obie/utterances.json is the built-in set):
//
//   {"format": "emoface.obie.utterances", "version": "1.0", "generator": "…",
//    "refractory": 3.0,     // s of animation between the starts of two utterances, at least
//    "delay": 0.3,          // s from the event to the start of its utterance
//    "max_wait": 3.0,       // s an utterance may be postponed by the refractory time before it is dropped
//    "rules": [{"emotion": "fear", "threshold": 0.5, "rise": 0.25, "texts": ["Oh no!", "Careful!"]}, …]}
//
// A rule fires at a timeline step when its basic emotion (ESV name) reaches `threshold` having been
// below it at the previous step, or jumps by at least `rise` while above it (a second goal while
// still happy). Of the rules firing at one step the one furthest above its threshold speaks; its text
// is drawn with core::Rng(seed, step). An utterance starts at max(event time + delay, previous start +
// max(refractory, previous duration + 0.3 s)) unless that is more than max_wait late (then dropped),
// so Obie never talks over himself and does not chatter.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/obie/time_map.hpp"
#include "emoface/parlee/agent.hpp"

namespace emoface::obie {

inline constexpr int kUtterancesFormatMajor = 1;
inline constexpr int kUtterancesFormatMinor = 0;

struct UtteranceRule {
  std::string emotion;             ///< sadness, happiness, anger, fear, disgust or surprise
  double threshold = 0.5;          ///< (0, 1]
  double rise = 0.25;              ///< (0, 1]; a jump this large above the threshold fires again
  std::vector<std::string> texts;  ///< non-empty, each 1–200 bytes of UTF-8
};

struct UtteranceSet {
  std::vector<UtteranceRule> rules;
  double refractory = 3.0;  ///< s, [0.5, 600]
  double delay = 0.3;       ///< s, [0, 10]
  double max_wait = 3.0;    ///< s, [0, 600]
  void validate() const;    ///< throws InvalidInput
};

/// The built-in set (data/obie/utterances.json, compiled in).
const UtteranceSet& default_utterances();
/// Throws FormatError (file + JSON pointer).
UtteranceSet parse_utterances(std::string_view text, const std::string& file);
UtteranceSet read_utterances_file(const std::string& path);
std::string write_utterances(const UtteranceSet& set);

/// Index of an ESV emotion name (sadness 0 … surprise 5); throws InvalidInput for others.
std::size_t esv_index(std::string_view emotion);

struct PlannedUtterance {
  std::size_t step = 0;    ///< index into the timeline records
  double minute = 0.0;     ///< match minute of that step
  double time = 0.0;       ///< animation seconds when it starts
  std::string emotion;
  double intensity = 0.0;  ///< the emotion's basic intensity at that step
  std::string text;
};

/// Seconds a text takes to say (e.g. measured by synthesis); 0 if unknown.
using SpeechDuration = std::function<double(const std::string& text)>;

/// Chooses the utterances of a timeline (records[k] at animation time step_seconds[k]).
/// Deterministic in `seed`. Throws InvalidInput for mismatched sizes or an invalid set.
std::vector<PlannedUtterance> choose_utterances(const std::vector<parlee::StepRecord>& records,
                                                const std::vector<double>& step_seconds, const UtteranceSet& set,
                                                std::uint64_t seed, const SpeechDuration& duration = {});

}  // namespace emoface::obie
