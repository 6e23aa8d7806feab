#include "emoface/facemesh/io.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

using Json = nlohmann::ordered_json;

const Face& default_face() {
  static const Face face = make_generic_face();
  return face;
}

bool same_rig(const Rig& a, const Rig& b) { return format_rig(a) == format_rig(b); }

TEST(RigIo, RoundTripsTheDefaultRig) {
  const Rig& rig = default_face().rig;
  const std::string text = format_rig(rig);
  const Rig back = parse_rig(text, "mem");
  EXPECT_TRUE(same_rig(rig, back));
  EXPECT_EQ(back.muscles.size(), rig.muscles.size());
  EXPECT_EQ(back.regions, rig.regions);
  EXPECT_EQ(back.ibug68, rig.ibug68);
  ASSERT_EQ(back.lips.control_points.size(), 144u);
  EXPECT_EQ(back.lips.control_points[17], rig.lips.control_points[17]);  // %.17g round trip is exact
}

// Applies `edit` to the default rig JSON and expects a FormatError whose pointer starts with
// `pointer` (and whose message holds `message`).
void expect_bad(const std::function<void(Json&)>& edit, const std::string& pointer,
                const std::string& message = "") {
  Json doc = Json::parse(format_rig(default_face().rig));
  edit(doc);
  try {
    parse_rig(doc.dump(), "bad.rig");
    FAIL() << "accepted: " << pointer;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "bad.rig");
    EXPECT_EQ(e.where().json_pointer.rfind(pointer, 0), 0u) << e.what() << " expected " << pointer;
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(RigIo, RejectsBadContent) {
  expect_bad([](Json& d) { d["format"] = "emoface.mesh"; }, "/format");
  expect_bad([](Json& d) { d["version"] = "2.0"; }, "/version");
  // A missing field is located at its object (core::JsonReader), the message names it.
  expect_bad([](Json& d) { d.erase("jaw"); }, "", "bad.rig: missing field \"jaw\"");
  expect_bad([](Json& d) { d["eyes"][1].erase("radius"); }, "/eyes/1", "missing field \"radius\"");
  expect_bad([](Json& d) { d["vertex_count"] = -3; }, "/vertex_count");
  expect_bad([](Json& d) { d["vertex_count"] = 1e12; }, "/vertex_count");
  expect_bad([](Json& d) { d["jaw"]["vertices"][0] = 99999999; }, "/jaw/vertices/0");
  expect_bad([](Json& d) { d["jaw"]["weights"][0] = 2.0; }, "/jaw/weights/0");
  expect_bad([](Json& d) { d["jaw"]["weights"].erase(0); }, "/jaw/weights");
  expect_bad([](Json& d) { d["muscles"][0]["rs"] = d["muscles"][0]["rf"]; }, "/muscles/0/rs");
  expect_bad([](Json& d) { d["muscles"][0]["tail"] = d["muscles"][0]["head"]; }, "/muscles/0/tail");
  expect_bad([](Json& d) { d["muscles"][0]["kind"] = "sheet"; }, "/muscles/0/kind");
  expect_bad([](Json& d) { d["muscles"][1]["name"] = d["muscles"][0]["name"]; }, "/muscles/1/name");
  expect_bad([](Json& d) { d["muscles"][0]["regions"][0] = "nose"; }, "/muscles/0/regions/0");
  expect_bad([](Json& d) { d["muscles"][0]["omega"] = "wide"; }, "/muscles/0/omega");
  expect_bad([](Json& d) { d["lips"]["control_points"].erase(0); }, "/lips/control_points");
  expect_bad([](Json& d) { d["lips"]["control_points"][3] = Json::array({1, 2}); }, "/lips/control_points/3");
  expect_bad([](Json& d) { d["eyes"].erase(1); }, "/eyes");
  expect_bad([](Json& d) { d["lips"]["samples_around"] = 5000; }, "/lips/samples_around");
  expect_bad([](Json& d) { d["lips"]["first_vertex"] = 5000; }, "/lips/first_vertex");
  expect_bad([](Json& d) { d["vertex_count"] = 20000000; }, "/vertex_count");
  expect_bad([](Json& d) { d["muscles"][0]["k"] = 1e308 * 10; }, "/muscles/0/k");
  expect_bad([](Json& d) { d["landmarks"]["ibug68"].erase(0); }, "/landmarks/ibug68");
  expect_bad([](Json& d) { d["regions"]["rest"].erase(0); }, "/regions");
  expect_bad([](Json& d) { d["regions"]["left_lower_face"].push_back(d["regions"]["rest"][0]); }, "/regions/");
  expect_bad([](Json& d) { d["materials"]["chrome"] = Json::array(); }, "/materials/chrome");
}

TEST(RigIo, RejectsMalformedAndTruncatedText) {
  const std::string text = format_rig(default_face().rig);
  EXPECT_THROW(parse_rig(text.substr(0, text.size() / 2), "t.rig"), FormatError);
  EXPECT_THROW(parse_rig("", "t.rig"), FormatError);
  EXPECT_THROW(parse_rig("[1,2,3]", "t.rig"), FormatError);
  EXPECT_THROW(parse_rig("{\"format\": \"emoface.rig\", \"version\": \"1.0\", \"x\": NaN}", "t.rig"), FormatError);
}

// The default rig with every format 1.1, 1.2 and 1.3 field set: a frame (mesh in decimetres,
// turned 90° about y and shifted), lips driven through bindings only, two parts, the border's jaw
// weights (1.2), the left eye's tightening angle (1.3).
Rig rig_1_1() {
  Rig rig = default_face().rig;
  rig.frame.scale = 0.1;
  rig.frame.rotation = Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix();
  rig.frame.translation = Eigen::Vector3d(0.01, -0.2, 0.03);
  rig.lips.samples_in_mesh = false;
  rig.lips.bound.push_back({7, 0.25, 0.5, Eigen::Vector3d(0.001, -0.002, 0.0005), 1.0});
  rig.lips.bound.push_back({3, 0.0, 1.0, Eigen::Vector3d::Zero(), 0.5});
  rig.parts.push_back({"eye_r", PartKind::Eyeball, 0, {1, 2, 5}});
  rig.parts.push_back({"teeth lower", PartKind::LowerTeeth, -1, {9}});
  rig.lips.border_jaw.assign(LipGrid::kAround, 0.0);
  rig.lips.border_jaw[3] = 0.25;
  rig.lips.border_jaw[18] = 1.0;
  rig.eyes[1].tighten_angle = 0.7 * rig.eyes[1].close_angle;
  return rig;
}

TEST(RigIo, RoundTripsFormat11Fields) {
  const Rig rig = rig_1_1();
  const std::string text = format_rig(rig);
  EXPECT_NE(text.find("\"version\": \"1.3\""), std::string::npos);
  const Rig back = parse_rig(text, "mem");
  EXPECT_EQ(format_rig(back), text);
  EXPECT_EQ(back.frame.scale, 0.1);
  EXPECT_EQ(back.frame.rotation, rig.frame.rotation);  // shortest round-trip doubles: exact
  EXPECT_EQ(back.frame.translation, rig.frame.translation);
  EXPECT_FALSE(back.lips.samples_in_mesh);
  ASSERT_EQ(back.lips.bound.size(), 2u);
  EXPECT_EQ(back.lips.bound[0].vertex, 7);
  EXPECT_EQ(back.lips.bound[0].u, 0.25);
  EXPECT_EQ(back.lips.bound[0].v, 0.5);
  EXPECT_EQ(back.lips.bound[0].offset, Eigen::Vector3d(0.001, -0.002, 0.0005));
  EXPECT_EQ(back.lips.bound[1].weight, 0.5);
  ASSERT_EQ(back.parts.size(), 2u);
  EXPECT_EQ(back.parts[1].name, "teeth lower");
  EXPECT_EQ(back.parts[1].kind, PartKind::LowerTeeth);
  EXPECT_EQ(back.parts[0].side, 0);
  EXPECT_EQ(back.parts[0].vertices, (std::vector<int>{1, 2, 5}));
  EXPECT_EQ(back.lips.border_jaw, rig.lips.border_jaw);
  EXPECT_FALSE(back.eyes[0].tighten_angle.has_value());
  ASSERT_TRUE(back.eyes[1].tighten_angle.has_value());
  EXPECT_EQ(*back.eyes[1].tighten_angle, *rig.eyes[1].tighten_angle);
}

TEST(RigIo, ReadsVersion10WithDefaults) {
  Json doc = Json::parse(format_rig(default_face().rig));
  EXPECT_FALSE(doc.contains("frame"));  // 1.1 fields at their defaults are not written
  EXPECT_FALSE(doc.contains("parts"));
  EXPECT_FALSE(doc["lips"].contains("bound"));
  EXPECT_FALSE(doc["lips"].contains("border_jaw"));  // 1.2: empty = derived by the solver
  EXPECT_FALSE(doc["eyes"][0].contains("tighten_angle"));  // 1.3: empty = close_angle
  doc["version"] = "1.0";
  const Rig rig = parse_rig(doc.dump(), "old.rig");
  EXPECT_TRUE(rig.frame.is_identity());
  EXPECT_TRUE(rig.lips.samples_in_mesh);
  EXPECT_TRUE(rig.lips.bound.empty());
  EXPECT_TRUE(rig.parts.empty());
  EXPECT_TRUE(rig.lips.border_jaw.empty());
  EXPECT_FALSE(rig.eyes[0].tighten_angle || rig.eyes[1].tighten_angle);
  EXPECT_TRUE(same_rig(rig, default_face().rig));
}

// The unknown-field rule of docs/formats.md (core::JsonReader): a newer minor version may add
// fields anywhere and they are ignored; the reader's own or an older minor version rejects an
// unknown field (a typo) at its pointer.
TEST(RigIo, UnknownFieldRule) {
  const Json base = Json::parse(format_rig(rig_1_1()));
  Json newer = base;
  newer["version"] = "1.4";
  newer["a_later_minor_field"] = Json::object({{"x", 1}});
  newer["lips"]["another_one"] = 3;
  newer["lips"]["bound"][1]["stiffness"] = 0.5;
  newer["eyes"][0]["iris_radius"] = 0.006;
  newer["muscles"][2]["note"] = "added in 1.4";
  newer["frame"]["units"] = "dm";
  newer["parts"][0]["colour"] = "white";
  EXPECT_EQ(format_rig(parse_rig(newer.dump(), "new.rig")), format_rig(rig_1_1()));
  const std::vector<std::pair<std::function<void(Json&)>, std::string>> typos{
      {[](Json& d) { d["lipz"] = 1; }, "/lipz"},
      {[](Json& d) { d["lips"]["samples_arround"] = 24; }, "/lips/samples_arround"},
      {[](Json& d) { d["lips"]["bound"][1]["wieght"] = 1; }, "/lips/bound/1/wieght"},
      {[](Json& d) { d["jaw"]["max_angel"] = 0.3; }, "/jaw/max_angel"},
      {[](Json& d) { d["eyes"][1]["raduis"] = 0.01; }, "/eyes/1/raduis"},
      {[](Json& d) { d["landmarks"]["ibug"] = Json::array(); }, "/landmarks/ibug"},
      {[](Json& d) { d["muscles"][3]["omgea"] = 1; }, "/muscles/3/omgea"},
      {[](Json& d) { d["frame"]["scael"] = 1; }, "/frame/scael"},
      {[](Json& d) { d["parts"][1]["sied"] = 0; }, "/parts/1/sied"},
      {[](Json& d) { d["a/b~c"] = 0; }, "/a~1b~0c"},  // RFC 6901 escapes
  };
  for (const char* version : {"1.3", "1.2", "1.1", "1.0"}) {
    for (const auto& [edit, pointer] : typos) {
      Json doc = base;
      doc["version"] = version;
      edit(doc);
      try {
        parse_rig(doc.dump(), "typo.rig");
        ADD_FAILURE() << "accepted " << pointer << " in " << version;
      } catch (const FormatError& e) {
        EXPECT_EQ(e.where().file, "typo.rig");
        EXPECT_EQ(e.where().json_pointer, pointer) << e.what();
        EXPECT_NE(std::string(e.what()).find("unknown field"), std::string::npos) << e.what();
      }
    }
  }
}

// As expect_bad, starting from rig_1_1().
void expect_bad_11(const std::function<void(Json&)>& edit, const std::string& pointer) {
  Json doc = Json::parse(format_rig(rig_1_1()));
  edit(doc);
  try {
    parse_rig(doc.dump(), "bad.rig");
    FAIL() << "accepted: " << pointer;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "bad.rig");
    EXPECT_EQ(e.where().json_pointer.rfind(pointer, 0), 0u) << e.what() << " expected " << pointer;
  }
}

