#include "emoface/runtime/character.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/mindmap/io.hpp"
#include "emoface/parlee/domain.hpp"
#include "emoface/parlee/io.hpp"

namespace emoface::runtime {
namespace {

const std::string kData = std::string(EMOFACE_SOURCE_DIR) + "/data";

CharacterConfig parlee_config() {
  CharacterConfig c;
  c.source = SourceKind::Parlee;
  c.domain_text = core::read_file(kData + "/parlee/football.domain");
  c.agent = parlee::read_agent_file(kData + "/parlee/agents/neutral.json");
  return c;
}

std::vector<parlee::Event> match_events() {
  return parlee::read_events_file(kData + "/parlee/match.ndjson");
}

std::size_t param(const std::string& name) {
  const auto& n = Character::parameter_names();
  return static_cast<std::size_t>(std::find(n.begin(), n.end(), name) - n.begin());
}

TEST(Character, FortyTwoParametersAndLatency) {
  Character c{CharacterConfig{}};
  EXPECT_EQ(Character::parameter_names().size(), 42u);
  EXPECT_EQ(c.parameters().size(), 42u);
  EXPECT_DOUBLE_EQ(c.latency(), 18.0 / 60.0);  // ceil(0.3 s · 60 fps) frames
  c.update(1.0);
  EXPECT_NEAR(c.output_time(), 1.0 - c.latency(), 1e-12);
}

TEST(Character, DirectEmotionsShowAfterTheLatencyAndSmile) {
  Character c{CharacterConfig{}};
  c.update(0.5);
  EXPECT_TRUE(c.push_event(R"j({"emotions": {"happiness": 0.9}})j").applied);
  c.update(0.2);  // still inside the latency: the output has not seen the event yet
  EXPECT_EQ(c.emotions()[1], 0.0);
  c.update(2.0);
  EXPECT_EQ(c.emotions()[1], 0.9);
  EXPECT_GT(c.parameters()[param("zygomatic_major_l")], 0.3);
  EXPECT_EQ(c.parameters()[param("zygomatic_major_l")], c.parameters()[param("zygomatic_major_r")]);
  // replace: the others go to 0; without it they are kept
  EXPECT_TRUE(c.push_event(R"j({"emotions": {"surprise": 0.5}})j").applied);
  c.update(1.0);
  EXPECT_EQ(c.emotions()[1], 0.9);
  EXPECT_EQ(c.emotions()[5], 0.5);
  EXPECT_TRUE(c.push_event(R"j({"emotions": {"sadness": 0.4}, "replace": true})j").applied);
  c.update(1.0);
  EXPECT_EQ(c.emotions(), (std::array<double, 6>{0.4, 0, 0, 0, 0, 0}));
}

TEST(Character, BadEventsAreReportedAndSkipped) {
  Character c{CharacterConfig{}};
  for (const char* bad :
       {"{", "[]", R"j({"emotions": {"joy": 1}})j", R"j({"emotions": {"happiness": 2}})j",
        R"j({"emotions": {"happiness": "x"}})j", R"j({"emotions": 3})j", R"j({"x": 1})j",
        R"j({"action": "(shot team)"})j", R"j({"stimulus": "gift"})j"}) {
    const EventResult r = c.push_event(bad);
    EXPECT_FALSE(r.applied) << bad;
    EXPECT_FALSE(r.message.empty()) << bad;
  }
  c.update(1.0);
  EXPECT_EQ(c.emotions(), (std::array<double, 6>{}));
}

TEST(Character, ParleeDecayPerSecondMatchesThePerStepFormAtTheStepLength) {
  // events one thesis step (1 s) apart: the runtime's time-based decay + update must equal the
  // agent's own per-step update (§5.6.3–5.6.4) exactly
  CharacterConfig cfg = parlee_config();
  Character c(cfg);
  parlee::DomainSpec spec;
  parlee::parse_domain_text(cfg.domain_text, "<domain>", spec);
  const parlee::Domain domain(spec);
  parlee::Agent reference(domain, cfg.agent);
  const auto events = match_events();
  for (std::size_t k = 0; k < 40; ++k) {
    c.update(1.0);
    parlee::Event e = events[k];
    e.time = static_cast<double>(k + 1);
    const parlee::StepRecord rec = reference.step(e);
    ASSERT_TRUE(c.push_parlee_event(events[k]).applied) << k;
    const auto occ = c.occ_emotions();
    for (std::size_t i = 0; i < parlee::kEmotionCount; ++i)
      ASSERT_EQ(occ[i], rec.emotions[i]) << k << " " << i;
  }
  // between events the decay is continuous, ParleE's law (parlee::decayed, §5.6.3 slower at low
  // intensity, r = 1/2): after another 2.5 s (2.5 steps) surprise (Φ = 0.3 with the neutral
  // personality's Φ = 0.3^(1.5 − 0.5), ω = 1) is E·q / (1 + E·(1 − q)), q = 0.3^(r·2.5) = 0.3^1.25
  const auto before = c.occ_emotions();
  c.update(2.5);
  const auto after = c.occ_emotions();
  const auto s = static_cast<std::size_t>(parlee::Emotion::Surprise);
  const double q = std::pow(0.3, 1.25);
  ASSERT_GT(before[s], 0.01);
  EXPECT_NEAR(after[s], before[s] * q / (1 + before[s] * (1 - q)), 1e-15);
  // halving the step length doubles the decay per second: 1 s = 2 steps; fear after the kick-off
  // (Φ = 0.85): q = 0.85^(0.5·2) = 0.85
  const auto fear = static_cast<std::size_t>(parlee::Emotion::Fear);
  CharacterConfig half = parlee_config();
  half.options.step_seconds = 0.5;
  Character h(half);
  h.update(1.0);
  ASSERT_TRUE(h.push_parlee_event(events[0]).applied);
  const auto h0 = h.occ_emotions();
  ASSERT_GT(h0[fear], 0.1);
  h.update(1.0);
  EXPECT_NEAR(h.occ_emotions()[fear], h0[fear] * 0.85 / (1 + h0[fear] * 0.15), 1e-15);
  // with every intensity alike (r = 1) the per-second law is E·Φ^(Δt/step): E·0.3^2.5 (surprise
  // after 40') and E·0.85² (fear after the kick-off, 2 steps)
  CharacterConfig flat = parlee_config();
  flat.agent.emotions.low_intensity_rate = 1.0;
  Character f(flat);
  f.update(1.0);
  for (std::size_t k = 0; k < 40; ++k) {
    ASSERT_TRUE(f.push_parlee_event(events[k]).applied);
    f.update(1.0);
  }
  const auto f0 = f.occ_emotions();
  ASSERT_GT(f0[s], 0.01);
  f.update(2.5);
  EXPECT_NEAR(f.occ_emotions()[s], f0[s] * std::pow(0.3, 2.5), 1e-15);
  flat.options.step_seconds = 0.5;
  Character fh(flat);
  fh.update(1.0);
  ASSERT_TRUE(fh.push_parlee_event(events[0]).applied);
  const auto fh0 = fh.occ_emotions();
  ASSERT_GT(fh0[fear], 0.1);
  fh.update(1.0);
  EXPECT_NEAR(fh.occ_emotions()[fear], fh0[fear] * 0.85 * 0.85, 1e-15);
}

TEST(Character, ParleeEventNotAllowedIsSkippedAndTheAgentStaysUsable) {
  const auto events = match_events();
  Character a(parlee_config()), b(parlee_config());
  a.update(1.0);
  b.update(1.0);
  const EventResult r = a.push_event(R"j({"action": "(fly-to-the-moon team)"})j");
  EXPECT_FALSE(r.applied);
  EXPECT_NE(r.message.find("not applicable"), std::string::npos) << r.message;
  EXPECT_FALSE(a.push_event(R"j({"action": "(shot team)", "feedback": 7})j").applied);
  for (std::size_t k = 0; k < 10; ++k) {
    ASSERT_TRUE(a.push_parlee_event(events[k]).applied);
    ASSERT_TRUE(b.push_parlee_event(events[k]).applied);
    a.update(1.0);
    b.update(1.0);
  }
  EXPECT_EQ(a.occ_emotions(), b.occ_emotions());
  EXPECT_EQ(a.parameters(), b.parameters());
}

TEST(Character, DeterministicWithASeed) {
  CharacterConfig cfg;
  cfg.options.seed = 5;
  Character a(cfg), b(cfg);
  cfg.options.seed = 6;
  Character other(cfg);
  bool differs = false;
  for (int i = 0; i < 600; ++i) {
    a.update(1.0 / 60);
    b.update(1.0 / 60);
    other.update(1.0 / 60);
    ASSERT_EQ(a.parameters(), b.parameters());
    differs |= a.parameters() != other.parameters();
  }
  EXPECT_TRUE(differs);
  // blinks happen (about one per 4 s) and close the lids fully
  double lid = 0;
  Character c{CharacterConfig{}};
  for (int i = 0; i < 1200; ++i) {
    c.update(1.0 / 60);
    lid = std::max(lid, c.parameters()[param("eye_blink_l")]);
  }
  EXPECT_GT(lid, 0.9);
}

channels::Utterance hand_utterance() {
  channels::Utterance u;
  u.sample_rate = 1000;
  u.phonemes = {
      {"h", 0, 0.08}, {"@", 0.08, 0.15}, {"l", 0.15, 0.22}, {"oU", 0.22, 0.5}, {"_:", 0.5, 0.6}};
  u.samples.assign(600, 0);
  return u;
}

// Runs `steps` updates of irregular length with events and speech, returning every output.
std::vector<double> run(Character& c, int from, int steps) {
  std::vector<double> out;
  for (int i = from; i < from + steps; ++i) {
    if (i % 97 == 13) c.speak(hand_utterance());
    c.update(i % 3 == 0 ? 1.0 / 30 : 1.0 / 60);
    out.insert(out.end(), c.parameters().begin(), c.parameters().end());
    out.insert(out.end(), c.emotions().begin(), c.emotions().end());
  }
  return out;
}

TEST(Character, SnapshotRestoreContinuesBitIdentically) {
  const auto events = match_events();
  std::vector<CharacterConfig> configs;
  configs.push_back(CharacterConfig{});
  configs.push_back(parlee_config());
  CharacterConfig mm;
  mm.source = SourceKind::MindMap;
  mm.map = mindmap::read_mind_map(kData + "/mindmap/characters/ana.json");
  configs.push_back(mm);
  for (const auto& cfg : configs) {
    Character a(cfg);
    a.push_event(R"j({"emotions": {"happiness": 0.7, "surprise": 0.4}})j");
    if (cfg.source == SourceKind::Parlee) {
      for (std::size_t k = 0; k < 3; ++k) ASSERT_TRUE(a.push_parlee_event(events[k]).applied);
    }
    if (cfg.source == SourceKind::MindMap) {
      ASSERT_TRUE(a.push_event(R"j({"stimulus": "gift", "weights": {"happiness": 0.9}})j").applied)
          << to_string(cfg.source);
    }
    run(a, 0, 150);
    const std::string snap = a.snapshot();
    Character b = restore_character(snap, "snap.json");
    EXPECT_EQ(b.snapshot(), snap);  // the snapshot round trip is exact
    const auto ra = run(a, 150, 400);
    const auto rb = run(b, 150, 400);
    ASSERT_EQ(ra.size(), rb.size());
    for (std::size_t i = 0; i < ra.size(); ++i)
      ASSERT_EQ(ra[i], rb[i]) << to_string(cfg.source) << " value " << i;
  }
}

TEST(Character, SnapshotBadInput) {
  Character a{CharacterConfig{}};
  a.update(0.5);
  const std::string snap = a.snapshot();
  EXPECT_THROW(restore_character("{", "s.json"), FormatError);
  EXPECT_THROW(restore_character(R"j({"format": "emoface.character_state", "version": "2.0"})j"),
               FormatError);
  EXPECT_THROW(restore_character(R"j({"format": "emoface.character_state", "version": "1.0"})j"),
               FormatError);
  std::string bad = snap;
  bad.replace(bad.find("\"frames_in\":"), 12, "\"frames_in\":-");
  EXPECT_THROW(restore_character(bad), FormatError);
  std::string clock = snap;
  const std::size_t at = clock.find("\"time\":") + 7;
  clock.replace(at, clock.find(',', at) - at,
                "100000000.0");  // the mixer's frames no longer match the clock
  try {
    restore_character(clock, "s.json");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("/mixer/frames_in"), std::string::npos) << e.what();
  }
  try {
    std::string wrong = snap;
    wrong.replace(wrong.find("\"esv_out\":["), 11, "\"esv_out\":[7,");
    restore_character(wrong, "s.json");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("/esv_out"), std::string::npos) << e.what();
  }
}

