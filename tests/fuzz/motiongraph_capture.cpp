// libFuzzer target: the capture readers (OpenFace 2.0 CSV, MediaPipe face-landmarker NDJSON, label
// side files) must reject bad input with an emoface error, never crash or hang; what they accept
// must survive cleaning, stabilisation, trimming and the writers' round trip. Seeds:
// tests/fuzz/corpus/motiongraph_capture (data/capture/ examples, trimmed).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/capture.hpp"

namespace mg = emoface::motiongraph;

template <class F>
static void guarded(F&& f) {
  try {
    f();
  } catch (const emoface::Error&) {
  } catch (const emoface::InvalidInput&) {
  }
}

static void process(const mg::TrackedFrames& t) {
  for (mg::TrackedFrames part : mg::clean_frames(t)) {
    guarded([&] { mg::stabilise_head(part); });
    guarded([&] { (void)mg::find_segments(part); });
  }
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  guarded([&] {
    mg::OpenFaceReadOptions o;
    o.label_column = "label";
    const mg::TrackedFrames t = mg::parse_openface_csv(text, "fuzz.csv", o);
    const mg::TrackedFrames back = mg::parse_openface_csv(mg::openface_csv(t), "fuzz.csv", o);
    if (back.frames.size() != t.frames.size() || back.times != t.times) std::abort();  // round trip
    process(t);
  });
  guarded([&] { process(mg::parse_openface_csv(text, "fuzz.csv")); });
  guarded([&] {
    mg::MediaPipeReadOptions o;
    o.use_z = true;
    process(mg::parse_mediapipe_ndjson(text, "fuzz.ndjson", o));
  });
  guarded([&] {
    const mg::LabelTable t = mg::parse_label_table(text, "fuzz.csv");
    if (mg::parse_label_table(mg::label_table_csv(t), "x").entries != t.entries) std::abort();
  });
  return 0;
}
