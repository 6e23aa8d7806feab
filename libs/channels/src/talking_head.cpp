#include "emoface/channels/talking_head.hpp"

#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::channels {

void TalkingHeadOptions::validate() const {
  speech.validate();
  timeline.validate();
  render.validate();
}

TalkingHead run_talking_head(const Script& script, const VisemeSet& visemes, const ConflictTable& conflicts,
                             const EmotionMapper& mapper, const TalkingHeadOptions& options) {
  options.validate();
  visemes.validate();
  conflicts.validate();
  TalkingHead out;
  std::vector<Utterance> utterances;
  std::vector<std::vector<PhonemeTiming>> phonemes;
  std::vector<double> starts;
  std::shared_ptr<const SpeechSynthesizer> synth = options.synthesizer;
  if (!synth && !script.speech.empty()) synth = std::make_shared<EspeakProgram>(options.speech);
  for (const SpeechItem& s : script.speech) {
    utterances.push_back(synth->synthesize(s.text));
    phonemes.push_back(utterances.back().phonemes);
    starts.push_back(s.time);
    out.sample_rate = utterances.back().sample_rate;
  }
  out.timeline = build_timeline(script, phonemes, visemes, mapper, options.timeline, options.seed);
  out.tracks = render(out.timeline, visemes, conflicts, options.render);
  const double duration = out.tracks.time(out.tracks.frames() - 1);
  out.audio = place_utterances(utterances, starts, out.sample_rate, duration);
  out.audio.resize(static_cast<std::size_t>(std::llround(duration * out.sample_rate)), 0);
  return out;
}

}  // namespace emoface::channels