TEST(RigIo, RejectsBadFormat11Content) {
  expect_bad_11([](Json& d) { d["frame"]["scale"] = 0.0; }, "/frame/scale");
  expect_bad_11([](Json& d) { d["frame"]["scale"] = -1.0; }, "/frame/scale");
  expect_bad_11([](Json& d) { d["frame"]["scale"] = "big"; }, "/frame/scale");
  expect_bad_11([](Json& d) { d["frame"].erase("translation"); }, "/frame");
  expect_bad_11([](Json& d) { d["frame"]["rotation"].erase(2); }, "/frame/rotation");
  expect_bad_11([](Json& d) { d["frame"]["rotation"][1] = Json::array({0, 2, 0}); }, "/frame/rotation");
  // a reflection is orthonormal but not a rotation
  expect_bad_11([](Json& d) { d["frame"]["rotation"] = Json::parse("[[-1,0,0],[0,1,0],[0,0,1]]"); }, "/frame/rotation");
  expect_bad_11([](Json& d) { d["frame"]["rotation"] = Json::parse("[[1,0,0],[0,1,0],[0,0,1.00001]]"); }, "/frame/rotation");
  expect_bad_11([](Json& d) { d["frame"]["translation"][1] = nullptr; }, "/frame/translation/1");
  expect_bad_11([](Json& d) { d["lips"]["bound"][0]["vertex"] = 99999999; }, "/lips/bound/0/vertex");
  expect_bad_11([](Json& d) { d["lips"]["bound"][0]["vertex"] = -1; }, "/lips/bound/0/vertex");
  expect_bad_11([](Json& d) { d["lips"]["bound"][1]["vertex"] = 7; }, "/lips/bound/1/vertex");
  expect_bad_11([](Json& d) { d["lips"]["bound"][0]["u"] = 1.0; }, "/lips/bound/0/u");
  expect_bad_11([](Json& d) { d["lips"]["bound"][0]["u"] = -0.1; }, "/lips/bound/0/u");
  expect_bad_11([](Json& d) { d["lips"]["bound"][0]["v"] = 1.5; }, "/lips/bound/0/v");
  expect_bad_11([](Json& d) { d["lips"]["bound"][0]["weight"] = 1.01; }, "/lips/bound/0/weight");
  expect_bad_11([](Json& d) { d["lips"]["bound"][0]["offset"][2] = "nan"; }, "/lips/bound/0/offset/2");
  expect_bad_11([](Json& d) { d["lips"]["bound"][0].erase("weight"); }, "/lips/bound/0");
  expect_bad_11([](Json& d) { d["lips"]["bound"] = 3; }, "/lips/bound");
  expect_bad_11([](Json& d) { d["lips"]["samples_in_mesh"] = "no"; }, "/lips/samples_in_mesh");
  // with the grid in the mesh, a bound vertex may not also be a grid sample
  expect_bad_11([](Json& d) {
    d["lips"]["samples_in_mesh"] = true;
    d["lips"]["bound"][0]["vertex"] = d["lips"]["first_vertex"].get<int>() + 3;
  }, "/lips/bound/0/vertex");
  expect_bad_11([](Json& d) { d["lips"]["control_points"] = Json::array(); }, "/lips/bound");
  expect_bad_11([](Json& d) { d["lips"]["border_jaw"].erase(23); }, "/lips/border_jaw");
  expect_bad_11([](Json& d) { d["lips"]["border_jaw"].push_back(0.5); }, "/lips/border_jaw");
  expect_bad_11([](Json& d) { d["lips"]["border_jaw"][5] = 1.5; }, "/lips/border_jaw/5");
  expect_bad_11([](Json& d) { d["lips"]["border_jaw"][6] = -0.1; }, "/lips/border_jaw/6");
  expect_bad_11([](Json& d) { d["lips"]["border_jaw"][7] = "half"; }, "/lips/border_jaw/7");
  expect_bad_11([](Json& d) { d["lips"]["border_jaw"] = 0.5; }, "/lips/border_jaw");
  // 1.3: the tightening angle lies in [0, close_angle] (more could shut the eye)
  expect_bad_11(
      [](Json& d) {
        d["eyes"][1]["tighten_angle"] = d["eyes"][1]["close_angle"].get<double>() + 0.01;
      },
      "/eyes/1/tighten_angle");
  expect_bad_11([](Json& d) { d["eyes"][1]["tighten_angle"] = -0.1; }, "/eyes/1/tighten_angle");
  expect_bad_11([](Json& d) { d["eyes"][1]["tighten_angle"] = "nan"; }, "/eyes/1/tighten_angle");
  expect_bad_11([](Json& d) { d["eyes"][0]["tighten_angle"] = nullptr; }, "/eyes/0/tighten_angle");
  expect_bad_11(
      [](Json& d) {
        d["lips"]["control_points"] = Json::array();
        d["lips"].erase("bound");
      },
      "/lips/border_jaw");
  expect_bad_11([](Json& d) { d["parts"][0]["kind"] = "wing"; }, "/parts/0/kind");
  expect_bad_11([](Json& d) { d["parts"][0]["side"] = 2; }, "/parts/0/side");
  expect_bad_11([](Json& d) { d["parts"][0]["name"] = ""; }, "/parts/0/name");
  expect_bad_11([](Json& d) { d["parts"][0]["vertices"] = Json::array({5, 2}); }, "/parts/0/vertices/1");
  expect_bad_11([](Json& d) { d["parts"][0]["vertices"] = Json::array({5, 5}); }, "/parts/0/vertices/1");
  expect_bad_11([](Json& d) { d["parts"][0]["vertices"][2] = 99999999; }, "/parts/0/vertices/2");
  expect_bad_11([](Json& d) { d["parts"] = Json::object(); }, "/parts");
}

