#include "emoface/core/json_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

namespace emoface::core {
namespace {

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const FormatError& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kDoc = R"({"format": "emoface.thing", "version": "1.1", "generator": "emoface 0.1.0",
  "name": "x", "gain": 2.5, "count": 3, "flag": true, "list": [1, 2.5, "s"],
  "a/b": {"c~d": [0, {"deep": "no"}]}})";

TEST(JsonReader, TypedGettersReadValues) {
  JsonReader r(kDoc, "t.json", "thing", {1, 1});
  const JsonValue root = r.root();
  EXPECT_EQ(root.at("name").string(), "x");
  EXPECT_EQ(root.at("gain").number(), 2.5);
  EXPECT_EQ(root.at("gain").number(0, 10), 2.5);
  EXPECT_EQ(root.at("count").integer(0, 5), 3);
  EXPECT_EQ(root.at("count").index(10), 3u);
  EXPECT_TRUE(root.at("flag").boolean());
  EXPECT_EQ(root.at("list").items().size(), 3u);
  EXPECT_EQ(root.at("list")[1].number(), 2.5);
  EXPECT_EQ(root.number_or("missing", 7.0), 7.0);
  EXPECT_EQ(root.number_or("gain", 7.0), 2.5);
  EXPECT_EQ(root.string_or("missing", "d"), "d");
  EXPECT_FALSE(root.boolean_or("missing", false));
  EXPECT_TRUE(root.has("flag"));
  EXPECT_FALSE(root.has("nope"));
  EXPECT_FALSE(root.find("nope").has_value());
  EXPECT_EQ(r.version().minor, 1);
  EXPECT_TRUE(r.strict());
}

TEST(JsonReader, PointersAreEscapedRfc6901) {
  JsonReader r(kDoc, "t.json", "thing", {1, 1});
  const JsonValue deep = r.root().at("a/b").at("c~d")[1].at("deep");
  EXPECT_EQ(deep.pointer(), "/a~1b/c~0d/1/deep");
  EXPECT_EQ(message_of([&] { deep.number(); }),
            "t.json: at /a~1b/c~0d/1/deep: expected a number, got a string");
  // The escaped pointer resolves to the same value in nlohmann's own RFC 6901 implementation.
  EXPECT_EQ(r.root().json().at(nlohmann::ordered_json::json_pointer(deep.pointer())), "no");
}

TEST(JsonReader, OneMessageStyleForEveryMistake) {
  JsonReader r(kDoc, "t.json", "thing", {1, 1});
  const JsonValue root = r.root();
  EXPECT_EQ(message_of([&] { root.at("nope"); }), "t.json: missing field \"nope\"");
  EXPECT_EQ(message_of([&] { root.at("name").number(); }),
            "t.json: at /name: expected a number, got a string");
  EXPECT_EQ(message_of([&] { root.at("gain").number(0, 1); }),
            "t.json: at /gain: 2.5 is out of range [0, 1]");
  EXPECT_EQ(message_of([&] { root.at("gain").integer(0, 10); }),
            "t.json: at /gain: expected an integer, got 2.5");
  EXPECT_EQ(message_of([&] { root.at("count").integer(4, 10); }),
            "t.json: at /count: 3 is out of range [4, 10]");
  EXPECT_EQ(message_of([&] { root.at("list")[3]; }),
            "t.json: at /list: index 3 out of range (3 elements)");
  EXPECT_EQ(message_of([&] { root.at("list").expect_array(2); }),
            "t.json: at /list: expected 2 elements, got 3");
  EXPECT_EQ(message_of([&] { root.at("list")[2].boolean(); }),
            "t.json: at /list/2: expected true or false, got a string");
  EXPECT_EQ(message_of([&] { root.at("flag").at("x"); }),
            "t.json: at /flag: expected an object, got a boolean");
  EXPECT_EQ(message_of([&] { root.at("flag").items(); }),
            "t.json: at /flag: expected an array, got a boolean");
}

TEST(JsonReader, UnknownFieldsRejectedAtSameOrOlderMinor) {
  const std::string doc =
      R"({"format": "emoface.thing", "version": "1.0", "name": "x", "nmae": 1})";
  JsonReader same(doc, "t.json", "thing", {1, 0});
  EXPECT_EQ(message_of([&] { same.root().only_keys({"name"}); }),
            "t.json: at /nmae: unknown field \"nmae\"");
  JsonReader older(doc, "t.json", "thing", {1, 3});  // a 1.0 file read by a 1.3 reader
  EXPECT_TRUE(older.strict());
  EXPECT_THROW(JsonReader(doc, "t.json", "thing", {1, 3}).root().only_keys({"name"}), FormatError);
}

