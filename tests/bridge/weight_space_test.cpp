// Weight-space motion graphs on the face (issue 19 item 2): ARKit layout, the generated weight
// database and Live Link takes, and synthesized weights driving the face through the exact mapping.
#include "emoface/bridge/weight_space.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

#include "emoface/core/errors.hpp"
#include "emoface/faceweights/names.hpp"
#include "emoface/motiongraph/weights.hpp"
#include "emoface/muscles/parameters.hpp"

namespace mg = emoface::motiongraph;
namespace br = emoface::bridge;

namespace {
const br::FaceLandmarkModel& face() {
  static const br::FaceLandmarkModel model;
  return model;
}

br::WeightDatabaseOptions small_options() {
  br::WeightDatabaseOptions o;
  o.database.sequences_per_label = 2;
  o.database.subjects = 3;
  o.database.min_frames = 8;
  o.database.max_frames = 14;
  return o;
}
}  // namespace

TEST(ArkitLayout, RegionsCoverEveryChannelButTheTongue) {
  const mg::LandmarkLayout l = br::arkit_layout();
  EXPECT_EQ(l.source_landmark_count, 52u);
  ASSERT_EQ(l.regions.size(), 5u);
  std::set<int> all;
  for (const auto& r : l.regions) all.insert(r.landmarks.begin(), r.landmarks.end());
  EXPECT_EQ(all.size(), 51u);
  const auto& names = emoface::faceweights::arkit_names();
  const auto tongue = std::find(names.begin(), names.end(), "tongueOut") - names.begin();
  EXPECT_EQ(all.count(static_cast<int>(tongue)), 0u);
  EXPECT_EQ(l.regions[0].landmarks.size(), 14u);  // eyes
  EXPECT_EQ(l.regions[1].landmarks.size(), 5u);   // brows
  EXPECT_EQ(l.regions[2].landmarks.size(), 2u);   // nose
  EXPECT_EQ(l.regions[3].landmarks.size(), 23u);  // mouth
  EXPECT_EQ(l.regions[4].landmarks.size(), 7u);   // cheeks + jaw
  for (int id : l.regions[3].landmarks)
    EXPECT_EQ(names[static_cast<std::size_t>(id)].rfind("mouth", 0), 0u);
}

TEST(WeightDatabase, FaceDrivenWeightsFollowTheMapping) {
  // Happiness at intensity 1: the weights are Mapper::forward of the fuzzy side parameters.
  const std::vector<double> w = br::expression_weights(face(), mg::Label::Happiness, 1.0);
  ASSERT_EQ(w.size(), 52u);
  const std::vector<double> side = face().side_parameters(mg::Label::Happiness, 1.0);
  std::vector<double> params(emoface::muscles::kParameterCount, 0.0);
  std::copy(side.begin(), side.end(), params.begin());
  EXPECT_EQ(w, br::arkit_mapper().forward(params));
  const auto& names = emoface::faceweights::arkit_names();
  const auto smile = std::find(names.begin(), names.end(), "mouthSmile_L") - names.begin();
  EXPECT_GT(w[static_cast<std::size_t>(smile)], 0.2);
  // Neutral is all zero.
  for (double v : br::expression_weights(face(), mg::Label::Neutral, 0.7)) EXPECT_EQ(v, 0.0);
}

TEST(WeightDatabase, SameSequencesAsTheLandmarkDatabaseAndDeterministic) {
  const br::WeightDatabaseOptions o = small_options();
  const mg::Database w = br::generate_weight_database(face(), o);
  const mg::Database l = mg::generate_synthetic_database(face(), o.database);
  EXPECT_EQ(w.dimensions, 1);
  EXPECT_EQ(w.landmark_count, 52u);
  ASSERT_EQ(w.sequences.size(), l.sequences.size());
  for (std::size_t s = 0; s < w.sequences.size(); ++s) {
    EXPECT_EQ(w.sequences[s].id, l.sequences[s].id);
    EXPECT_EQ(w.sequences[s].label, l.sequences[s].label);
    EXPECT_EQ(w.sequences[s].frames.size(), l.sequences[s].frames.size());
    for (const auto& p : w.sequences[s].frames) {
      EXPECT_GE(p.minCoeff(), 0.0);
      EXPECT_LE(p.maxCoeff(), 1.0);
    }
  }
  const mg::Database again = br::generate_weight_database(face(), o);
  EXPECT_EQ(again.sequences[3].frames[5], w.sequences[3].frames[5]);
  br::WeightDatabaseOptions bad = o;
  bad.noise_std = -1.0;
  EXPECT_THROW(br::generate_weight_database(face(), bad), emoface::InvalidInput);
  bad = o;
  bad.gain_std = std::nan("");
  EXPECT_THROW(br::generate_weight_database(face(), bad), emoface::InvalidInput);
}

