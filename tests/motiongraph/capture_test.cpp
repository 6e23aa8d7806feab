// Capture readers, writers, cleaning, stabilisation, trimming and labels (issue 19, item 1).
#include "emoface/motiongraph/capture.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>
#include <string>

#include "emoface/core/errors.hpp"
#include "emoface/motiongraph/preprocess.hpp"

namespace emoface::motiongraph {
namespace {

CaptureExampleOptions small_example() {
  CaptureExampleOptions o;
  o.database.seed = 4;
  o.database.sequences_per_label = 2;
  o.database.subjects = 3;
  o.database.min_frames = 8;
  o.database.max_frames = 14;
  return o;
}

const std::vector<TrackedFrames>& example_takes() {
  static const std::vector<TrackedFrames> takes =
      generate_capture_takes(ParametricLandmarkModel(), small_example());
  return takes;
}

// A frame of 68 landmarks on a rough face: eye corners 36/45 are 100 px apart.
Pose face_pose() {
  Pose p(68, 2);
  for (int i = 0; i < 68; ++i) p.row(i) << 200.0 + 3.0 * i, 200.0 + 0.5 * i * (i % 7);
  p.row(36) << 250.0, 200.0;
  p.row(45) << 350.0, 200.0;
  return p;
}

TrackedFrames take_of(const std::vector<Pose>& frames) {
  TrackedFrames t;
  t.id = "t";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    t.times.push_back(static_cast<double>(i) / 30.0);
    t.confidence.push_back(0.98);
    t.success.push_back(1);
    t.frames.push_back(frames[i]);
  }
  return t;
}

std::string expect_format_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const FormatError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a FormatError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(OpenFace, RoundTripOfAGeneratedTakeWithActionUnits) {
  TrackedFrames take = example_takes()[0];
  take.au_names = {"AU01_r", "AU12_r", "AU45_c"};
  for (std::size_t i = 0; i < take.size(); ++i)
    take.au.push_back({0.1 * static_cast<double>(i % 5), 1.5, i % 2 ? 1.0 : 0.0});
  const std::string text = openface_csv(take);
  OpenFaceReadOptions o;
  o.label_column = "label";
  const TrackedFrames back = parse_openface_csv(text, "take.csv", o);
  EXPECT_EQ(back.id, "take");
  ASSERT_EQ(back.size(), take.size());
  EXPECT_EQ(back.times, take.times);
  EXPECT_EQ(back.confidence, take.confidence);
  EXPECT_EQ(back.success, take.success);
  EXPECT_EQ(back.labels, take.labels);
  EXPECT_EQ(back.au_names, take.au_names);
  EXPECT_EQ(back.au, take.au);
  for (std::size_t i = 0; i < take.size(); ++i) ASSERT_EQ(back.frames[i], take.frames[i]) << i;
  // The same text again (writer deterministic), and OpenFace's ", " separators.
  EXPECT_EQ(openface_csv(back), text);
  EXPECT_EQ(text.substr(0, 48), "frame, face_id, timestamp, confidence, success, ");
}

// A header as OpenFace 2.0 writes it (spaces after commas, gaze/pose/3D columns we do not use).
std::string openface_header(bool with_3d) {
  std::string h = "frame, face_id, timestamp, confidence, success, gaze_0_x, pose_Tx";
  for (const char* a : {"x_", "y_"})
    for (int i = 0; i < 68; ++i) h += std::string(", ") + a + std::to_string(i);
  if (with_3d)
    for (const char* a : {"X_", "Y_", "Z_"})
      for (int i = 0; i < 68; ++i) h += std::string(", ") + a + std::to_string(i);
  return h + ", AU01_r, AU01_c\n";
}

std::string openface_row(int frame, int face, double time, double conf, int success, double base,
                         bool with_3d) {
  std::string r = std::to_string(frame) + ", " + std::to_string(face) + ", " +
                  std::to_string(time) + ", " + std::to_string(conf) + ", " +
                  std::to_string(success) + ", 0.1, 12.5";
  for (int a = 0; a < 2; ++a)
    for (int i = 0; i < 68; ++i) r += ", " + std::to_string(base + i + 100 * a);
  if (with_3d)
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < 68; ++i) r += ", " + std::to_string(-base - i - 1000 * a);
  return r + ", 2.5, 1\n";
}

