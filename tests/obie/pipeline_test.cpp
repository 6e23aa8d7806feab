#include "emoface/obie/pipeline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/video.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/solver.hpp"
#include "emoface/parlee/io.hpp"
#include "test_match.hpp"

namespace emoface::obie {
namespace {

const std::string kAgent = std::string(EMOFACE_SOURCE_DIR) + "/data/parlee/agents/neutral.json";

ObieOptions small_options() {
  ObieOptions o;
  o.fps = 10;
  o.width = 48;
  o.height = 56;
  o.gltf_fps = 2;
  o.threads = 2;
  return o;
}

const facemesh::Face& face() {
  static const facemesh::Face f = facemesh::make_generic_face();
  return f;
}

struct Collect : FrameSink {
  int width = 0, height = 0, begun = 0, finished = 0;
  double fps = 0;
  std::size_t audio = 0;
  std::vector<core::Image> frames;
  void begin(const ObieResult& r, int w, int h, double f) override {
    ++begun;
    width = w;
    height = h;
    fps = f;
    audio = r.head.audio.size();
  }
  void frame(const core::Image& image) override { frames.push_back(image); }
  void finish() override { ++finished; }
};

// One run with speech, shared by the invariant tests (espeak-ng is process-global state).
struct SpeechRun {
  MatchScript match;
  ObieResult result;
  Collect sink;
  std::vector<Progress> progress;
};
const SpeechRun& speech_run() {
  static const SpeechRun* run = [] {
    auto* r = new SpeechRun;
    r->match = parse_match(test::short_match_json(), "short.json");
    r->result = run_obie(r->match, parlee::read_agent_file(kAgent), face(), small_options(),
                         [r](const Progress& p) { r->progress.push_back(p); }, &r->sink, "short.json");
    return r;
  }();
  return *run;
}

TEST(Pipeline, EveryStageInRange) {
  const SpeechRun& run = speech_run();
  const ObieResult& r = run.result;
  ASSERT_EQ(r.timeline.size(), run.match.events.size() + 1);
  for (const auto& rec : r.timeline)
    for (double v : rec.basic) {
      EXPECT_GE(v, 0.0);
      EXPECT_LE(v, 1.0);
    }
  // displays: ordered as the channels require (§4.5.2), intensities in [0,1]
  ASSERT_FALSE(r.script.emotions.empty());
  for (std::size_t i = 0; i < r.script.emotions.size(); ++i) {
    const auto& e = r.script.emotions[i];
    e.timing.validate();
    for (double v : e.intensities) EXPECT_TRUE(v >= 0 && v <= 1);
    if (i > 0) {
      EXPECT_GT(e.timing.start, r.script.emotions[i - 1].timing.start);
      EXPECT_GT(e.timing.end, r.script.emotions[i - 1].timing.end);
    }
  }
  // tracks: 40 named parameters, contractions in [0,1], angles within ±π
  const auto& tracks = r.head.tracks;
  tracks.validate();
  EXPECT_EQ(tracks.names, channels::default_parameter_names());
  for (std::size_t f = 0; f < tracks.frames(); ++f)
    for (std::size_t c = 0; c < tracks.names.size(); ++c) {
      const double v = tracks.at(f, c);
      if (channels::is_signed_parameter(tracks.names[c])) {
        EXPECT_LE(std::abs(v), M_PI);
      } else {
        EXPECT_GE(v, -1e-12) << tracks.names[c] << " frame " << f;
        EXPECT_LE(v, 1 + 1e-12) << tracks.names[c] << " frame " << f;
      }
    }
  // meshes finite, glTF frames at 2 fps with increasing times
  ASSERT_FALSE(r.gltf_frames.empty());
  EXPECT_EQ(r.gltf_frames.size(), r.gltf_times.size());
  for (std::size_t i = 0; i < r.gltf_frames.size(); ++i) {
    EXPECT_TRUE(r.gltf_frames[i].allFinite());
    EXPECT_EQ(r.gltf_frames[i].rows(), face().mesh.vertices.rows());
    EXPECT_NEAR(r.gltf_times[i], 0.5 * static_cast<double>(i), 1e-9);
  }
  // the face moves: some frame differs from the neutral mesh by more than a millimetre
  double moved = 0;
  for (const auto& v : r.gltf_frames) moved = std::max(moved, (v - face().mesh.vertices).cwiseAbs().maxCoeff());
  EXPECT_GT(moved, 1e-3);
}

TEST(Pipeline, FearNarrowsButNeverClosesTheEyes) {
  // Issue 14: Obie spent the first 40 minutes with his eyes shut because fear saturated the lid
  // muscle. Now orbicularis oculi palpebralis only tightens (AU7); closure is eye_blink (AU45).
  // Every frame of the tracks outside blinks keeps at least 30 % of the neutral aperture.
  const SpeechRun& run = speech_run();
  const auto& tracks = run.result.head.tracks;
  double fear = 0.0;
  for (const auto& rec : run.result.timeline)
    fear = std::max(fear, rec.basic[3]);  // ESV order: fear 4th
  EXPECT_GT(fear, 0.5);  // the short match frightens him (the against team attacks, then scores)
  const muscles::FaceSolver solver(face().mesh, face().rig);
  const double a0 = muscles::eye_aperture(face().rig, face().mesh.vertices, 0);
  std::vector<int> index(tracks.names.size());
  for (std::size_t c = 0; c < tracks.names.size(); ++c)
    index[c] = static_cast<int>(muscles::parameter_index(tracks.names[c]));
  const std::size_t blink_l = muscles::parameter_index("eye_blink_l"),
                    blink_r = muscles::parameter_index("eye_blink_r");
  std::vector<double> values(muscles::kParameterCount);
  muscles::Deformation d;
  muscles::DeformWorkspace ws;
  std::size_t checked = 0;
  double smallest = 1e9, largest_palpebralis = 0.0;
  for (std::size_t f = 0; f < tracks.frames(); ++f) {
    std::fill(values.begin(), values.end(), 0.0);
    for (std::size_t c = 0; c < tracks.names.size(); ++c)
      values[static_cast<std::size_t>(index[c])] = tracks.at(f, c);
    if (values[blink_l] > 0.0 || values[blink_r] > 0.0)
      continue;  // a blink closes the eyes on purpose
    for (const char* pose : {"head_yaw", "head_pitch", "head_roll"})
      values[muscles::parameter_index(pose)] = 0.0;
    largest_palpebralis = std::max(
        largest_palpebralis, values[muscles::parameter_index("orbicularis_oculi_palpebralis_r")]);
    solver.deform(values, d, ws);
    for (int e = 0; e < 2; ++e)
      smallest = std::min(smallest, muscles::eye_aperture(face().rig, d.vertices, e) / a0);
    ++checked;
  }
  std::printf(
      "fear up to %.2f, palpebralis up to %.2f: smallest aperture %.2f of neutral over %zu "
      "frames\n",
      fear, largest_palpebralis, smallest, checked);
  EXPECT_GT(checked, tracks.frames() / 2);
  EXPECT_GT(largest_palpebralis, 0.3);  // the tightener is used
  EXPECT_GE(smallest, 0.30);
}

TEST(Pipeline, DurationsAgree) {
  const SpeechRun& run = speech_run();
  const ObieResult& r = run.result;
  // 1 s lead-in + 14 minutes at 1 s/min + 3.5 s tail = 18.5 s → 186 frames at 10 fps
  EXPECT_DOUBLE_EQ(r.time_map.duration(), 18.5);
  EXPECT_EQ(r.frames, 186u);
  EXPECT_EQ(r.head.tracks.frames(), r.frames);
  EXPECT_DOUBLE_EQ(r.seconds(), 18.5);
  // audio and tracks end together (within one frame)
  const double audio_seconds = static_cast<double>(r.head.audio.size()) / r.head.sample_rate;
  EXPECT_NEAR(audio_seconds, r.seconds(), 1.0 / r.head.tracks.fps);
  // every frame went to the sink, in the right size, after begin() saw the final audio
  EXPECT_EQ(run.sink.begun, 1);
  EXPECT_EQ(run.sink.finished, 1);
  EXPECT_EQ(run.sink.frames.size(), r.frames);
  EXPECT_EQ(r.frames_rendered, r.frames);
  EXPECT_EQ(run.sink.width, 48);
  EXPECT_EQ(run.sink.height, 56);
  EXPECT_EQ(run.sink.audio, r.head.audio.size());
  for (const auto& im : run.sink.frames) EXPECT_EQ(im.rgb.size(), 48u * 56u * 3u);
  // step times follow the time map
  for (std::size_t k = 0; k < r.timeline.size(); ++k)
    EXPECT_DOUBLE_EQ(r.step_seconds[k], r.time_map.seconds(r.timeline[k].time));
  // progress reached the end of each stage
  ASSERT_FALSE(run.progress.empty());
  EXPECT_EQ(run.progress.back().stage, "frames");
  EXPECT_EQ(run.progress.back().done, r.frames);
}

TEST(Pipeline, UtterancesAreSpokenInTheLipChannel) {
  const ObieResult& r = speech_run().result;
  // fear crosses its threshold right after kick-off and sadness at 12' (the goal against)
  ASSERT_GE(r.utterances.size(), 2u);
  EXPECT_EQ(r.utterances.front().emotion, "fear");
  bool sad_at_12 = false;
  for (const auto& u : r.utterances) sad_at_12 = sad_at_12 || (u.emotion == "sadness" && u.minute == 12);
  EXPECT_TRUE(sad_at_12);
  const auto& set = default_utterances();
  for (const auto& u : r.utterances) {
    // the rule really fired: the emotion is at or above its threshold at that step
    for (const auto& rule : set.rules)
      if (rule.emotion == u.emotion)
        EXPECT_GE(r.timeline[u.step].shown[esv_index(u.emotion)], rule.threshold);
    // lip segments (not silence) start within the utterance's first second …
    bool lip = false;
    for (const auto& seg : r.head.timeline.lip)
      lip = lip || (seg.start >= u.time - 1e-9 && seg.start < u.time + 1.0 && seg.viseme != "sil");
    EXPECT_TRUE(lip) << u.text;
    // … the audio is not silent there …
    const auto s0 = static_cast<std::size_t>(u.time * r.head.sample_rate);
    int loud = 0;
    for (std::size_t i = s0; i < s0 + static_cast<std::size_t>(r.head.sample_rate) && i < r.head.audio.size(); ++i)
      loud = std::max(loud, std::abs(static_cast<int>(r.head.audio[i])));
    EXPECT_GT(loud, 1000) << u.text;
    // … and the jaw/lip parameters move while he speaks
    double open = 0;
    for (const char* p : {"masseter", "orbicularis_oris_funneler", "orbicularis_oris_pressor", "mentalis_l"}) {
      const auto track = r.head.tracks.series(p);
      const auto f0 = static_cast<std::size_t>(u.time * 10);
      for (std::size_t f = f0; f < f0 + 10 && f < track.size(); ++f) open = std::max(open, track[f]);
    }
    EXPECT_GT(open, 0.05) << u.text;
  }
  // nothing is said before the first event
  EXPECT_GT(r.utterances.front().time, r.time_map.seconds(1));
}

TEST(Pipeline, KeyMomentsMapToTheirFrames) {
  const ObieResult& r = speech_run().result;
  ASSERT_EQ(r.key_frames.size(), 2u);
  const auto o = small_options();
  // 12' → 1 + 12 = 13 s, + 0.6 s delay → frame round(13.6·10) = 136
  EXPECT_EQ(r.key_frames[1].frame, 136u);
  EXPECT_EQ(key_moment_frame(r.time_map, 12, o.key_moment_delay, o.fps, r.frames), 136u);
  EXPECT_EQ(r.key_frames[0].frame, 16u);  // 0' → 1 s + 0.6 s
  EXPECT_EQ(key_moment_frame(r.time_map, 1000, 0, 10, r.frames), r.frames - 1);
  // the rendered key frame is the frame the sink got
  EXPECT_EQ(r.key_frames[1].image.rgb, speech_run().sink.frames[136].rgb);
  // at 12' the goal against shows: sadness/anger up, no happiness
  EXPECT_GT(std::max(r.key_frames[1].shown[0], r.key_frames[1].shown[2]), 0.3);
  EXPECT_EQ(r.key_frames[1].shown[1], 0.0);
  EXPECT_GT(r.key_frames[1].esv[3], 0.5);  // felt: fear of losing
  // the face differs from the start frame
  EXPECT_NE(r.key_frames[0].image.rgb, r.key_frames[1].image.rgb);
}

TEST(Pipeline, GoalsAndPeaks) {
  const ObieResult& r = speech_run().result;
  ASSERT_EQ(r.goals.size(), 1u);
  EXPECT_EQ(r.goals[0].minute, 12);
  EXPECT_EQ(r.goals[0].team, "Against");
  EXPECT_EQ(r.goals[0].against_score, 1);
  EXPECT_EQ(r.peaks[3].emotion, "fear");
  EXPECT_GT(r.peaks[3].value, 0.9);
  for (const auto& p : r.peaks) {
    double m = 0;
    for (const auto& rec : r.timeline) m = std::max(m, rec.basic[esv_index(p.emotion)]);
    EXPECT_DOUBLE_EQ(p.value, m);
  }
  const auto summary = nlohmann::json::parse(format_summary(r, speech_run().match));
  EXPECT_EQ(summary["format"], "emoface.obie.summary");
  EXPECT_EQ(summary["frames"], r.frames);
  EXPECT_EQ(summary["final_score"], "0-1");
  EXPECT_TRUE(summary.contains("timings_s"));
  // timeline NDJSON: the stream header, then one line per record, each with the animation time
  const std::string tl = format_timeline(r);
  EXPECT_EQ(tl.rfind(core::ndjson_header("obie.timeline", {1, 0}), 0), 0u);
  EXPECT_EQ(static_cast<std::size_t>(std::count(tl.begin(), tl.end(), '\n')), r.timeline.size() + 1);
  EXPECT_NE(tl.find("{\"agent\":\"neutral\",\"anim_time\":13.0,"), std::string::npos);  // 12' → 1 + 12 s
}

TEST(Pipeline, DeterministicWithASeed) {
  // Without speech (espeak-ng keeps process-global state; the app test checks speech across processes).
  const MatchScript match = parse_match(test::short_match_json(), "short.json");
  const auto agent = parlee::read_agent_file(kAgent);
  ObieOptions o = small_options();
  o.speech = false;
  o.render_frames = false;
  const ObieResult a = run_obie(match, agent, face(), o);
  const ObieResult b = run_obie(match, agent, face(), o);
  o.threads = 1;
  const ObieResult c = run_obie(match, agent, face(), o);
  o.seed = 99;
  const ObieResult d = run_obie(match, agent, face(), o);
  EXPECT_EQ(a.head.tracks.values, b.head.tracks.values);
  EXPECT_EQ(a.head.tracks.values, c.head.tracks.values);
  EXPECT_NE(a.head.tracks.values, d.head.tracks.values);  // blinks and gaze/head noise follow the seed
  ASSERT_EQ(a.gltf_frames.size(), c.gltf_frames.size());
  for (std::size_t i = 0; i < a.gltf_frames.size(); ++i) EXPECT_TRUE(a.gltf_frames[i] == c.gltf_frames[i]);
  EXPECT_EQ(format_summary(a, match, false), format_summary(b, match, false));
  EXPECT_EQ(format_timeline(a), format_timeline(c));
  EXPECT_EQ(core::encode_png(key_moment_sheet(a)), core::encode_png(key_moment_sheet(c)));
  EXPECT_EQ(core::encode_png(emotion_chart(a)), core::encode_png(emotion_chart(b)));
  EXPECT_EQ(a.frames_rendered, 0u);
  EXPECT_TRUE(a.utterances.empty());
  for (auto s : a.head.audio) ASSERT_EQ(s, 0);
  EXPECT_NEAR(static_cast<double>(a.head.audio.size()) / a.head.sample_rate, a.seconds(), 0.1);
}

TEST(Pipeline, ScriptsThatDoNotFitTheDomainAreLocated) {
  const auto agent = parlee::read_agent_file(kAgent);
  ObieOptions o = small_options();
  o.speech = false;
  // a shot by the side not on the ball at minute 14 (index 13)
  const MatchScript bad = parse_match(test::short_match_json(R"J(, {"minute": 14, "action": "(shot oteam)", "outcome": "goal"})J"),
                                      "short.json");
  try {
    run_obie(bad, agent, face(), o, {}, nullptr, "short.json");
    FAIL() << "no error";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("short.json: at /events/13"), std::string::npos) << e.what();
  }
  const MatchScript unknown = parse_match(test::short_match_json(R"J(, {"minute": 14, "action": "(fly team)"})J"), "s.json");
  EXPECT_THROW(run_match(unknown, agent, "s.json"), FormatError);
  MatchScript missing = parse_match(test::short_match_json(), "s.json");
  missing.domain = {"/nonexistent/football.domain"};
  EXPECT_THROW(run_match(missing, agent), Error);
}

TEST(Pipeline, RejectsBadOptions) {
  const MatchScript match = parse_match(test::short_match_json(), "short.json");
  const auto agent = parlee::read_agent_file(kAgent);
  auto bad = [&](auto change) {
    ObieOptions o = small_options();
    change(o);
    EXPECT_THROW(run_obie(match, agent, face(), o), InvalidInput);
  };
  bad([](ObieOptions& o) { o.fps = 0; });
  bad([](ObieOptions& o) { o.fps = std::nan(""); });
  bad([](ObieOptions& o) { o.width = 8; });
  bad([](ObieOptions& o) { o.gltf_fps = 50; });
  bad([](ObieOptions& o) { o.threads = -1; });
  bad([](ObieOptions& o) { o.display.onset = 0; });
  bad([](ObieOptions& o) { o.display.reaction_gain = 0.5; });
  bad([](ObieOptions& o) { o.display.smile_outranks_speech = -0.1; });
  bad([](ObieOptions& o) { o.time.seconds_per_minute = -1; });
  bad([](ObieOptions& o) { o.utterances.refractory = 0; });
  bad([](ObieOptions& o) { o.voice.rate = 10; });
}

TEST(Displays, HandBuiltTimeline) {
  std::vector<parlee::StepRecord> rec(5);
  rec[1].shown[3] = 1.0;  // fear
  rec[2].shown[3] = 1.0;
  rec[3].shown[3] = 1.0;
  rec[3].shown[1] = 0.4;  // happiness rises by 0.4 ≥ 0.15: a reaction
  rec[4].shown[3] = 1.0;
  rec[4].shown[1] = 0.39;
  const std::vector<double> t = {1, 2, 3, 4, 10};
  DisplayOptions o;
  const auto d = emotion_displays(rec, t, o);
  // t + 0.15 s delay: 1.15 neutral (no display); 2.15 fear rises (fear fresh until 5.15), 3.15 the
  // same (merged); 4.15 happiness rises by 0.4 (fresh until 7.15) while fear is still fresh: both
  // show (fear 1, happiness 0.4·1.5); 5.15 fear's window closes: happiness 0.6 alone (fear ×0);
  // 7.15 the full ESV returns; 10.15 differs by 0.01 < 0.02: merged, held 2 s.
  ASSERT_EQ(d.size(), 4u);
  EXPECT_DOUBLE_EQ(d[0].timing.start, 2.15);
  EXPECT_DOUBLE_EQ(d[0].timing.end, 4.15 + 0.8);
  EXPECT_DOUBLE_EQ(d[0].intensities[3], 1.0);
  EXPECT_DOUBLE_EQ(d[1].timing.start, 4.15);
  EXPECT_NEAR(d[1].intensities[1], 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(d[1].intensities[3], 1.0);
  EXPECT_DOUBLE_EQ(d[1].timing.end, 5.15 + 0.8);
  EXPECT_DOUBLE_EQ(d[2].timing.start, 5.15);
  EXPECT_NEAR(d[2].intensities[1], 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(d[2].intensities[3], 0.0);
  EXPECT_DOUBLE_EQ(d[2].timing.end, 7.15 + 0.8);
  EXPECT_DOUBLE_EQ(d[3].timing.start, 7.15);
  EXPECT_DOUBLE_EQ(d[3].intensities[1], 0.4);
  EXPECT_DOUBLE_EQ(d[3].intensities[3], 1.0);
  EXPECT_DOUBLE_EQ(d[3].timing.end, 12.15 + 0.8);
  EXPECT_DOUBLE_EQ(d[3].timing.onset, 0.4);
  // §4.1: only a display with happiness ≥ 0.9 outranks speech (priority 1); here none
  for (const auto& item : d) EXPECT_EQ(item.priority, 0);
  DisplayOptions happy = o;
  happy.smile_outranks_speech = 0.6;  // the reaction shows happiness 0.6
  const auto h = emotion_displays(rec, t, happy);
  EXPECT_EQ(h[1].priority, 1);
  EXPECT_EQ(h[2].priority, 1);
  EXPECT_EQ(h[3].priority, 0);
  o.reactions = false;
  const auto plain = emotion_displays(rec, t, o);
  ASSERT_EQ(plain.size(), 2u);  // fear, then fear + happiness
  EXPECT_DOUBLE_EQ(plain[1].timing.start, 4.15);
  EXPECT_DOUBLE_EQ(plain[1].intensities[1], 0.4);
  // a short gap shrinks the onset so that Do + Dr fits (thesis §4.4)
  const auto tight = emotion_displays(rec, {1, 2, 2.1, 2.2, 2.3}, o);
  for (const auto& item : tight) item.timing.validate();
  EXPECT_THROW(emotion_displays(rec, {1, 2, 3}, o), InvalidInput);
  EXPECT_THROW(emotion_displays(rec, {1, 2, 1, 4, 5}, o), InvalidInput);
  for (const auto& item : d) item.timing.validate();
}

}  // namespace
}  // namespace emoface::obie

namespace emoface::obie {
namespace {

// The §7.4 match's key moments (data/obie/match_7_4.json): 40.5' shows the blend of happiness and
// surprise (Fig. 7.9), 80' sadness (Fig. 7.8); the displays keep the blend (per-emotion reactions).
TEST(Pipeline, KeyMomentsOfTheMatchShowTheThesisExpressions) {
  const std::string file = std::string(EMOFACE_SOURCE_DIR) + "/data/obie/match_7_4.json";
  const MatchScript match = read_match_file(file);
  ObieOptions o = small_options();
  o.speech = false;
  o.render_frames = false;
  o.gltf_fps = 0;
  const ObieResult r =
      run_obie(match, parlee::read_agent_file(kAgent), face(), o, {}, nullptr, file);
  ASSERT_EQ(r.key_frames.size(), 4u);
  auto kf = [&](double minute) {
    for (const auto& k : r.key_frames)
      if (k.moment.minute == minute) return k;
    ADD_FAILURE() << "no key moment at " << minute;
    return KeyMomentFrame{};
  };
  constexpr std::size_t kSad = 0, kHappy = 1, kSurprise = 5;
  const auto goal = kf(40.5);
  for (std::size_t e : {0u, 2u, 3u, 4u}) {
    EXPECT_LT(goal.shown[e], goal.shown[kSurprise]) << e;
  }
  EXPECT_GT(goal.shown[kHappy], 0.9);
  EXPECT_GT(goal.shown[kSurprise], 0.5);
  EXPECT_EQ(expression_text(goal.shown).rfind("happiness 1.00 + surprise", 0), 0u)
      << expression_text(goal.shown);
  const auto late = kf(80);
  for (std::size_t e = 1; e < 6; ++e) EXPECT_LT(late.shown[e], late.shown[kSad]) << e;
  EXPECT_EQ(expression_text(late.shown).rfind("sadness", 0), 0u) << expression_text(late.shown);
  EXPECT_EQ(expression_text(kf(30).shown).rfind("happiness", 0), 0u)
      << expression_text(kf(30).shown);
  // §4.1: the broad smile of the lead outranks speech ("Yes, yes, yes!")
  bool outranks = false;
  for (const auto& item : r.script.emotions)
    if (item.timing.start <= goal.time && goal.time <= item.timing.end)
      outranks |= item.priority == 1;
  EXPECT_TRUE(outranks);
}

}  // namespace
}  // namespace emoface::obie

namespace emoface::obie {
namespace {

// Issue 17 item 3: Obie decays by match time. The long free-kick at 40' and the goal at 40.5' are
// half a minute apart, so surprise (Φ = 0.3 per minute, empty M column, ω = 1, r = 1/2) decays by
// half a minute between them: ψ = E·0.3^(1/4) / (1 + E·(1 − 0.3^(1/4))), not by two steps. The
// §7.4 timeline is byte-identical across two runs with one seed.
TEST(Pipeline, MatchTimeDecayAndAByteIdenticalTimeline) {
  const std::string file = std::string(EMOFACE_SOURCE_DIR) + "/data/obie/match_7_4.json";
  const MatchScript match = read_match_file(file);
  const auto agent = parlee::read_agent_file(kAgent);
  const auto records = run_match(match, agent, file);
  auto at = [&](double minute) {
    for (const auto& r : records)
      if (r.time == minute) return r;
    ADD_FAILURE() << "no record at " << minute;
    return parlee::StepRecord{};
  };
  // joy (Φ = 0.9 per minute) is not saturated at 40.5': by hand, with M's joy column (distress
  // 0.3, fear 0.2; S counts emotions ≥ α = 0.1) damping the goal's impulse
  const std::size_t joy = parlee::index(parlee::Emotion::Joy);
  const std::size_t dis = parlee::index(parlee::Emotion::Distress);
  const std::size_t fear = parlee::index(parlee::Emotion::Fear);
  const parlee::StepRecord free_kick = at(40), goal = at(40.5);
  const double e = free_kick.emotions[joy];
  ASSERT_GT(e, 0.05);
  const double q = std::pow(0.9, 0.25);  // e^(−aΔt) = Φ^(r·Δt/step) = 0.9^(0.5·30/60)
  const double psi = e * q / (1 + e * (1 - q));
  auto s_of = [&](std::size_t j) {
    return free_kick.emotions[j] >= 0.1 ? free_kick.emotions[j] : 0.0;
  };
  const double damp = std::min(1.0, 0.3 * s_of(dis) + 0.2 * s_of(fear));
  const double expected = psi + goal.impulse[joy] * (1 - damp);
  ASSERT_LT(expected, 0.99);
  EXPECT_NEAR(goal.emotions[joy], expected, 1e-12);
  // a whole step per event (the per-step clock) would have left less: 0.9·e < ψ
  EXPECT_GT(psi, 0.9 * e + 0.01 * e);

  ObieOptions o = small_options();
  o.speech = false;
  o.render_frames = false;
  o.gltf_fps = 0;
  o.seed = 11;
  const ObieResult a = run_obie(match, agent, face(), o, {}, nullptr, file);
  const ObieResult b = run_obie(match, agent, face(), o, {}, nullptr, file);
  const std::string ta = format_timeline(a);
  EXPECT_GT(ta.size(), 10000u);
  EXPECT_EQ(ta, format_timeline(b));
}

}  // namespace
}  // namespace emoface::obie
