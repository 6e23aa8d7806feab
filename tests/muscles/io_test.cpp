#include "emoface/muscles/io.hpp"

#include <gtest/gtest.h>

#include "emoface/core/errors.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/morph_targets.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace emoface::muscles {
namespace {

std::vector<ParameterFrame> csv(const std::string& text, FrameReadOptions o = {}) {
  return parse_parameter_frames(text, FrameFormat::Csv, "p.csv", o);
}

TEST(ParameterFrames, CsvWithMetadataAndTimes) {
  const auto frames = csv("id,time,masseter,zygomatic_major_l,happiness\n0,0.5,0.25,1,0.9\n1,1.0,0,0.5,0.2\n");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].time, 0.5);
  EXPECT_EQ(frames[0].values[parameter_index("masseter")], 0.25);
  EXPECT_EQ(frames[1].values[parameter_index("zygomatic_major_l")], 0.5);
  EXPECT_EQ(frames[1].values[parameter_index("risorius_r")], 0.0);
  // no time column: index / fps
  FrameReadOptions o;
  o.fps = 10;
  const auto f2 = csv("masseter\n0.1\n0.2\n", o);
  EXPECT_DOUBLE_EQ(f2[1].time, 0.1);
}

TEST(ParameterFrames, RoundTrips) {
  std::vector<ParameterFrame> frames(3);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].time = 0.1 * static_cast<double>(i) + 1.0 / 3.0;
    frames[i].values.assign(kParameterCount, 0.0);
    frames[i].values[i] = 1.0 / 7.0;
    frames[i].values[36] = -0.123456789;
  }
  for (auto format : {FrameFormat::Csv, FrameFormat::Json}) {
    const std::string text = format == FrameFormat::Csv ? format_parameter_frames_csv(frames) : format_parameter_frames_json(frames, 25);
    const auto back = parse_parameter_frames(text, format, "x");
    ASSERT_EQ(back.size(), frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      EXPECT_EQ(back[i].time, frames[i].time);
      EXPECT_EQ(back[i].values, frames[i].values);
    }
  }
}

TEST(ParameterFrames, NdjsonAndJson) {
  const auto nd = parse_parameter_frames("{\"time\": 0.2, \"parameters\": {\"masseter\": 0.5}}\n\n{\"masseter\": 1}\n",
                                         FrameFormat::Ndjson, "p.ndjson");
  ASSERT_EQ(nd.size(), 2u);
  EXPECT_EQ(nd[0].time, 0.2);
  EXPECT_EQ(nd[1].values[parameter_index("masseter")], 1.0);
  const auto one = parse_parameter_frames("{\"risorius_l\": 0.3}", FrameFormat::Json, "p.json");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].values[parameter_index("risorius_l")], 0.3);
  EXPECT_EQ(frame_format_from_path("a.jsonl"), FrameFormat::Ndjson);
  EXPECT_THROW(frame_format_from_path("a.txt"), InvalidInput);
  EXPECT_EQ(frame_format_from_string(to_string(FrameFormat::Json)), FrameFormat::Json);
}

void expect_error(const std::string& text, FrameFormat format, std::size_t line) {
  try {
    parse_parameter_frames(text, format, "bad");
    FAIL() << text;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "bad");
    EXPECT_EQ(e.where().line, line) << text << " -> " << e.what();
  }
}

TEST(ParameterFrames, RejectsBadInput) {
  expect_error("smile\n1\n", FrameFormat::Csv, 1);                    // unknown column
  expect_error("masseter,masseter\n1,1\n", FrameFormat::Csv, 1);      // duplicate column
  expect_error("masseter\n1\nnan\n", FrameFormat::Csv, 3);            // NaN
  expect_error("masseter\n1e400\n", FrameFormat::Csv, 2);             // overflow
  expect_error("masseter\n1.5\n", FrameFormat::Csv, 2);               // out of range
  expect_error("masseter\nabc\n", FrameFormat::Csv, 2);               // not a number
  expect_error("masseter,risorius_l\n1\n", FrameFormat::Csv, 2);      // wrong field count
  expect_error("masseter\n\"1\n", FrameFormat::Csv, 2);               // malformed quoting
  expect_error("", FrameFormat::Csv, 1);                              // no header
  expect_error("{\"masseter\": 1}\n{\"masseter\": \n", FrameFormat::Ndjson, 2);  // truncated
  expect_error("{\"masseter\": \"x\"}\n", FrameFormat::Ndjson, 1);
  expect_error("{\"smile\": 1}\n", FrameFormat::Ndjson, 1);
  expect_error("[1, 2]", FrameFormat::Json, 0);
  expect_error("{\"format\": \"emoface.params\", \"version\": \"9.0\", \"frames\": []}", FrameFormat::Json, 0);
  expect_error("{\"format\": \"emoface.params\", \"version\": \"1.0\", \"frames\": [{\"parameters\": {\"masseter\": -1}}]}", FrameFormat::Json, 0);
  expect_error("[1]\n", FrameFormat::Ndjson, 1);  // not an object
  expect_error("{\"time\": \"x\", \"masseter\": 0.1}\n", FrameFormat::Ndjson, 1);
  FrameReadOptions lenient;
  lenient.ignore_unknown_columns = true;
  EXPECT_NO_THROW(csv("smile,masseter\n1,0.5\n", lenient));
  lenient.fps = 0.0;
  EXPECT_THROW(csv("masseter\n1\n", lenient), InvalidInput);
}