TEST(OpenFace, ReadsOpenFaceHeadersFacesAnd3D) {
  const std::string text = openface_header(true) + openface_row(1, 0, 0.0, 0.98, 1, 10, true) +
                           openface_row(1, 1, 0.0, 0.90, 1, 500, true) +  // a second face: ignored
                           openface_row(2, 0, 0.033, 0.97, 1, 11, true);
  const TrackedFrames t = parse_openface_csv(text, "dir/clip.csv");
  EXPECT_EQ(t.id, "clip");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t.frames[1](5, 0), 16.0);   // x_5 = 11 + 5
  EXPECT_DOUBLE_EQ(t.frames[1](5, 1), 116.0);  // y_5
  EXPECT_EQ(t.au_names, (std::vector<std::string>{"AU01_r", "AU01_c"}));
  EXPECT_EQ(t.au[0], (std::vector<double>{2.5, 1.0}));
  OpenFaceReadOptions o3;
  o3.use_3d = true;
  const TrackedFrames t3 = parse_openface_csv(text, "clip.csv", o3);
  ASSERT_EQ(t3.dimensions, 3);
  EXPECT_DOUBLE_EQ(t3.frames[0](2, 2), -2012.0);  // Z_2 = -10 - 2 - 2000
  OpenFaceReadOptions second;
  second.face_id = 1;
  EXPECT_DOUBLE_EQ(parse_openface_csv(text, "clip.csv", second).frames[0](0, 0), 500.0);
}

TEST(OpenFace, BadInputIsALocatedFormatError) {
  const std::string h = openface_header(false);
  auto row = [](int f, double t, double c = 0.9, int s = 1) {
    return openface_row(f, 0, t, c, s, 10, false);
  };
  auto err = [](const std::string& text, OpenFaceReadOptions o = {}) {
    return expect_format_error([&] { parse_openface_csv(text, "f.csv", o); });
  };
  EXPECT_NE(err("").find("f.csv"), std::string::npos);
  EXPECT_NE(err("").find("empty file"), std::string::npos);
  EXPECT_NE(err(h).find("no frames"), std::string::npos);
  std::string missing = h;
  missing.replace(missing.find(", y_17"), 6, ", q_17");
  EXPECT_NE(err(missing + row(1, 0)).find("f.csv:1: missing column \"y_17\""), std::string::npos);
  EXPECT_NE(err("frame, timestamp, timestamp\n").find("appears twice"), std::string::npos);
  std::string truncated = row(2, 0.1);
  truncated.resize(truncated.size() / 2);
  EXPECT_NE(err(h + row(1, 0) + truncated + "\n").find("f.csv:3: expected 145 fields"),
            std::string::npos);
  std::string nan = row(1, 0);
  nan.replace(nan.find(", 12.5, ") + 8, 9, "nan      ");  // x_0
  EXPECT_NE(err(h + nan).find("f.csv:2:8: expected a finite number"), std::string::npos)
      << err(h + nan);
  std::string inf = row(1, 0);
  inf.replace(inf.find(", 12.5, ") + 8, 9, "1e999    ");
  EXPECT_NE(err(h + inf).find("expected a finite number"), std::string::npos);
  std::string huge = row(1, 0);
  huge.replace(huge.find(", 12.5, ") + 8, 9, "3e7      ");
  EXPECT_NE(err(h + huge).find("f.csv:2:8: coordinate out of range"), std::string::npos);
  EXPECT_NE(err(h + row(1, 0, 1.5)).find("f.csv:2:4: confidence must be in [0, 1]"),
            std::string::npos);
  EXPECT_NE(err(h + row(1, 0, 0.9, 2)).find("f.csv:2:5: success must be 0 or 1"),
            std::string::npos);
  EXPECT_NE(err(h + row(1, 0.5) + row(2, 0.5)).find("f.csv:3:3: timestamps must increase"),
            std::string::npos);
  EXPECT_NE(err(h + "1, 0, \"0.1, 2\n").find("malformed row"), std::string::npos);
  OpenFaceReadOptions lab;
  lab.label_column = "emotion";
  EXPECT_NE(err(h + row(1, 0), lab).find("missing column \"emotion\""), std::string::npos);
  OpenFaceReadOptions bad;
  bad.face_id = -1;
  EXPECT_THROW(parse_openface_csv(h + row(1, 0), "f.csv", bad), InvalidInput);
}

