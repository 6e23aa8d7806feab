#include "emoface/fuzzyexpr/io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/fuzzyexpr/engine.hpp"

namespace emoface::fuzzyexpr {
namespace {

using Json = nlohmann::ordered_json;
const std::string kRulesPath = std::string(EMOFACE_SOURCE_DIR) + "/data/fuzzyexpr/rules.json";

bool same(const RuleBase& a, const RuleBase& b) { return to_json_text(a) == to_json_text(b); }

TEST(RuleFile, DataFileMatchesBuiltInAndRoundTrips) {
  const RuleBase from_file = read_rule_base(kRulesPath);
  EXPECT_TRUE(same(from_file, default_rule_base()));
  const RuleBase again = parse_rule_base(to_json_text(from_file), "roundtrip");
  EXPECT_TRUE(same(from_file, again));
  EXPECT_EQ(again.input_sets.size(), 5u);
  EXPECT_EQ(again.blend.size(), 13u);
  EXPECT_EQ(again.no_blend.size(), 2u);
  // Same engine output after the round trip.
  Engine a(from_file), b(again);
  Esv esv{0.3, 0.1, 0.7, 0.2, 0.0, 0.45};
  EXPECT_EQ(a.convert(esv), b.convert(esv));
}

TEST(RuleFile, WriteIsAtomicAndReadable) {
  auto path = (std::filesystem::temp_directory_path() / "emoface_rules_roundtrip.json").string();
  write_rule_base(default_rule_base(), path);
  EXPECT_TRUE(same(read_rule_base(path), default_rule_base()));
  std::filesystem::remove(path);
  EXPECT_THROW(read_rule_base(path), IoError);
}

// Applies `edit` to the default document and expects FormatError at `pointer` mentioning `fragment`.
void expect_bad(const std::function<void(Json&)>& edit, const std::string& pointer,
                const std::string& fragment) {
  Json doc = Json::parse(core::read_file(kRulesPath));
  edit(doc);
  try {
    parse_rule_base(doc.dump(), "bad.json");
    FAIL() << "no error for expected " << pointer << " / " << fragment;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "bad.json");
    EXPECT_EQ(e.where().json_pointer, pointer) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(RuleFile, BadContentNamesTheField) {
  expect_bad([](Json& d) { d["format"] = "emoface.rig"; }, "/format", "unknown format");
  expect_bad([](Json& d) { d["version"] = "2.0"; }, "/version", "newer");
  expect_bad([](Json& d) { d.erase("input_sets"); }, "", "missing field \"input_sets\"");
  expect_bad([](Json& d) { d["single"]["joy"] = Json::array(); }, "/single/joy", "unknown emotion");
  expect_bad([](Json& d) { d["single"]["sadness"][0]["muscles"][1] = "buccinator"; },
             "/single/sadness/0/muscles/1", "unknown muscle");
  expect_bad([](Json& d) { d["single"]["sadness"][0]["levels"][2] = "Huge"; },
             "/single/sadness/0/levels/2", "undefined output set");
  expect_bad([](Json& d) { d["single"]["sadness"][0]["levels"].erase(4); },
             "/single/sadness/0/levels", "one level per input set");
  expect_bad([](Json& d) { d["single"]["fear"][1]["muscles"][0] = "depressor_labii"; },
             "/single/fear/1/muscles/0", "already has rules");
  expect_bad([](Json& d) { d["input_sets"][1]["points"] = {0.3, 0.2, 0.5}; },
             "/input_sets/1/points", "a <= b <= c <= d");
  expect_bad([](Json& d) { d["input_sets"][1]["points"] = {0.0, 0.23}; }, "/input_sets/1/points",
             "expected 3 numbers");
  expect_bad([](Json& d) { d["input_sets"][1]["points"][0] = "x"; }, "/input_sets/1/points/0",
             "expected a number");
  expect_bad([](Json& d) { d["input_sets"][2]["shape"] = "gaussian"; }, "/input_sets/2/shape",
             "unknown shape");
  expect_bad([](Json& d) { d["input_sets"][2]["name"] = "Low"; }, "/input_sets/2/name", "duplicate");
  expect_bad([](Json& d) { d["input_sets"][3]["points"] = {0.8, 0.9, 1.0}; }, "/input_sets",
             "do not cover");
  expect_bad([](Json& d) { d["input_sets"] = Json::array({d["input_sets"][0]}); }, "/input_sets",
             "2 to 16");
  expect_bad([](Json& d) { d["blend"][0]["emotions"] = {"fear", "fear"}; }, "/blend/0/emotions",
             "two different");
  expect_bad([](Json& d) { d["blend"][1]["emotions"] = {"fear", "surprise"}; }, "/blend/1/emotions",
             "more than once");
  expect_bad([](Json& d) { d["blend"][0]["second"][0] = "frontalis_medialis"; }, "/blend/0/second/0",
             "assigned twice");
  expect_bad([](Json& d) { d["no_blend"].erase(1); }, "/blend", "sadness+surprise");
  expect_bad([](Json& d) { d["blend"][0]["extra"] = 1; }, "/blend/0/extra", "unknown field");
  // A typo at the root of a same-version file is an error (issue 18: core::JsonReader's rule).
  expect_bad([](Json& d) { d["no_blnd"] = Json::array(); }, "/no_blnd", "unknown field");
  expect_bad([](Json& d) { d["input_sets"][0]["points"] = 3; }, "/input_sets/0/points",
             "expected 3 numbers");
  expect_bad([](Json& d) { d["single"] = Json::array(); }, "/single",
             "expected an object, got an array");
}

TEST(RuleFile, NewerMinorVersionMayAddFields) {
  Json doc = Json::parse(core::read_file(kRulesPath));
  doc["version"] = "1.7";
  doc["blend"][0]["comment"] = "a field from the future";
  EXPECT_NO_THROW(parse_rule_base(doc.dump(), "newer.json"));
}

TEST(RuleFile, MalformedAndTruncatedJson) {
  const std::string text = core::read_file(kRulesPath);
  for (std::size_t cut : {std::size_t{0}, std::size_t{1}, text.size() / 3, text.size() - 3}) {
    EXPECT_THROW(parse_rule_base(text.substr(0, cut), "cut.json"), FormatError) << cut;
  }
  try {
    parse_rule_base("{\n \"format\": \"emoface.fuzzyrules\",\n \"version\": 1.0,,\n}", "m.json");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().line, 3u);
  }
  EXPECT_THROW(parse_rule_base("[1, 2, 3]", "a.json"), FormatError);
  EXPECT_THROW(parse_rule_base(std::string(100000, '['), "deep.json"), FormatError);
}

TEST(Fll, ExportsEveryBlockAndVariable) {
  const std::string fll = to_fll(default_rule_base());
  EXPECT_NE(fll.find("Engine: emoface_fuzzyexpr"), std::string::npos);
  EXPECT_NE(fll.find("InputVariable: surprise"), std::string::npos);
  EXPECT_NE(fll.find("OutputVariable: masseter"), std::string::npos);
  EXPECT_NE(fll.find("RuleBlock: single_sadness"), std::string::npos);
  EXPECT_NE(fll.find("RuleBlock: blend_surprise_fear"), std::string::npos);
  EXPECT_NE(fll.find("rule: if sadness is High then triangularis is Medium"), std::string::npos);
  // "−" cells: "no contraction" by default (a rule to VerySmall), left out with NoRule
  EXPECT_NE(fll.find("rule: if sadness is VeryLow then triangularis is VerySmall"), std::string::npos);
  FllOptions no_rule;
  no_rule.missing_rule = MissingRule::NoRule;
  EXPECT_EQ(to_fll(default_rule_base(), no_rule).find("sadness is VeryLow then triangularis"), std::string::npos);
  FllOptions bad;
  bad.centroid_resolution = 1;
  EXPECT_THROW(to_fll(default_rule_base(), bad), InvalidInput);
}

}  // namespace
}  // namespace emoface::fuzzyexpr