TEST(RigIo, FrameRotationToleranceIs1e6) {
  Rig rig = rig_1_1();
  rig.frame.rotation(0, 1) += 2e-7;  // |R^T R - I| ~ 2e-7: accepted
  EXPECT_NO_THROW(validate_rig(rig));
  rig.frame.rotation(0, 1) += 2e-5;
  EXPECT_THROW(validate_rig(rig), FormatError);
}

TEST(RigIo, GridRangeIsNotCheckedWhenTheSamplesAreNotInTheMesh) {
  Rig rig = default_face().rig;
  rig.lips.first_vertex = static_cast<int>(rig.vertex_count);  // would exceed the mesh
  EXPECT_THROW(validate_rig(rig), FormatError);
  rig.lips.samples_in_mesh = false;
  EXPECT_NO_THROW(validate_rig(rig));
}

TEST(Frame, MapsBothWaysByTheFormula) {
  Frame f;
  f.scale = 0.1;
  f.rotation = Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix();
  f.translation = Eigen::Vector3d(1, 2, 3);
  // rotation by 90° about y takes (1, 0, 0) to (0, 0, -1): 0.1·(0, 0, -1) + (1, 2, 3)
  EXPECT_TRUE(f.to_rig(Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1, 2, 2.9), 1e-15));
  const Eigen::Vector3d p(0.3, -4, 7);
  EXPECT_TRUE(f.to_mesh(f.to_rig(p)).isApprox(p, 1e-14));
  EXPECT_FALSE(f.is_identity());
  EXPECT_TRUE(Frame{}.is_identity());
}