TEST(MediaPipe, CorrespondenceTableAndTheMeanRule) {
  const auto& table = mediapipe_to_ibug68();
  ASSERT_EQ(table.size(), 68u);
  std::set<int> used;
  std::size_t pairs = 0;
  for (const auto& e : table) {
    ASSERT_TRUE(e.size() == 1 || e.size() == 2);
    pairs += e.size() == 2;
    for (int i : e) {
      EXPECT_GE(i, 0);
      EXPECT_LT(i, 478);
      used.insert(i);
    }
  }
  EXPECT_EQ(pairs, 5u);                         // jaw 3, 4, 12 and nose bridge 27, 28
  EXPECT_EQ(table[30], std::vector<int>{4});    // nose tip
  EXPECT_EQ(table[36], std::vector<int>{33});   // subject's right eye, outer corner
  EXPECT_EQ(table[45], std::vector<int>{263});  // subject's left eye, outer corner
  EXPECT_EQ(table[8], std::vector<int>{152});   // chin
  // Point k at (k, 2k, −k)/1000: iBUG 3 = mean(132, 58) → x = 95/1000·640 = 60.8, y = 190/1000·490
  // = 93.1.
  std::string frame = "{\"timestamp_ms\": 0, \"face_landmarks\": [[";
  for (int k = 0; k < 478; ++k)
    frame += (k ? ", " : "") + std::string("{\"x\": ") + std::to_string(k / 1000.0) +
             ", \"y\": " + std::to_string(2 * k / 1000.0) +
             ", \"z\": " + std::to_string(-k / 1000.0) + "}";
  frame += "]], \"face_blendshapes\": []}\n";
  MediaPipeReadOptions o;
  o.use_z = true;
  const TrackedFrames t = parse_mediapipe_ndjson(frame, "mp.ndjson", o);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t.frames[0](3, 0), 60.8, 1e-9);
  EXPECT_NEAR(t.frames[0](3, 1), 93.1, 1e-9);
  EXPECT_NEAR(t.frames[0](3, 2), -60.8, 1e-9);
  EXPECT_NEAR(t.frames[0](30, 0), 4.0 / 1000 * 640, 1e-9);
  EXPECT_TRUE(t.labels.empty());
}

TEST(MediaPipe, GeneratedPointsReadBackAsTheLandmarks) {
  const TrackedFrames& take = example_takes()[1];
  std::vector<Eigen::MatrixXd> points;
  std::vector<double> times;
  for (std::size_t i = 0; i < 6; ++i) {
    points.push_back(take.success[i] ? mediapipe_points_from_ibug68(take.frames[i])
                                     : Eigen::MatrixXd());
    times.push_back(take.times[i]);
  }
  const std::vector<std::string> labels(6, "neutral");
  const TrackedFrames back =
      parse_mediapipe_ndjson(mediapipe_ndjson(times, points, labels), "x.ndjson");
  ASSERT_EQ(back.size(), 6u);
  EXPECT_EQ(back.labels, labels);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(back.success[i], take.success[i]);
    EXPECT_NEAR(back.times[i], times[i], 1e-12);
    if (take.success[i]) {
      EXPECT_LT((back.frames[i] - take.frames[i]).cwiseAbs().maxCoeff(), 1e-5) << i;
    }
  }
}

