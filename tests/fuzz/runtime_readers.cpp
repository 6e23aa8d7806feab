// libFuzzer target (build-fuzz/tests/fuzz/fuzz_runtime_readers tests/fuzz/corpus/runtime_readers)
// for the readers added by issue 16: the first byte picks the reader (emoface timing TSV / JSON,
// Rhubarb TSV / JSON, WAV, espeak-ng -x output + alignment, character config, character snapshot,
// an event pushed to a character). Accepted timing documents must round-trip exactly. Any exception
// other than emoface's FormatError / InvalidInput is a bug (and crashes here).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "emoface/channels/speech.hpp"
#include "emoface/channels/timing_io.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/runtime/character.hpp"

namespace {

namespace ch = emoface::channels;
namespace rt = emoface::runtime;

void same(const ch::SpeechTiming& a, const ch::SpeechTiming& b) {
  if (a.kind != b.kind || a.segments.size() != b.segments.size()) std::abort();
  for (std::size_t i = 0; i < a.segments.size(); ++i)
    if (a.segments[i].phoneme != b.segments[i].phoneme ||
        a.segments[i].start != b.segments[i].start || a.segments[i].end != b.segments[i].end)
      std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    switch (data[0] % 9) {
      case 0: {
        const ch::SpeechTiming t = ch::parse_timing_tsv(text, "fuzz.tsv");
        same(t, ch::parse_timing_tsv(ch::format_timing_tsv(t)));
        if (!t.segments.empty()) (void)ch::external_utterance(t);
        break;
      }
      case 1: {
        const ch::SpeechTiming t = ch::parse_timing_json(text, "fuzz.json");
        same(t, ch::parse_timing_json(ch::format_timing_json(t)));
        break;
      }
      case 2: {
        const ch::RhubarbCues r = ch::parse_rhubarb_tsv(text, "fuzz.tsv");
        (void)ch::rhubarb_to_visemes(r);
        (void)ch::parse_rhubarb_tsv(ch::format_rhubarb_tsv(r));
        break;
      }
      case 3:
        (void)ch::rhubarb_to_visemes(ch::parse_rhubarb_json(text, "fuzz.json"));
        break;
      case 4:
        (void)ch::parse_wav(text, "fuzz.wav");
        break;
      case 5: {
        std::vector<std::int16_t> samples(2000, 100);
        for (std::size_t i = 0; i < samples.size() && i < text.size(); ++i)
          samples[i] = static_cast<std::int16_t>(text[i] < 32 ? 0 : text[i] * 37);
        (void)ch::align_phonemes(ch::parse_espeak_phonemes(text), samples, 1000);
        break;
      }
      case 6: {
        rt::Character c(rt::parse_character_config(text, "fuzz.json"));
        c.update(0.1);
        break;
      }
      case 7: {
        rt::Character c = rt::restore_character(text, "fuzz.json");
        c.update(0.05);
        break;
      }
      default: {
        static rt::Character c{rt::CharacterConfig{}};
        (void)c.push_event(text);
        c.update(0.02);
        break;
      }
    }
  } catch (const emoface::FormatError&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