// The unknown-field rule of docs/formats.md through core::JsonReader (issue 18): a typo in a 1.0
// "emoface.params" file is an error naming it; a newer minor (1.3) may add fields.
TEST(ParameterFrames, UnknownFieldRuleOfTheParamsEnvelope) {
  const std::string body =
      R"("fps": 10, "frames": [{"time": 0.5, "parameters": {"masseter": 0.25}, "note": "x"}]})";
  try {
    parse_parameter_frames(R"({"format": "emoface.params", "version": "1.0", )" + body,
                           FrameFormat::Json, "p.json");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_STREQ(e.what(), "p.json: at /frames/0/note: unknown field \"note\"");
  }
  const auto frames = parse_parameter_frames(
      R"({"format": "emoface.params", "version": "1.3", )" + body, FrameFormat::Json, "p.json");
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].time, 0.5);
  EXPECT_EQ(frames[0].values[parameter_index("masseter")], 0.25);
  try {
    parse_parameter_frames(
        R"({"format": "emoface.params", "version": "1.0", "fps": -1, "frames": []})",
        FrameFormat::Json, "p.json");
    FAIL();
  } catch (const FormatError& e) {
    EXPECT_STREQ(e.what(), "p.json: at /fps: fps must be a number in (0, 1000]");
  }
}

TEST(ParameterFrames, CsvSkipsStampsAndRepeatedHeadersOfConcatenatedShards) {
  const std::string shard = "# emoface 0.1.0\ntime,masseter\n0,0.5\n";
  const auto frames = parse_parameter_frames(shard + shard, FrameFormat::Csv, "cat.csv");
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1].values[parameter_index("masseter")], 0.5);
}

}  // namespace
}  // namespace emoface::muscles

// A transferred rig's glTF is written in the mesh file's own frame: p_rig = s·R·p_mesh + t, so positions go
// through to_mesh, deltas by Rᵀ·δ/s, normals by Rᵀ, head rotations by Rᵀ·q·R (hand-computed values).
TEST(MorphTargets, ExpressInMeshFrame) {
  emoface::muscles::BakedRig rig;
  rig.neutral.vertices.resize(1, 3);
  rig.neutral.vertices << 3.0, 4.0, 5.0;
  emoface::facemesh::MorphTarget t;
  t.name = "x";
  t.position_deltas.resize(1, 3);
  t.position_deltas << 2.0, 0.0, 0.0;
  t.normal_deltas.resize(1, 3);
  t.normal_deltas << 0.0, 1.0, 0.0;
  rig.targets.push_back(t);
  rig.head_pivot = Eigen::Vector3d(1.0, 1.0, 1.0);
  std::vector<emoface::facemesh::WeightAnimation> anims(1);
  anims[0].head_rotations.push_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())));
  emoface::facemesh::Frame f;
  f.scale = 2.0;
  f.rotation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();  // x → y, y → −x
  f.translation = Eigen::Vector3d(1.0, 0.0, 0.0);
  emoface::muscles::express_in_mesh_frame(rig, anims, f);
  // to_mesh(3,4,5) = Rᵀ·((3,4,5) − (1,0,0)) / 2 = Rᵀ·(2,4,5)/2 = (4, −2, 5)/2
  EXPECT_NEAR((rig.neutral.vertices.row(0) - Eigen::RowVector3d(2.0, -1.0, 2.5)).norm(), 0.0, 1e-12);
  // Rᵀ·(2,0,0)/2 = (0,−2,0)/2; Rᵀ·(0,1,0) = (1,0,0)
  EXPECT_NEAR((rig.targets[0].position_deltas.row(0) - Eigen::RowVector3d(0.0, -1.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((rig.targets[0].normal_deltas.row(0) - Eigen::RowVector3d(1.0, 0.0, 0.0)).norm(), 0.0, 1e-12);
  // a rotation about the rig's y axis is a rotation about Rᵀ·y = (1, 0, 0) in the mesh frame
  const Eigen::AngleAxisd q(anims[0].head_rotations[0]);
  EXPECT_NEAR(q.angle(), 0.3, 1e-12);
  EXPECT_NEAR((q.axis() - Eigen::Vector3d(1.0, 0.0, 0.0)).norm(), 0.0, 1e-12);
  // identity frame: nothing changes
  emoface::muscles::express_in_mesh_frame(rig, anims, emoface::facemesh::Frame{});
  EXPECT_NEAR((rig.neutral.vertices.row(0) - Eigen::RowVector3d(2.0, -1.0, 2.5)).norm(), 0.0, 1e-12);
}