TEST(MediaPipe, BadInputIsALocatedFormatError) {
  auto err = [](const std::string& text) {
    return expect_format_error([&] { parse_mediapipe_ndjson(text, "m.ndjson"); });
  };
  Eigen::MatrixXd pts = mediapipe_points_from_ibug68(face_pose());
  const std::string good = mediapipe_ndjson({0.0}, {pts});
  EXPECT_NE(err("{\"timestamp_ms\": 1,\n").find("m.ndjson:1"), std::string::npos);
  EXPECT_NE(err("[1, 2]\n").find("expected an object"), std::string::npos);
  EXPECT_NE(err("{\"face_landmarks\": []}\n").find("at /timestamp_ms: missing field"),
            std::string::npos);
  EXPECT_NE(err("{\"timestamp_ms\": 1, \"face_landmarks\": [[{\"x\": 1}]]}\n")
                .find("expected 478 points"),
            std::string::npos);
  EXPECT_NE(err(good + good).find("m.ndjson:2: at /timestamp_ms: timestamps must increase"),
            std::string::npos);  // not increasing
  std::string bad = good;
  bad.replace(bad.find("{\"x\": "), 6, "{\"x\": \"a\", \"x0\": ");
  EXPECT_NE(err(bad).find("/face_landmarks/0/0/x: expected a number"), std::string::npos)
      << err(bad);
  std::string far = good;
  far.replace(far.find("\"y\": "), 5, "\"y\": 1000, \"y0\": ");
  EXPECT_NE(err(far).find("number out of range"), std::string::npos) << err(far);
  EXPECT_NE(err("# only a comment\n").find("no frames"), std::string::npos);
  // Found by the fuzzer: a number that overflows a double is a located error, not a crash.
  std::string overflow = good;
  overflow.replace(overflow.find("\"y\": "), 5, "\"y\": 0.659e8628, \"y0\": ");
  EXPECT_NE(err(overflow).find("m.ndjson:1: not JSON"), std::string::npos) << err(overflow);
  // No face in a frame: success 0.
  const TrackedFrames none =
      parse_mediapipe_ndjson("{\"timestamp_ms\": 5, \"face_landmarks\": []}\n", "m");
  EXPECT_EQ(none.success[0], 0);
  MediaPipeReadOptions o;
  o.image_width = 0;
  EXPECT_THROW(parse_mediapipe_ndjson(good, "m", o), InvalidInput);
}

TEST(CleanFrames, ShortGapsAreInterpolatedLongGapsSplit) {
  std::vector<Pose> frames;
  for (int i = 0; i < 30; ++i) frames.push_back(face_pose().array() + static_cast<double>(i));
  TrackedFrames t = take_of(frames);
  for (std::size_t i : {5u, 6u}) t.success[i] = 0, t.frames[i].setZero();  // 2 frames: filled
  for (std::size_t i : {14u, 15u, 16u, 17u, 18u}) t.confidence[i] = 0.2;   // 5 frames: split
  t.confidence[28] = t.confidence[29] = 0.1;  // the last part ends at 27
  const auto parts = clean_frames(t);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].id, "t.p0");
  EXPECT_EQ(parts[1].id, "t.p1");
  ASSERT_EQ(parts[0].size(), 14u);  // frames 0–13
  ASSERT_EQ(parts[1].size(), 9u);   // frames 19–27
  // Frame 5 lies 1/3 of the way from frame 4 to frame 7: 4 + 1 = 5 (the values grow by 1 per
  // frame).
  EXPECT_NEAR(parts[0].frames[5](0, 0), face_pose()(0, 0) + 5.0, 1e-9);
  EXPECT_NEAR(parts[0].frames[6](3, 1), face_pose()(3, 1) + 6.0, 1e-9);
  EXPECT_EQ(parts[0].success[5], 1);
  FrameFilterOptions o;
  o.min_frames = 10;  // the 9-frame part goes
  EXPECT_EQ(clean_frames(t, o).size(), 1u);
  o.max_gap = 5;  // now the 5-frame gap is filled too
  ASSERT_EQ(clean_frames(t, o).size(), 1u);
  EXPECT_EQ(clean_frames(t, o)[0].id, "t");
  o.min_confidence = 2.0;
  EXPECT_THROW(clean_frames(t, o), InvalidInput);
}