TEST(JsonReader, NewerMinorMayAddFields) {
  const std::string doc =
      R"({"format": "emoface.thing", "version": "1.4", "name": "x", "extra": 1})";
  JsonReader r(doc, "t.json", "thing", {1, 2});
  EXPECT_FALSE(r.strict());
  EXPECT_NO_THROW(r.root().only_keys({"name"}));
  // Known fields are still checked.
  EXPECT_EQ(r.root().at("name").string(), "x");
}

TEST(JsonReader, EnvelopeFieldsAllowedOnlyAtTheRoot) {
  const std::string doc =
      R"({"format": "emoface.thing", "version": "1.0", "generator": "g", "sub": {"version": 1}})";
  JsonReader r(doc, "t.json", "thing", {1, 0});
  EXPECT_NO_THROW(r.root().only_keys({"sub"}));
  EXPECT_EQ(message_of([&] { r.root().at("sub").only_keys({}); }),
            "t.json: at /sub/version: unknown field \"version\"");
  EXPECT_EQ(message_of([&] { r.root().only_keys(std::vector<std::string>{}); }),
            "t.json: at /sub: unknown field \"sub\"");
}

TEST(JsonReader, EnvelopeAndSyntaxErrorsAreLocated) {
  EXPECT_EQ(
      message_of([] {
        JsonReader("{\"format\": \"emoface.other\", \"version\": \"1.0\"}", "f", "thing", {1, 0});
      }),
      "f: at /format: unknown format \"emoface.other\" (expected \"emoface.thing\")");
  EXPECT_EQ(
      message_of([] {
        JsonReader("{\"format\": \"emoface.thing\", \"version\": \"2.0\"}", "f", "thing", {1, 0});
      }),
      "f: at /version: version 2.0 is newer than this reader (1.0); upgrade emoface");
  EXPECT_THROW(JsonReader("{\"format\": ", "f", "thing", {1, 0}), FormatError);
  EXPECT_THROW(JsonReader("", "f", "thing", {1, 0}), FormatError);
  EXPECT_THROW(JsonReader("[1]", "f", "thing", {1, 0}), FormatError);
}

TEST(JsonReader, UnversionedDocumentsChooseTheRule) {
  JsonReader strict(ParsedJson{nlohmann::ordered_json::parse(R"({"a": 1, "format": 2})")}, "u.json",
                    true);
  EXPECT_FALSE(strict.versioned());
  // Without an envelope "format" is an ordinary (here unknown) field.
  EXPECT_EQ(message_of([&] { strict.root().only_keys({"a"}); }),
            "u.json: at /format: unknown field \"format\"");
  JsonReader lax(ParsedJson{nlohmann::ordered_json::parse(R"({"a": 1, "b": 2})")}, "u.json", false);
  EXPECT_NO_THROW(lax.root().only_keys({"a"}));
}

TEST(JsonReader, HugeAndNonFiniteNumbers) {
  // The parser refuses 1e400 with its position.
  EXPECT_EQ(message_of([] {
              JsonReader(R"({"format": "emoface.thing", "version": "1.0", "big": 1e400})", "t.json",
                         "thing", {1, 0});
            }),
            "t.json: invalid JSON: number overflow parsing '1e400'");
  // A document built in code can hold NaN/inf: refused as a number, never returned.
  nlohmann::ordered_json built = {{"nan", std::nan("")}, {"inf", INFINITY}};
  JsonReader code(ParsedJson{built}, "code", true);
  EXPECT_EQ(message_of([&] { code.root().at("nan").number(); }),
            "code: at /nan: not a finite number");
  EXPECT_THROW(code.root().at("inf").number(0, 1), FormatError);
  JsonReader r(R"({"format": "emoface.thing", "version": "1.0",
                   "u": 18446744073709551615, "neg": -5})",
               "t.json", "thing", {1, 0});
  EXPECT_EQ(message_of([&] { r.root().at("u").integer(0, 10); }),
            "t.json: at /u: 18446744073709551615 is out of range [0, 10]");
  EXPECT_EQ(message_of([&] { r.root().at("neg").index(10); }),
            "t.json: at /neg: -5 is out of range [0, 10]");
}

TEST(JsonReader, RejectsUnknownFieldsRule) {
  EXPECT_TRUE(rejects_unknown_fields({1, 0}, {1, 0}));
  EXPECT_TRUE(rejects_unknown_fields({1, 0}, {1, 2}));
  EXPECT_FALSE(rejects_unknown_fields({1, 3}, {1, 2}));
}

}  // namespace
}  // namespace emoface::core
