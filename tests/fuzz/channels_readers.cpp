// libFuzzer target (build-fuzz/tests/fuzz/fuzz_channels_readers tests/fuzz/corpus/channels_readers)
// for every reader of the channels library: the first byte picks the reader
// (markup script, tracks JSON, tracks CSV, visemes, conflicts); the rest is the input. Any
// exception other than emoface's FormatError / InvalidInput is a bug (and crashes here).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "emoface/channels/io.hpp"
#include "emoface/channels/script.hpp"
#include "emoface/core/errors.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  namespace ch = emoface::channels;
  try {
    switch (data[0] % 5) {
      case 0: {
        const ch::Script s = ch::parse_script(text, "fuzz.xml");
        // the timeline builder must also cope with whatever the parser accepted
        std::vector<std::vector<ch::PhonemeTiming>> ph(s.speech.size(), {{"a", 0.0, 0.1}});
        ch::TimelineOptions o;
        o.blinks = o.gaze_noise = o.head_noise = false;
        (void)ch::build_timeline(s, ph, ch::default_viseme_set(),
                                 [](const std::array<double, 6>& e) {
                                   return std::vector<ch::Target>{{"zygomatic_major_l", e[1]}};
                                 },
                                 o, 1);
        break;
      }
      case 1: (void)ch::parse_tracks_json(text, "fuzz.json"); break;
      case 2: (void)ch::parse_tracks_csv(text, "fuzz.csv"); break;
      case 3: (void)ch::parse_visemes(text, "fuzz.json"); break;
      default: (void)ch::parse_conflicts(text, "fuzz.json"); break;
    }
  } catch (const emoface::FormatError&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