TEST(StabiliseHead, RemovesAKnownSimilarityMotion) {
  // The expression moves only non-anchor landmarks (mouth), the head rotates, scales and shifts.
  const StabiliseOptions so;
  std::vector<Pose> base, moved;
  for (int i = 0; i < 20; ++i) {
    Pose p = face_pose();
    for (int l = 48; l < 68; ++l) p(l, 1) += 0.5 * i;
    base.push_back(p);
    const double a = i < 5 ? 0.0 : 0.02 * (i - 4), s = i < 5 ? 1.0 : 1.0 + 0.01 * (i - 4);
    Eigen::Matrix2d r;
    r << std::cos(a), std::sin(a), -std::sin(a), std::cos(a);
    Pose q =
        (p * r * s).rowwise() + Eigen::RowVector2d(3.0 * (i >= 5 ? i : 0), -2.0 * (i >= 5 ? i : 0));
    moved.push_back(q);
  }
  // The reference is the median of the first 5 frames (whose mouths differ): anchors are fixed, so
  // every stabilised frame is its base pose.
  TrackedFrames t = take_of(moved);
  const std::vector<double> residual = stabilise_head(t, so);
  for (std::size_t i = 0; i < base.size(); ++i) {
    EXPECT_LT((t.frames[i] - base[i]).cwiseAbs().maxCoeff(), 1e-9) << i;
    EXPECT_LT(residual[i], 1e-9);
  }
  StabiliseOptions bad;
  bad.anchors = {1, 2};
  EXPECT_THROW(stabilise_head(t, bad), InvalidInput);
}

TEST(FindSegments, OnsetsAndPeaksOfAHandMadeTake) {
  // All landmarks move by a(t)·d with |d| = 20 px = 0.2 of the 100 px eye-corner distance.
  const std::vector<double> a = {0,   0,   0,   0,   0,   0,   0,   0, 0, 0, .25, .5,
                                 .75, 1,   1,   1,   .75, .5,  .25, 0, 0, 0, 0,   0,
                                 0,   .02, .04, .06, .04, .02, 0,   0, 0, 0,  // too weak
                                 0,   0,   .25, .5,  .5,  .5,  .25, 0, 0, 0};
  std::vector<Pose> frames;
  for (double x : a)
    frames.push_back(face_pose().rowwise() + Eigen::RowVector2d(12.0 * x, 16.0 * x));
  std::vector<double> m;
  const auto segments = find_segments(take_of(frames), {}, &m);
  // The baseline is 0 (rest frames within ±1.5 s everywhere), so e = m. Smoothed m(9) = (0 + 0 +
  // 0.25)/3 · 20 px = 1.67 px > low = 0.6 px: the episode starts at 9, so the segment starts at 8;
  // the largest m is at 14 (1 + 1 + 1)/3. The weak bump peaks at (0.04 + 0.06 + 0.04)/3 · 20 =
  // 0.93 px: above low, below high = 1.5 px. The third starts at 35 (m = 0.25/3 · 20) and peaks at
  // 38 (0.5 · 20 = 10 px).
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].first, 8u);
  EXPECT_EQ(segments[0].peak, 14u);
  EXPECT_EQ(segments[1].first, 34u);
  EXPECT_EQ(segments[1].peak, 38u);
  EXPECT_NEAR(m[14], 20.0, 1e-9);
  EXPECT_NEAR(m[9], 20.0 / 12.0, 1e-9);
  TrimOptions t;
  t.low = 0.5;
  t.high = 0.4;
  EXPECT_THROW(find_segments(take_of(frames), t), InvalidInput);
  t = {};
  t.baseline_window = 0.0;
  EXPECT_THROW(find_segments(take_of(frames), t), InvalidInput);
}