TEST(Character, ShippedConfigs) {
  const CharacterConfig obie = read_character_config(kData + "/runtime/obie.json");
  EXPECT_EQ(obie.source, SourceKind::Parlee);
  EXPECT_EQ(obie.face, "default");
  Character o(obie);
  o.update(1.0);
  EXPECT_TRUE(o.push_parlee_event(match_events()[0]).applied);
  const CharacterConfig ana = read_character_config(kData + "/runtime/ana.json");
  EXPECT_EQ(ana.map.character, "ana");
  Character a(ana);
  EXPECT_TRUE(a.push_event(R"j({"stimulus": "gift"})j").applied);
  const EventResult unknown = a.push_event(R"j({"stimulus": "no-such-stimulus"})j");
  EXPECT_FALSE(unknown.applied);
  EXPECT_FALSE(unknown.message.empty());
  a.update(2.0);
  EXPECT_GT(a.emotions()[1], 0.1);  // the gift made ana happy (her map: gift → happiness 0.9)
  EXPECT_EQ(read_character_config(kData + "/runtime/direct.json").source, SourceKind::Direct);
}

TEST(Character, ConfigRoundTripAndBadInput) {
  const CharacterConfig c = parse_character_config(format_character_config(parlee_config()));
  EXPECT_EQ(c.source, SourceKind::Parlee);
  EXPECT_EQ(format_character_config(c), format_character_config(parlee_config()));
  const std::string env = R"j({"format": "emoface.character", "version": "1.0", )j";
  const auto err = [](const std::string& text) {
    try {
      parse_character_config(text, "c.json");
    } catch (const FormatError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(err(env + R"j("fps": 5})j").find("fps"), std::string::npos);
  EXPECT_NE(err(env + R"j("lookahead": 0.5})j").find("lookahead"), std::string::npos);
  EXPECT_NE(err(env + R"j("lookahead": "x"})j").find("/lookahead"), std::string::npos);
  EXPECT_NE(err(env + R"j("colour": 1})j").find("/colour"), std::string::npos);
  EXPECT_NE(err(env + R"j("source": {"kind": "oracle"}})j").find("/source/kind"),
            std::string::npos);
  EXPECT_NE(err(env + R"j("source": {"kind": "parlee"}})j").find("/source"), std::string::npos);
  EXPECT_NE(err(env + R"j("speech": {"rate": 1e9}})j").find("rate"), std::string::npos);
  EXPECT_NE(err("{").find("c.json"), std::string::npos);
  EXPECT_EQ(parse_character_config(env + R"j("seed": 9})j").options.seed, 9u);
}

// The unknown-field rule of docs/formats.md (core::JsonReader, issue 18 item 1): a newer minor
// version may add fields (ignored), the same or an older one rejects them with a located error.
TEST(Character, UnknownFieldRuleOfTheFormats) {
  const auto doc = [](const std::string& version, const std::string& body) {
    return R"j({"format": "emoface.character", "version": ")j" + version + "\", " + body + "}";
  };
  const auto err = [](const std::string& text) {
    try {
      parse_character_config(text, "c.json");
    } catch (const FormatError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string extra = R"j("seed": 4, "colour": 1, "display": {"onset": 0.5, "sparkle": 2},)j"
                            R"j( "source": {"kind": "direct", "mood": "x"})j";
  for (const char* v : {"1.0", "1.1"}) {
    const std::string e = err(doc(v, extra));
    EXPECT_NE(e.find("c.json: at /colour: unknown field \"colour\""), std::string::npos) << e;
    EXPECT_NE(err(doc(v, R"j("display": {"sparkle": 2})j")).find("at /display/sparkle"),
              std::string::npos);
    EXPECT_NE(err(doc(v, R"j("source": {"kind": "direct", "mood": "x"})j")).find("/source/mood"),
              std::string::npos);
  }
  const CharacterConfig newer = parse_character_config(doc("1.7", extra), "c.json");  // ignored
  EXPECT_EQ(newer.options.seed, 4u);
  EXPECT_EQ(newer.options.display.onset, 0.5);
  EXPECT_NE(err(doc("2.0", R"j("seed": 4)j")).find("c.json"), std::string::npos);
  // a newer minor still checks the fields it knows, with their pointers
  EXPECT_NE(err(doc("1.7", R"j("display": {"onset": "x"})j")).find("c.json: at /display/onset"),
            std::string::npos);
  EXPECT_NE(err(doc("1.1", R"j("mix": {"priority": [1, 2]})j")).find("/mix/priority"),
            std::string::npos);
  EXPECT_EQ(parse_character_config(doc("1.1", R"j("seed": 18446744073709551615)j")).options.seed,
            18446744073709551615u);
  EXPECT_NE(err(doc("1.1", R"j("seed": -1)j")).find("/seed"), std::string::npos);

  // snapshots (emoface.character_state 1.0): a 1.x newer minor with added fields restores and
  // continues identically; 1.0 with an added field is refused at its pointer
  Character a{CharacterConfig{}};
  a.push_event(R"j({"emotions": {"happiness": 0.7}})j");
  a.update(1.0);
  const std::string snap = a.snapshot();
  const std::string v10 = R"j("version":"1.0")j";
  ASSERT_NE(snap.find(v10), std::string::npos);
  std::string added = snap;
  added.replace(added.find("\"mixer\":{"), 9, R"j("mixer":{"lanes":3,)j");
  added.replace(added.find("\"esv_out\":"), 10, R"j("weather":"rain","esv_out":)j");
  try {
    restore_character(added, "s.json");
    ADD_FAILURE() << "an unknown field of a 1.0 snapshot was accepted";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: at /"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("unknown field"), std::string::npos) << e.what();
  }
  std::string newer_snap = added;
  newer_snap.replace(newer_snap.find(v10), v10.size(), R"j("version":"1.3")j");
  Character b = restore_character(newer_snap, "s.json");
  for (int i = 0; i < 120; ++i) {
    a.update(1.0 / 60);
    b.update(1.0 / 60);
    ASSERT_EQ(a.parameters(), b.parameters()) << i;
  }
}

TEST(Character, ArkitAndFacsWeights) {
  Character c{CharacterConfig{}};
  ASSERT_EQ(Character::arkit_names().size(), 52u);
  c.update(0.5);
  ASSERT_EQ(c.arkit().size(), 52u);
  const auto smile = static_cast<std::size_t>(
      std::find(Character::arkit_names().begin(), Character::arkit_names().end(), "mouthSmile_L") -
      Character::arkit_names().begin());
  ASSERT_LT(smile, 52u);
  EXPECT_EQ(c.arkit()[smile], 0.0);
  c.push_emotions({0, 1, 0, 0, 0, 0});
  c.update(2.0);
  EXPECT_GT(c.arkit()[smile], 0.2);
  for (double w : c.arkit()) EXPECT_TRUE(w >= 0 && w <= 1);
  EXPECT_EQ(c.facs().size(), Character::facs_names().size());
  EXPECT_GT(*std::max_element(c.facs().begin(), c.facs().end()), 0.2);
}

TEST(Character, FaceVerticesOnRequest) {
  CharacterConfig cfg;
  cfg.face = "default";
  cfg.options.blinks = cfg.options.gaze_noise = cfg.options.head_noise = false;
  Character c(cfg);
  ASSERT_TRUE(c.has_face());
  c.update(0.1);
  const facemesh::Vertices neutral = c.vertices();
  EXPECT_EQ(neutral.rows(), c.mesh().vertices.rows());
  // no emotion: the neutral face (the default face's lips are rebuilt from the lip surface, S(u, v)
  // + offset, which reproduces the neutral to rounding, ~5e-10 m)
  EXPECT_LT((neutral - c.mesh().vertices).cwiseAbs().maxCoeff(), 1e-8);
  c.push_emotions({0, 1, 0, 0, 0, 0});
  c.update(2.0);
  EXPECT_GT((c.vertices() - neutral).cwiseAbs().maxCoeff(), 1e-3);  // the smile moved the face (m)
  Character none{CharacterConfig{}};
  EXPECT_THROW(none.vertices(), InvalidInput);
}

TEST(Character, SpeechFromTheEspeakProgramMovesTheLips) {
  CharacterConfig cfg;
  cfg.options.blinks = cfg.options.gaze_noise = cfg.options.head_noise = false;
  Character c(cfg);
  double start = -1;
  const channels::Utterance u = c.speak("Oh, really? I like it very much.", &start);
  EXPECT_NEAR(start, 0.2, 1e-12);  // after the silence pad
  double jaw = 0;
  for (int i = 0; i < 240; ++i) {
    c.update(1.0 / 60);
    jaw = std::max(jaw, c.parameters()[param("masseter")]);
  }
  EXPECT_GT(u.duration(), 2.0);
  EXPECT_GT(jaw, 0.3);
}

}  // namespace
}  // namespace emoface::runtime