TEST(LiveLinkTakes, RoundTripTrimAndLabels) {
  br::WeightTakeOptions o;
  o.database = small_options();
  const auto takes = br::generate_weight_takes(face(), o);
  ASSERT_EQ(takes.size(), 3u);
  const std::string csv = br::live_link_csv(takes[0], 30.0);
  EXPECT_EQ(csv.rfind("Timecode,BlendShapeCount,EyeBlinkLeft,", 0), 0u);
  const mg::TrackedFrames back = br::parse_live_link_take(csv, "dir/take_S001.csv", 30.0);
  EXPECT_EQ(back.id, "take_S001");
  ASSERT_EQ(back.size(), takes[0].size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    EXPECT_EQ(back.frames[i], takes[0].frames[i]) << i;  // %.17g: bit-identical
    EXPECT_NEAR(back.times[i], takes[0].times[i], 1e-9);
  }
  // Every expression of the takes is found by trimming (each subject has 14·2/3 ≈ 4–5).
  const mg::LabelTable labels = br::weight_take_labels(takes);
  std::size_t expressions = 0;
  for (const auto& t : takes)
    for (std::size_t i = 1; i < t.labels.size(); ++i)
      expressions += t.labels[i - 1] == "neutral" && t.labels[i] != "neutral";
  EXPECT_EQ(labels.entries.size(), expressions);
  // The database from the files and the side table: one sequence per expression, labels matching.
  std::vector<mg::TrackedFrames> read;
  for (const auto& t : takes)
    read.push_back(br::parse_live_link_take(br::live_link_csv(t, 30.0), t.id + ".csv", 30.0));
  const mg::Database db = mg::capture_database(read, {}, &labels);
  EXPECT_EQ(db.sequences.size(), expressions);
  EXPECT_EQ(db.dimensions, 1);
  EXPECT_NEAR(db.frame_rate, 30.0, 1e-6);
}

TEST(LiveLinkTakes, BadInputIsLocated) {
  br::WeightTakeOptions o;
  o.database = small_options();
  const std::string good = br::live_link_csv(br::generate_weight_takes(face(), o)[0], 30.0);
  auto error_of = [](const std::string& text) -> std::string {
    try {
      br::parse_live_link_take(text, "t.csv", 30.0);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  const std::size_t line2 = good.find('\n') + 1, line3 = good.find('\n', line2) + 1;
  // Truncated row.
  std::string truncated = good.substr(0, line3 - 30) + "\n";
  EXPECT_NE(error_of(truncated).find("t.csv:2"), std::string::npos) << error_of(truncated);
  // NaN, out of range, non-number in the third data value of line 2.
  for (const char* bad : {"nan", "1.5", "-0.2", "abc", "inf"}) {
    std::string text = good;
    const std::size_t a = text.find(',', text.find(',', text.find(',', line2) + 1) + 1) + 1;
    const std::size_t b = text.find(',', a);
    text.replace(a, b - a, bad);
    const std::string e = error_of(text);
    EXPECT_NE(e.find("t.csv:2"), std::string::npos) << bad << ": " << e;
  }
  // Missing column, empty file, header only.
  std::string missing = good;
  missing.replace(missing.find("EyeBlinkLeft"), 12, "Nothing");
  EXPECT_NE(error_of(missing).find("t.csv"), std::string::npos);
  EXPECT_NE(error_of("").find("t.csv"), std::string::npos);
  EXPECT_NE(error_of(good.substr(0, line2)).find("t.csv"), std::string::npos);
  // Times that do not increase.
  std::string repeated = good.substr(0, line3) + good.substr(line2, line3 - line2);
  EXPECT_NE(error_of(repeated).find("t.csv:3"), std::string::npos) << error_of(repeated);
  // The writer refuses a non-integer rate and a landmark take.
  const mg::TrackedFrames t = br::parse_live_link_take(good, "t.csv", 30.0);
  EXPECT_THROW(br::live_link_csv(t, 29.97), emoface::InvalidInput);
  mg::TrackedFrames landmarks;
  landmarks.dimensions = 2;
  EXPECT_THROW(br::live_link_csv(landmarks, 30.0), emoface::InvalidInput);
}

TEST(WeightDrive, SynthesizedWeightsDriveTheFaceExactly) {
  const mg::Database db = br::generate_weight_database(face(), small_options());
  const mg::PreparedDatabase data =
      mg::preprocess(db, br::arkit_layout(), mg::weight_preprocess_options());
  const mg::MotionGraph g = mg::build_graph(data, mg::weight_graph_options());
  mg::SynthesisState st = mg::initial_state(g);
  const auto frames = mg::synthesize(g, st, mg::Label::Surprise, mg::weight_synthesis_options());
  br::WeightDriveReport rep;
  const auto params = br::weight_parameters(g, frames, &rep);
  ASSERT_EQ(params.size(), frames.size());
  EXPECT_EQ(rep.frames, frames.size());
  EXPECT_EQ(params[0].values.size(), emoface::muscles::kParameterCount);
  EXPECT_NEAR(params[1].time, 1.0 / 30.0, 1e-12);
  // Weights made by the mapping (plus gains and noise) are reproduced within a few hundredths; the
  // mapping itself is exact up to the fit's small ridge term: forward(inverse(forward(p))) =
  // forward(p) within 1e-5.
  EXPECT_LT(rep.max_weight_error, 0.03);
  std::cout << "max weight error " << rep.max_weight_error << "\n";
  const std::vector<double> side = face().side_parameters(mg::Label::Surprise, 0.8);
  std::vector<double> p(emoface::muscles::kParameterCount, 0.0);
  std::copy(side.begin(), side.end(), p.begin());
  const std::vector<double> w = br::arkit_mapper().forward(p);
  std::vector<double> q;
  br::arkit_mapper().inverse(w, q);
  const std::vector<double> again = br::arkit_mapper().forward(q);
  for (std::size_t c = 0; c < w.size(); ++c) EXPECT_NEAR(again[c], w[c], 1e-5) << c;
  // The jaw opens on the surprise apex (jawOpen → masseter).
  const auto& names = emoface::muscles::parameter_names();
  const auto masseter =
      std::find_if(names.begin(), names.end(),
                   [](const std::string& n) { return n.find("masseter") != std::string::npos; }) -
      names.begin();
  EXPECT_GT(params.back().values[static_cast<std::size_t>(masseter)], 0.2);
  // A landmark graph is refused.
  mg::MotionGraph landmarks = g;
  landmarks.dimensions = 2;
  EXPECT_THROW(br::weight_parameters(landmarks, frames), emoface::InvalidInput);
}