TEST(LabelTable, ParsesRoundTripsAndLocatesErrors) {
  const LabelTable t = parse_label_table(
      "# comment\ntake,segment,label\nS1,*,happiness\nS1,2,fear\n\"a,b\",0,anger\n", "l.csv");
  ASSERT_EQ(t.entries.size(), 3u);
  EXPECT_EQ(t.entries.at({"S1", "*"}), Label::Happiness);
  EXPECT_EQ(t.entries.at({"a,b", "0"}), Label::Anger);
  EXPECT_EQ(parse_label_table(label_table_csv(t), "x").entries, t.entries);
  auto err = [](const std::string& text) {
    return expect_format_error([&] { parse_label_table(text, "l.csv"); });
  };
  EXPECT_NE(err("").find("no header"), std::string::npos);
  EXPECT_NE(err("take,label\n").find("l.csv:1:1"), std::string::npos);
  EXPECT_NE(err("take,segment,label\nS1,x,fear\n").find("l.csv:2:2"), std::string::npos);
  EXPECT_NE(err("take,segment,label\nS1,1,joy\n").find("l.csv:2:3"), std::string::npos);
  EXPECT_NE(err("take,segment,label\nS1,1\n").find("l.csv:2: expected 3 fields"),
            std::string::npos);
  EXPECT_NE(err("take,segment,label\nS1,1,fear\nS1,01,anger\n").find("labelled twice"),
            std::string::npos);
  EXPECT_NE(err("take,segment,label\n,1,fear\n").find("empty take"), std::string::npos);
}

TEST(CaptureDatabase, LongTakesBecomeTheLabelledSequences) {
  const CaptureExampleOptions o = small_example();
  const Database truth = generate_synthetic_database(ParametricLandmarkModel(), o.database);
  std::vector<TrackedFrames> takes;
  for (const auto& t : example_takes())  // through the file format, as a user would
    takes.push_back(parse_openface_csv(openface_csv(t), t.id + ".csv", [] {
      OpenFaceReadOptions r;
      r.label_column = "label";
      return r;
    }()));
  ReadReport rep;
  const Database db = capture_database(takes, {}, nullptr, &rep);
  EXPECT_TRUE(rep.skipped.empty());
  EXPECT_NEAR(db.frame_rate, 30.0, 1e-9);
  ASSERT_EQ(db.sequences.size(), truth.sequences.size());
  // Per subject, the labels in take order are those of the subject's sequences; lengths are the
  // onsets' (± 2 frames: the detected onset and the peak of a noisy hold).
  for (const auto& subject : {"S001", "S002", "S003"}) {
    std::vector<Label> expected, found;
    std::vector<std::size_t> len_expected, len_found;
    for (const auto& s : truth.sequences)
      if (s.subject == subject)
        expected.push_back(s.label), len_expected.push_back(s.frames.size());
    for (const auto& s : db.sequences)
      if (s.subject == std::string("take_") + subject)
        found.push_back(s.label), len_found.push_back(s.frames.size());
    EXPECT_EQ(found, expected) << subject;
    ASSERT_EQ(len_found.size(), len_expected.size());
    for (std::size_t k = 0; k < len_found.size(); ++k)
      EXPECT_NEAR(static_cast<double>(len_found[k]), static_cast<double>(len_expected[k]), 3.0)
          << subject << " " << k;
  }
  // Every sequence starts neutral and passes the preprocessing checks.
  EXPECT_NO_THROW(preprocess(db, default_layout(), [] {
    PreprocessOptions p;
    p.clean = false;
    return p;
  }()));
  // Labels from a side file instead of the column give the same database.
  std::vector<TrackedFrames> unlabelled = takes;
  LabelTable side;
  for (auto& t : unlabelled) {
    t.labels.clear();
    std::size_t k = 0;
    for (const auto& s : db.sequences)
      if (s.subject == t.id) side.entries[{t.id, std::to_string(k++)}] = s.label;
  }
  const Database db2 = capture_database(unlabelled, {}, &side);
  ASSERT_EQ(db2.sequences.size(), db.sequences.size());
  for (std::size_t i = 0; i < db.sequences.size(); ++i)
    EXPECT_EQ(db2.sequences[i].label, db.sequences[i].label);
  // A missing label stops the run, or is skipped and reported.
  side.entries.erase(side.entries.begin());
  EXPECT_THROW(capture_database(unlabelled, {}, &side), InvalidInput);
  CaptureOptions skip;
  skip.on_error = OnError::Skip;
  ReadReport r2;
  EXPECT_EQ(capture_database(unlabelled, skip, &side, &r2).sequences.size(),
            db.sequences.size() - 1);
  ASSERT_EQ(r2.skipped.size(), 1u);
  EXPECT_NE(r2.skipped[0].find("has no label"), std::string::npos);
}

