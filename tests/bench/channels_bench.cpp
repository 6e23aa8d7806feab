// channels benchmark: a 60-second talking-head script (speech, two emotion displays, blinks, gaze
// and head movement), all 40 parameters at 100 fps. Run:
//   build-bench/tests/bench/channels_bench --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include "emoface/channels/talking_head.hpp"

namespace ch = emoface::channels;

namespace {

const char* kText =
    "Oh, really? I like it very much. The match started slowly, and for the first twenty minutes "
    "neither team could hold the ball for long. Then our striker found a gap on the left, ran past "
    "two defenders and shot from the edge of the box. The keeper never saw it coming. Everybody "
    "around me jumped up and shouted, strangers hugged each other, and somebody spilled a whole cup "
    "of coffee over my jacket. I did not even care. After the break the other side pushed hard, "
    "and we were lucky twice when the ball hit the post. In the last minute they scored from a "
    "corner, and the whole stadium went quiet. A draw is not a disaster, but it feels like one when "
    "you were winning for so long. Next week we play away, and I will be there again, of course. "
    "Maybe this time the weather will be kinder, and maybe our defence will remember how to defend.";

ch::Script script() {
  return ch::parse_script(std::string("<SCRIPT><PHONEME time=\"0.5\" text=\"") + kText +
                          "\"/>"
                          "<EMOTIONDISPLAY time=\"2\" duration=\"10\" Happiness=\"0.9\"/>"
                          "<EMOTIONDISPLAY time=\"40\" duration=\"12\" Sadness=\"0.6\" Anger=\"0.3\"/>"
                          "<GAZE time=\"20\" duration=\"3\" yaw=\"0.3\" pitch=\"-0.1\"/>"
                          "<HEAD time=\"25\" duration=\"2\" pitch=\"0.15\"/>"
                          "<SIGNAL time=\"8\" duration=\"1\" frontalis_medialis=\"0.6\" frontalis_lateralis=\"0.5\"/>"
                          "</SCRIPT>");
}

// fixed stand-in for fuzzyexpr (the mapping is not what is measured here)
std::vector<ch::Target> mapper(const std::array<double, 6>& e) {
  return {{"zygomatic_major_l", e[1]}, {"zygomatic_major_r", e[1]}, {"orbicularis_oculi_orbitalis_l", 0.5 * e[1]},
          {"orbicularis_oculi_orbitalis_r", 0.5 * e[1]}, {"frontalis_medialis_l", e[0]},
          {"frontalis_medialis_r", e[0]}, {"triangularis_l", e[0]}, {"triangularis_r", e[0]},
          {"corrugator_supercilii_l", e[2]}, {"corrugator_supercilii_r", e[2]}};
}

void BM_SpeechSynthesis(benchmark::State& state) {
  double audio = 0;
  for (auto _ : state) {
    const ch::Utterance u = ch::synthesize(kText);
    audio = u.duration();
    benchmark::DoNotOptimize(u.samples.data());
  }
  state.counters["audio_s"] = audio;
}
BENCHMARK(BM_SpeechSynthesis)->Unit(benchmark::kMillisecond);

// Arg 0: plain channel priorities (baseline); arg 1: the happiness display carries its own priority 1
// (§4.1 per-movement priority: the mixer's per-frame fixed-point path).
void BM_TimelineAndRender(benchmark::State& state) {
  const ch::Script s = script();
  const ch::Utterance u = ch::synthesize(kText);
  const ch::VisemeSet vs = ch::default_viseme_set();
  const ch::ConflictTable ct = ch::default_conflict_table();
  ch::TimelineOptions to;
  ch::RenderOptions ro;
  ro.fps = 100;
  ro.duration = 60;
  std::size_t frames = 0;
  for (auto _ : state) {
    ch::Timeline tl = ch::build_timeline(s, {u.phonemes}, vs, mapper, to, 42);
    if (state.range(0) == 1)
      tl.movements[static_cast<std::size_t>(ch::Channel::EmotionDisplay)].front().priority = 1;
    const ch::Tracks t = ch::render(tl, vs, ct, ro);
    frames = t.frames();
    benchmark::DoNotOptimize(t.values.data());
  }
  state.counters["frames"] = static_cast<double>(frames);
  state.counters["speech_s"] = u.duration();
}
BENCHMARK(BM_TimelineAndRender)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_Coarticulation(benchmark::State& state) {
  const ch::Utterance u = ch::synthesize(kText);
  const ch::VisemeSet vs = ch::default_viseme_set();
  std::vector<ch::LipSegment> segs;
  for (const auto& p : u.phonemes) segs.push_back({vs.viseme_for_phoneme(p.phoneme), p.start, p.end, 0.0, p.phoneme});
  const ch::Coarticulation lip(vs, segs);
  std::vector<double> out(6000);
  for (auto _ : state) {
    for (std::size_t p = 0; p < lip.parameters().size(); ++p) lip.sample(p, 0.0, 100.0, out.size(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["lip_params"] = static_cast<double>(lip.parameters().size());
}
BENCHMARK(BM_Coarticulation)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
