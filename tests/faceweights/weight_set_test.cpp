#include "emoface/faceweights/weight_set.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"

namespace emoface::faceweights {
namespace {

std::string minimal(const std::string& targets, const std::string& extra = "") {
  return R"({"format": "emoface.faceweights", "version": "1.0", "set": "mine", "naming": "custom",)"
         R"( "ranges": {"head_yaw": 0.5}, "sources": [{"id": "s", "citation": "c"}],)" +
         extra + R"( "targets": )" + targets + "}";
}

void expect_format_error(const std::string& text, const std::string& needle) {
  try {
    parse_weight_set(text, "w.json");
    FAIL() << "no error for " << text;
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("w.json"), std::string::npos) << e.what();
  }
}

TEST(WeightSet, BuiltinSetsLoadAndValidate) {
  const auto& a = builtin_weight_set("arkit");
  EXPECT_EQ(a.targets.size(), 52u);
  EXPECT_EQ(a.naming, "arkit");
  const auto& f = builtin_weight_set("facs");
  EXPECT_GT(f.targets.size(), 40u);
  for (const auto* s : {&a, &f}) {
    for (const auto& t : s->targets) {
      EXPECT_FALSE(t.sources.empty()) << t.name;
      if (t.terms.empty()) EXPECT_FALSE(t.note.empty()) << t.name;
    }
  }
  // the shapes with no muscle say so
  for (const char* none : {"tongueOut", "cheekPuff", "jawForward", "jawLeft", "jawRight",
                           "mouthLeft", "mouthRight", "mouthClose"}) {
    const auto i = a.find(none);
    ASSERT_TRUE(i.has_value()) << none;
    EXPECT_TRUE(a.targets[*i].terms.empty()) << none;
  }
  EXPECT_THROW(builtin_weight_set("vrm"), InvalidInput);
}

TEST(WeightSet, FindAcceptsEveryArkitSpelling) {
  const auto& a = builtin_weight_set("arkit");
  const auto i = a.find("eyeBlink_L").value();
  EXPECT_EQ(a.find("eyeBlinkLeft").value(), i);
  EXPECT_EQ(a.find("EyeBlinkLeft").value(), i);
  EXPECT_FALSE(a.find("eyeBlinkMiddle").has_value());
  const auto& f = builtin_weight_set("facs");
  EXPECT_EQ(f.find("au12_l").value(), f.find("AU12_L").value());
}

TEST(WeightSet, RoundTripThroughFile) {
  for (const char* name : {"arkit", "facs"}) {
    const auto& s = builtin_weight_set(name);
    const auto dir = std::filesystem::temp_directory_path() / "emoface_faceweights_rt";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / (std::string(name) + ".json")).string();
    write_weight_set(path, s);
    const WeightSet back = read_weight_set(path);
    EXPECT_EQ(back.set, s.set);
    EXPECT_EQ(back.ranges, s.ranges);
    ASSERT_EQ(back.targets.size(), s.targets.size());
    for (std::size_t i = 0; i < s.targets.size(); ++i) {
      EXPECT_EQ(back.targets[i].name, s.targets[i].name);
      EXPECT_EQ(back.targets[i].facs, s.targets[i].facs);
      EXPECT_EQ(back.targets[i].note, s.targets[i].note);
      EXPECT_EQ(back.targets[i].sources, s.targets[i].sources);
      ASSERT_EQ(back.targets[i].terms.size(), s.targets[i].terms.size());
      for (std::size_t k = 0; k < s.targets[i].terms.size(); ++k) {
        EXPECT_EQ(back.targets[i].terms[k].input, s.targets[i].terms[k].input);
        EXPECT_DOUBLE_EQ(back.targets[i].terms[k].weight, s.targets[i].terms[k].weight);
      }
    }
    EXPECT_EQ(format_weight_set(back), format_weight_set(s));
  }
}

TEST(WeightSet, MinimalDocumentParses) {
  const auto s = parse_weight_set(
      minimal(R"([{"name": "a", "terms": {"x": 0.5, "head_yaw+": 1}, "sources": ["s"]}])"), "w.json");
  ASSERT_EQ(s.targets.size(), 1u);
  EXPECT_EQ(s.targets[0].terms.size(), 2u);
}

TEST(WeightSet, BadInputsNameFileAndField) {
  expect_format_error("{", "w.json:1");
  expect_format_error(R"({"format": "emoface.rig", "version": "1.0"})", "/format");
  expect_format_error(R"({"format": "emoface.faceweights", "version": "2.0"})", "newer");
  expect_format_error(minimal("[]"), "no targets");
  expect_format_error(minimal("{}"), "/targets");
  expect_format_error(minimal(R"([{"terms": {}}])"), "/targets/0");
  expect_format_error(minimal(R"([{"name": "a", "terms": {"x": "big"}}])"), "/targets/0/terms/x");
  expect_format_error(minimal(R"([{"name": "a", "terms": {"x": 1}}, {"name": "A", "terms": {"x": 1}}])"),
                      "repeated name");
  expect_format_error(minimal(R"([{"name": "a", "terms": {"eye_gaze_yaw+": 1}}])"),
                      "needs ranges/eye_gaze_yaw");
  expect_format_error(minimal(R"([{"name": "a", "terms": {"head_yaw+": 1, "head_yaw": 1}}])"),
                      "both as a level");
  expect_format_error(minimal(R"([{"name": "a", "terms": {}}])"), "needs a note");
  expect_format_error(minimal(R"([{"name": "a", "terms": {"x": 1}, "sources": ["nope"]}])"),
                      "unknown source id");
  expect_format_error(minimal(R"([{"name": "a", "terms": {"x": 1e300}}])"), "|w| <= 10");
  expect_format_error(minimal(R"([{"name": "a", "terms": {"x": 1}}])", R"( "colour": 1,)"),
                      "unknown field");
  expect_format_error(
      R"({"format": "emoface.faceweights", "version": "1.0", "set": "x", "naming": "arkit",)"
      R"( "sources": [], "targets": [{"name": "smileLeft", "terms": {"x": 1}}]})",
      "not an ARKit blend shape");
  EXPECT_THROW(read_weight_set("/nonexistent/w.json"), IoError);
  // Unknown fields inside targets and sources are errors too in a 1.0 file (core::JsonReader).
  expect_format_error(minimal(R"([{"name": "a", "terms": {"x": 1}, "notes": "typo"}])"),
                      "at /targets/0/notes: unknown field \"notes\"");
}

TEST(WeightSet, NewerMinorVersionMayAddFields) {
  const std::string doc =
      R"({"format": "emoface.faceweights", "version": "1.4", "set": "x", "naming": "facs",)"
      R"( "colour": 1, "sources": [{"id": "s", "citation": "c", "doi": "d"}],)"
      R"( "targets": [{"name": "a", "terms": {"x": 1}, "sources": ["s"], "weight_hint": 2}]})";
  const WeightSet s = parse_weight_set(doc, "w.json");
  ASSERT_EQ(s.targets.size(), 1u);
  EXPECT_EQ(s.targets[0].terms[0].weight, 1.0);
}

}  // namespace
}  // namespace emoface::faceweights