class FaceIo : public testing::TempDirTest {};

TEST_F(FaceIo, LoadFaceConvertsTheMeshFrameToTheRigFrame) {
  Face face = default_face();
  face.rig = rig_1_1();
  save_face(path("face.rig"), face);
  // the file holds the mesh frame: p_mesh = to_mesh(p_rig)
  const Mesh file = read_mesh(path(face.rig.mesh_file));
  const Eigen::Vector3d p0 = default_face().mesh.vertices.row(0).transpose();
  EXPECT_TRUE(Eigen::Vector3d(file.vertices.row(0).transpose()).isApprox(face.rig.frame.to_mesh(p0), 1e-7));
  // decimetres: the file is ten times larger than the rig
  const double extent_rig = (default_face().mesh.vertices.colwise().maxCoeff() - default_face().mesh.vertices.colwise().minCoeff()).norm();
  const double extent_file = (file.vertices.colwise().maxCoeff() - file.vertices.colwise().minCoeff()).norm();
  EXPECT_NEAR(extent_file / extent_rig, 10.0, 1e-5);
  const Face back = load_face(path("face.rig"));
  EXPECT_LT((back.mesh.vertices - default_face().mesh.vertices).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_EQ(back.mesh.faces, default_face().mesh.faces);
  EXPECT_EQ(format_rig(back.rig), format_rig(face.rig));
}


TEST_F(FaceIo, SaveAndLoadFace) {
  save_face(path("face.rig"), default_face());
  const Face back = load_face(path("face.rig"));
  EXPECT_EQ(back.mesh.vertex_count(), default_face().mesh.vertex_count());
  EXPECT_EQ(back.mesh.faces, default_face().mesh.faces);
  EXPECT_TRUE(back.mesh.vertices.isApprox(default_face().mesh.vertices, 1e-7));
  EXPECT_TRUE(same_rig(back.rig, default_face().rig));
}

TEST_F(FaceIo, RejectsMissingOrMismatchedMesh) {
  write_rig(path("face.rig"), default_face().rig);  // mesh file not written
  EXPECT_THROW(load_face(path("face.rig")), FormatError);
  write_mesh(path("default_face.obj"), testing::tetrahedron());
  EXPECT_THROW(load_face(path("face.rig")), FormatError);  // vertex count mismatch
}

// What a --rig option names: the built-in faces by name, anything else a rig file.
TEST_F(FaceIo, LoadFaceOrBuiltin) {
  EXPECT_TRUE(same_rig(load_face_or_builtin("").rig, make_default_face().rig));
  EXPECT_TRUE(same_rig(load_face_or_builtin("generic").rig, default_face().rig));
  save_face(path("face.rig"), default_face());
  const Face disk = load_face_or_builtin(path("face.rig"));
  EXPECT_TRUE(same_rig(disk.rig, default_face().rig));
  EXPECT_EQ(disk.mesh.vertex_count(), default_face().mesh.vertex_count());
  EXPECT_THROW(load_face_or_builtin(path("none.rig")), IoError);
}

}  // namespace
}  // namespace emoface::facemesh

