#include "emoface/facemesh/io.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "emoface/core/errors.hpp"
#include "emoface/core/io.hpp"
#include "emoface/facemesh/default_face.hpp"
#include "emoface/facemesh/mesh_io.hpp"
#include "test_util.hpp"

namespace emoface::facemesh {
namespace {

using Json = nlohmann::ordered_json;

const Face& default_face() {
  static const Face face = make_default_face();
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

// Applies `edit` to the default rig JSON and expects a FormatError whose pointer starts with `pointer`.
void expect_bad(const std::function<void(Json&)>& edit, const std::string& pointer) {
  Json doc = Json::parse(format_rig(default_face().rig));
  edit(doc);
  try {
    parse_rig(doc.dump(), "bad.rig");
    FAIL() << "accepted: " << pointer;
  } catch (const FormatError& e) {
    EXPECT_EQ(e.where().file, "bad.rig");
    EXPECT_EQ(e.where().json_pointer.rfind(pointer, 0), 0u) << e.what() << " expected " << pointer;
  }
}

TEST(RigIo, RejectsBadContent) {
  expect_bad([](Json& d) { d["format"] = "emoface.mesh"; }, "/format");
  expect_bad([](Json& d) { d["version"] = "2.0"; }, "/version");
  expect_bad([](Json& d) { d.erase("jaw"); }, "/jaw");
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

class FaceIo : public testing::TempDirTest {};

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

}  // namespace
}  // namespace emoface::facemesh
