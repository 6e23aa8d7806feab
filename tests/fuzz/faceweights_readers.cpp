// libFuzzer target (build-fuzz/tests/fuzz/fuzz_faceweights_readers tests/fuzz/corpus/faceweights)
// for the faceweights readers: the first byte picks the reader (weight set JSON, ARKit/Live Link Face
// CSV track, Live Link timecode); the rest is the input. A weight set that parses must also build a
// Mapper and survive a forward map and a fit. Anything but FormatError / InvalidInput is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/faceweights/tracks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  namespace fw = emoface::faceweights;
  try {
    switch (data[0] % 3) {
      case 0: {
        const fw::WeightSet set = fw::parse_weight_set(text, "fuzz.json");
        const std::vector<std::string> names = {"a", "b", "head_yaw", "eye_gaze_yaw", "x"};
        const fw::Mapper m(set, names);
        const auto w = m.forward(std::vector<double>(names.size(), 0.5));
        std::vector<double> p;
        (void)m.inverse(w, p);
        break;
      }
      case 1: {
        fw::WeightTrackReadOptions o;
        o.fps = 30;
        (void)fw::parse_weight_track(text, fw::builtin_weight_set("arkit"), "fuzz.csv", o);
        break;
      }
      default:
        (void)fw::parse_live_link_timecode(text, 60);
    }
  } catch (const emoface::FormatError&) {
  } catch (const emoface::InvalidInput&) {
  }
  return 0;
}
