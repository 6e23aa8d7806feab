#include "emoface/obie/utterances.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::obie {
namespace {

// Records with the given happiness (index 1) and fear (index 3) per step, one step per second.
std::vector<parlee::StepRecord> records(const std::vector<double>& happy, const std::vector<double>& fear = {}) {
  std::vector<parlee::StepRecord> out(happy.size());
  for (std::size_t k = 0; k < happy.size(); ++k) {
    out[k].time = static_cast<double>(k);
    out[k].basic[1] = out[k].shown[1] = happy[k];
    out[k].basic[3] = out[k].shown[3] = k < fear.size() ? fear[k] : 0.0;
  }
  return out;
}

std::vector<double> seconds(std::size_t n) {
  std::vector<double> s(n);
  for (std::size_t k = 0; k < n; ++k) s[k] = 10.0 + static_cast<double>(k);
  return s;
}

UtteranceSet simple() {
  UtteranceSet set;
  set.refractory = 3;
  set.delay = 0.5;
  set.max_wait = 2;
  set.rules = {{"happiness", 0.4, 0.3, {"Yes!"}}, {"fear", 0.5, 0.3, {"Oh no!", "Careful!", "No, no!"}}};
  return set;
}

TEST(Utterances, CrossingAndRise) {
  // happiness crosses 0.4 at step 2, stays, jumps by 0.35 at step 6 (fires again), drifts at step 8
  const auto rec = records({0, 0.2, 0.45, 0.5, 0.5, 0.45, 0.8, 0.7, 0.75});
  const auto u = choose_utterances(rec, seconds(rec.size()), simple(), 7);
  ASSERT_EQ(u.size(), 2u);
  EXPECT_EQ(u[0].step, 2u);
  EXPECT_DOUBLE_EQ(u[0].time, 12.5);  // step time 12 + delay 0.5
  EXPECT_EQ(u[0].text, "Yes!");
  EXPECT_DOUBLE_EQ(u[0].intensity, 0.45);
  EXPECT_EQ(u[1].step, 6u);
  EXPECT_DOUBLE_EQ(u[1].time, 16.5);
  EXPECT_EQ(u[0].emotion, "happiness");
}

TEST(Utterances, RefractoryPostponesOrDrops) {
  // happiness crosses at step 1; fear crosses at step 2 (1 s later): postponed to 11.5 + 3 = 14.5 (2 s
  // late, within max_wait); a second fear crossing at step 4 would be at 14.5 → 17.5 (3 s late): dropped
  const auto rec = records({0, 0.5, 0.5, 0.5, 0.5, 0.5}, {0, 0, 0.6, 0.2, 0.6, 0.6});
  const auto u = choose_utterances(rec, seconds(rec.size()), simple(), 1);
  ASSERT_EQ(u.size(), 2u);
  EXPECT_EQ(u[0].emotion, "happiness");
  EXPECT_DOUBLE_EQ(u[0].time, 11.5);
  EXPECT_EQ(u[1].emotion, "fear");
  EXPECT_DOUBLE_EQ(u[1].time, 14.5);
}

TEST(Utterances, DurationKeepsUtterancesApart) {
  const auto rec = records({0, 0.5, 0, 0, 0.5, 0});
  auto set = simple();
  set.max_wait = 10;
  const auto u = choose_utterances(rec, seconds(rec.size()), set, 1, [](const std::string&) { return 4.0; });
  ASSERT_EQ(u.size(), 2u);
  EXPECT_DOUBLE_EQ(u[0].time, 11.5);
  EXPECT_DOUBLE_EQ(u[1].time, 11.5 + 4.0 + 0.3);  // previous duration + 0.3 s beats the 3 s refractory
}

TEST(Utterances, StrongestRuleWinsAtOneStep) {
  const auto rec = records({0, 0.45}, {0, 0.95});  // happiness 0.05 above its threshold, fear 0.45
  const auto u = choose_utterances(rec, seconds(2), simple(), 1);
  ASSERT_EQ(u.size(), 1u);
  EXPECT_EQ(u[0].emotion, "fear");
}

TEST(Utterances, SeededChoice) {
  std::vector<double> fear(200, 0.0);
  for (std::size_t k = 0; k < fear.size(); k += 10) fear[k] = 0.9;
  const auto rec = records(std::vector<double>(200, 0.0), fear);
  const auto a = choose_utterances(rec, seconds(rec.size()), simple(), 42);
  const auto b = choose_utterances(rec, seconds(rec.size()), simple(), 42);
  const auto c = choose_utterances(rec, seconds(rec.size()), simple(), 43);
  ASSERT_EQ(a.size(), 19u);
  std::set<std::string> texts;
  bool differs = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].text, b[i].text);
    differs = differs || a[i].text != c[i].text;
    texts.insert(a[i].text);
  }
  EXPECT_TRUE(differs);
  EXPECT_EQ(texts.size(), 3u);  // every text gets chosen over 19 draws (P(miss one) < 1e-3)
}