namespace emoface::facemesh {
namespace {

TEST(Enums, StringRoundTrips) {
  for (int i = 0; i < kRegionCount; ++i) {
    const auto r = static_cast<Region>(i);
    EXPECT_EQ(region_from_string(to_string(r)), r);
  }
  EXPECT_EQ(to_string(Region::RightLowerFace), "right_lower_face");
  EXPECT_EQ(thesis_number(Region::Rest), 11);
  for (int i = 0; i < kMaterialCount; ++i) EXPECT_EQ(material_from_string(to_string(static_cast<Material>(i))), static_cast<Material>(i));
  EXPECT_EQ(to_string(Material::Lash), "lash");
  for (int i = 0; i <= static_cast<int>(PartKind::Other); ++i) {
    EXPECT_EQ(part_kind_from_string(to_string(static_cast<PartKind>(i))), static_cast<PartKind>(i));
  }
  EXPECT_EQ(to_string(PartKind::LowerTeeth), "lower_teeth");
  EXPECT_THROW(part_kind_from_string("wing"), InvalidInput);
  for (auto k : {MuscleKind::Vector, MuscleKind::Sphincter}) EXPECT_EQ(muscle_kind_from_string(to_string(k)), k);
  EXPECT_THROW(region_from_string("forehead"), InvalidInput);
  EXPECT_THROW(material_from_string(""), InvalidInput);
  EXPECT_THROW(muscle_kind_from_string("sheet"), InvalidInput);
}

}  // namespace
}  // namespace emoface::facemesh
