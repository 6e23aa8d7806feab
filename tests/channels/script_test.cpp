#include "emoface/channels/script.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emoface/channels/parameters.hpp"
#include "emoface/core/errors.hpp"

namespace emoface::channels {
namespace {

void expect_error_at(const std::string& xml, std::size_t line, std::size_t column, const std::string& needle) {
  try {
    parse_script(xml, "s.xml");
    ADD_FAILURE() << "no error for: " << xml;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "s.xml");
    EXPECT_EQ(e.where().line, line) << e.what();
    if (column) EXPECT_EQ(e.where().column, column) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(Script, ThesisExampleWithTypographicQuotes) {
  const Script s = parse_script(
      "<PHONEME time=\xE2\x80\x9C" "0\xE2\x80\x9D text=\xE2\x80\x9COh really? I like it very much.\xE2\x80\x9D />\n"
      "<EMOTIONDISPLAY time=\"0\" duration=\"2.0\" Surprise=\"0.7\" />");
  ASSERT_EQ(s.speech.size(), 1u);
  EXPECT_EQ(s.speech[0].text, "Oh really? I like it very much.");
  ASSERT_EQ(s.emotions.size(), 1u);
  EXPECT_DOUBLE_EQ(s.emotions[0].intensities[5], 0.7);
  EXPECT_DOUBLE_EQ(s.emotions[0].timing.end, 2.0);
  EXPECT_EQ(s.emotions[0].where.line, 2u);
}

TEST(Script, AllElements) {
  const Script s = parse_script(R"(<SCRIPT>
    <signal time="1" duration="1" onset="0.2" offset="0.3" frontalis_medialis="0.6" masseter="0.1"/>
    <GAZE time="0" duration="1" yaw="0.2"/>
    <HEAD time="0.5" duration="2" pitch="-0.1" roll="0.05"/>
    <BLINK time="3"/>
    <EMBLEM time="4" duration="1" Disgust="0.8"/>
    <VISEME time="0" duration="0.1" name="AA"/>
  </SCRIPT>)");
  ASSERT_EQ(s.movements.size(), 4u);
  EXPECT_EQ(s.movements[0].channel, Channel::ConversationalSignal);
  EXPECT_EQ(s.movements[0].movement.targets.size(), 3u);  // medialis both sides + masseter
  EXPECT_DOUBLE_EQ(s.movements[0].movement.timing.onset, 0.2);
  EXPECT_EQ(s.movements[1].movement.targets[0].parameter, "eye_gaze_yaw");
  EXPECT_EQ(s.movements[2].movement.targets.size(), 2u);
  EXPECT_EQ(s.movements[3].channel, Channel::Manipulator);
  EXPECT_TRUE(s.emotions[0].emblem);
  EXPECT_EQ(s.visemes.size(), 1u);
}

TEST(Script, DefaultOnsetShrinksToFitShortDurations) {
  const Script s = parse_script(R"(<SIGNAL time="0" duration="0.5" masseter="1"/>)");
  EXPECT_NEAR(s.movements[0].movement.timing.onset + s.movements[0].movement.timing.offset, 0.5, 1e-12);
}

TEST(Script, Errors) {
  expect_error_at("<PHONEME time=\"0\" text=\"a\"", 1, 0, "malformed");
  expect_error_at("\n\n  <FOO time=\"1\"/>", 3, 3, "unknown element");
  expect_error_at("<PHONEME time=\"0\" text=\"  \"/>", 1, 1, "non-empty");
  expect_error_at("<PHONEME time=\"-1\" text=\"hi\"/>", 1, 1, "time");
  expect_error_at("<PHONEME time=\"x\" text=\"hi\"/>", 1, 1, "not a finite number");
  expect_error_at("<PHONEME time=\"nan\" text=\"hi\"/>", 1, 1, "not a finite number");
  expect_error_at("<PHONEME text=\"hi\"/>", 1, 1, "needs the attribute");
  expect_error_at("<PHONEME time=\"0\" text=\"hi\" speed=\"2\"/>", 1, 1, "unknown attribute");
  expect_error_at("<EMOTIONDISPLAY time=\"0\" duration=\"1\" Joy=\"1\"/>", 1, 1, "unknown attribute");
  expect_error_at("<EMOTIONDISPLAY time=\"0\" duration=\"1\"/>", 1, 1, "names no emotion");
  expect_error_at("<EMOTIONDISPLAY time=\"0\" duration=\"1\" Fear=\"1.5\"/>", 1, 1, "[0,1]");
  expect_error_at("<EMOTIONDISPLAY time=\"0\" duration=\"-1\" Fear=\"1\"/>", 1, 1, "duration");
  expect_error_at("<EMOTIONDISPLAY time=\"0\" duration=\"1\" onset=\"0.8\" offset=\"0.8\" Fear=\"1\"/>", 1, 1, "exceed");
  expect_error_at("<SIGNAL time=\"0\" duration=\"1\" nose=\"1\"/>", 1, 1, "unknown parameter");
  expect_error_at("<SIGNAL time=\"0\" duration=\"1\" masseter_l=\"1\"/>", 1, 1, "unknown parameter");
  expect_error_at("<SIGNAL time=\"0\" duration=\"1\"/>", 1, 1, "no parameter");
  expect_error_at("<GAZE time=\"0\" duration=\"1\" yaw=\"4\"/>", 1, 1, "1.6");
  expect_error_at("<SCRIPT>text</SCRIPT>", 1, 0, "unexpected text");
  expect_error_at("<!-- nothing -->", 1, 1, "no elements");
  expect_error_at("<PHONEME time=\"0\" text=\"\xff\"/>", 1, 0, "UTF-8");
  expect_error_at("<VISEME time=\"0\" duration=\"1\"/>", 1, 1, "name");
}

std::vector<Target> fake_mapper(const std::array<double, 6>& e) {
  return {{"zygomatic_major_l", e[1]}, {"frontalis_medialis_l", e[5]}};
}

TEST(Script, TimelineOrderErrorsNameTheElement) {
  TimelineOptions o;
  const VisemeSet vs = default_viseme_set();
  const Script same_start = parse_script(
      "<EMOTIONDISPLAY time=\"1\" duration=\"2\" Happiness=\"1\"/>\n<EMBLEM time=\"1\" duration=\"3\" Fear=\"1\"/>",
      "s.xml");
  try {
    build_timeline(same_start, {}, vs, fake_mapper, o, 1);
    ADD_FAILURE();
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().line, 2u);
  }
  const Script inverted = parse_script(
      "<SIGNAL time=\"0\" duration=\"5\" masseter=\"1\"/>\n<SIGNAL time=\"1\" duration=\"1\" masseter=\"0.5\"/>", "s.xml");
  EXPECT_THROW(build_timeline(inverted, {}, vs, fake_mapper, o, 1), FormatError);
  const Script overlap = parse_script(
      "<PHONEME time=\"0\" text=\"a\"/>\n<VISEME time=\"0.05\" duration=\"0.1\" name=\"AA\"/>", "s.xml");
  EXPECT_THROW(build_timeline(overlap, {{{"a", 0.0, 0.2}}}, vs, fake_mapper, o, 1), FormatError);
  const Script unknown = parse_script("<VISEME time=\"0\" duration=\"0.1\" name=\"ZZ\"/>", "s.xml");
  EXPECT_THROW(build_timeline(unknown, {}, vs, fake_mapper, o, 1), FormatError);
}

TEST(Script, TimelineFromPhonemesIsDeterministic) {
  const Script s = parse_script(
      "<PHONEME time=\"0.5\" text=\"ma\"/>\n<EMOTIONDISPLAY time=\"0\" duration=\"3\" Happiness=\"1\"/>\n"
      "<HEAD time=\"1\" duration=\"1\" yaw=\"0.2\"/>");
  const std::vector<std::vector<PhonemeTiming>> ph = {{{"m", 0.0, 0.08}, {"a", 0.08, 0.3}, {"_:", 0.3, 0.4}}};
  const TimelineOptions o;
  const Timeline a = build_timeline(s, ph, default_viseme_set(), fake_mapper, o, 9);
  const Timeline b = build_timeline(s, ph, default_viseme_set(), fake_mapper, o, 9);
  const Timeline c = build_timeline(s, ph, default_viseme_set(), fake_mapper, o, 10);
  ASSERT_EQ(a.lip.size(), 5u);  // pad, m, a, _:, pad
  EXPECT_EQ(a.lip[0].viseme, "sil");
  EXPECT_DOUBLE_EQ(a.lip[0].start, 0.3);
  EXPECT_EQ(a.lip[1].viseme, "PBM");
  EXPECT_DOUBLE_EQ(a.lip[1].start, 0.5);
  EXPECT_EQ(a.lip[2].viseme, "AA");
  const auto& head = a.movements[static_cast<std::size_t>(Channel::Head)];
  ASSERT_FALSE(head.empty());
  for (std::size_t k = 0; k < a.movements.size(); ++k) {
    ASSERT_EQ(a.movements[k].size(), b.movements[k].size());
    for (std::size_t i = 0; i < a.movements[k].size(); ++i)
      EXPECT_EQ(a.movements[k][i].timing.start, b.movements[k][i].timing.start);
  }
  EXPECT_NE(a.movements[static_cast<std::size_t>(Channel::Gaze)][0].targets[0].value,
            c.movements[static_cast<std::size_t>(Channel::Gaze)][0].targets[0].value);
  // explicit head movement kept, noise kept away from it
  int explicit_head = 0;
  for (const auto& m : head) explicit_head += m.label.rfind("HEAD", 0) == 0;
  EXPECT_EQ(explicit_head, 1);
  RenderOptions ro;
  ro.fps = 1000;
  const Tracks t = render(a, default_viseme_set(), default_conflict_table(), ro);
  EXPECT_NO_THROW(t.validate());
  // continuity of every track (speech, emotion, blinks, gaze/head noise, conflict resolution):
  // at 1 kHz no column may jump by more than the steepest onset/offset slope allows
  for (std::size_t c = 0; c < t.names.size(); ++c)
    for (std::size_t f = 1; f < t.frames(); ++f)
      ASSERT_LT(std::abs(t.at(f, c) - t.at(f - 1, c)), 0.03) << t.names[c] << " at frame " << f;
}

}  // namespace
}  // namespace emoface::channels