TEST(Utterances, BuiltInSetIsTheDataFile) {
  const auto& set = default_utterances();
  set.validate();
  const auto file = read_utterances_file(std::string(EMOFACE_SOURCE_DIR) + "/data/obie/utterances.json");
  EXPECT_EQ(write_utterances(file), write_utterances(set));
  bool fear = false;
  for (const auto& r : set.rules)
    if (r.emotion == "fear") fear = std::find(r.texts.begin(), r.texts.end(), "Oh no!") != r.texts.end();
  EXPECT_TRUE(fear);  // thesis §7.2: fear → "Oh no!"
  EXPECT_EQ(write_utterances(parse_utterances(write_utterances(set), "x")), write_utterances(set));
}

std::string error_of(const std::string& body) {
  try {
    parse_utterances(R"({"format": "emoface.obie.utterances", "version": "1.0", )" + body + "}", "u.json");
  } catch (const FormatError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Utterances, UnknownFieldRule) {
  const std::string body =
      R"("rules": [{"emotion": "fear", "texts": ["x"], "pitch": 3}], "voice": 1)";
  EXPECT_EQ(error_of(body), "u.json: at /voice: unknown field \"voice\"");
  EXPECT_EQ(error_of(body.substr(0, body.find(", \"voice\""))),
            "u.json: at /rules/0/pitch: unknown field \"pitch\"");
  const std::string newer =
      R"({"format": "emoface.obie.utterances", "version": "1.2", )" + body + "}";
  EXPECT_EQ(parse_utterances(newer, "u.json").rules.size(), 1u);
}

TEST(Utterances, BadFilesNameTheirPlace) {
  EXPECT_NE(error_of(R"("refractory": 3)").find("rules"), std::string::npos);
  EXPECT_NE(error_of(R"("rules": [{"emotion": "glee", "texts": ["x"]}])").find("/rules/0/emotion"), std::string::npos);
  EXPECT_NE(error_of(R"("rules": [{"emotion": "fear", "threshold": 1.5, "texts": ["x"]}])").find("/rules/0/threshold"),
            std::string::npos);
  EXPECT_NE(error_of(R"("rules": [{"emotion": "fear", "threshold": 0, "texts": ["x"]}])").find("/rules/0/threshold"),
            std::string::npos);
  EXPECT_NE(error_of(R"("rules": [{"emotion": "fear", "texts": []}])").find("/rules/0/texts"), std::string::npos);
  EXPECT_NE(error_of(R"("rules": [{"emotion": "fear", "texts": [""]}])").find("/rules/0/texts/0"), std::string::npos);
  EXPECT_NE(error_of(R"("rules": [{"emotion": "fear", "texts": [")" + std::string(300, 'a') + R"("]}])")
                .find("/rules/0/texts/0"),
            std::string::npos);
  EXPECT_NE(error_of(R"("refractory": 0.1, "rules": [])").find("/refractory"), std::string::npos);
  EXPECT_NE(error_of(R"("delay": -1, "rules": [])").find("/delay"), std::string::npos);
  EXPECT_NE(error_of(R"("rules": [], "extra": 1)").find("/extra"), std::string::npos);
  EXPECT_NE(error_of(R"("rules": [{"emotion": "fear", "texts": ["x"], "pitch": 3}])").find("/rules/0/pitch"),
            std::string::npos);
  EXPECT_THROW(parse_utterances("{\"format\": \"emoface.obie.utterances\", \"vers", "u.json"), FormatError);
  EXPECT_THROW(esv_index("joy"), InvalidInput);
  EXPECT_EQ(esv_index("surprise"), 5u);
}

TEST(Utterances, RejectsMismatchedSizes) {
  const auto rec = records({0, 1});
  EXPECT_THROW(choose_utterances(rec, {1.0}, simple(), 1), InvalidInput);
  auto set = simple();
  set.rules[0].texts.clear();
  EXPECT_THROW(choose_utterances(rec, seconds(2), set, 1), InvalidInput);
}

}  // namespace
}  // namespace emoface::obie