TEST(CaptureExample, DeterministicWithHeadMotionAndDropouts) {
  const auto again = generate_capture_takes(ParametricLandmarkModel(), small_example());
  ASSERT_EQ(again.size(), 3u);
  for (std::size_t i = 0; i < again.size(); ++i)
    EXPECT_EQ(openface_csv(again[i]), openface_csv(example_takes()[i]));
  std::size_t dropped = 0;
  for (char s : again[0].success) dropped += s == 0;
  EXPECT_GT(dropped, 2u);
  CaptureExampleOptions bad = small_example();
  bad.head_roll = 1.0;
  EXPECT_THROW(generate_capture_takes(ParametricLandmarkModel(), bad), InvalidInput);
}

// The side file of the example generator: per take, the labels of the subject's sequences in order
// (the truth the takes were made from), and it labels an unlabelled capture like the column does.
TEST(CaptureExample, SegmentLabelTable) {
  const Database truth =
      generate_synthetic_database(ParametricLandmarkModel(), small_example().database);
  const LabelTable side = segment_label_table(example_takes());
  for (const std::string subject : {"S001", "S002", "S003"}) {
    std::vector<Label> expected, found;
    for (const auto& s : truth.sequences)
      if (s.subject == subject) expected.push_back(s.label);
    for (std::size_t k = 0; k < 100; ++k) {
      const auto it = side.entries.find({"take_" + subject, std::to_string(k)});
      if (it != side.entries.end()) found.push_back(it->second);
    }
    EXPECT_EQ(found, expected) << subject;
  }
  std::vector<TrackedFrames> unlabelled = example_takes();
  for (auto& t : unlabelled) t.labels.clear();
  const Database by_column = capture_database(example_takes());
  const Database by_table = capture_database(unlabelled, {}, &side);
  ASSERT_EQ(by_table.sequences.size(), by_column.sequences.size());
  for (std::size_t i = 0; i < by_table.sequences.size(); ++i)
    EXPECT_EQ(by_table.sequences[i].label, by_column.sequences[i].label);
  EXPECT_THROW(segment_label_table(unlabelled), InvalidInput);  // no label column
}

// A take written as MediaPipe NDJSON reads back as the same iBUG-68 take.
TEST(MediaPipe, TakeRoundTrip) {
  const TrackedFrames& take = example_takes()[0];
  const TrackedFrames back = parse_mediapipe_ndjson(mediapipe_ndjson(take), "t.ndjson");
  ASSERT_EQ(back.size(), take.size());
  EXPECT_EQ(back.labels, take.labels);
  EXPECT_EQ(back.success, take.success);
  std::size_t compared = 0;
  for (std::size_t i = 0; i < take.size(); ++i) {
    EXPECT_NEAR(back.times[i], take.times[i], 1e-9);
    if (!take.success[i]) continue;
    EXPECT_LT((back.frames[i] - take.frames[i]).cwiseAbs().maxCoeff(), 1e-4) << i;  // %.8g
    ++compared;
  }
  EXPECT_GT(compared, take.size() / 2);
}

}  // namespace
}  // namespace emoface::motiongraph
