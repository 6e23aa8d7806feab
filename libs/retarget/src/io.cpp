#include "emoface/retarget/io.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "emoface/core/io.hpp"
#include "emoface/core/json_reader.hpp"

namespace emoface::retarget {
namespace {
nlohmann::ordered_json vec(const Eigen::Vector3d& v) { return nlohmann::ordered_json::array({v.x(), v.y(), v.z()}); }
}  // namespace

namespace {
nlohmann::ordered_json report_json(const RetargetResult& r, bool include_time) {
  auto doc = core::make_envelope("retarget_report", {kReportFormatMajor, kReportFormatMinor});
  auto& c = doc["cleaning"];
  c["components"] = r.cleaning.components;
  c["kept_components"] = r.cleaning.kept_components;
  c["dropped_faces"] = r.cleaning.dropped_faces;
  c["dropped_vertices"] = r.cleaning.dropped_vertices;
  auto& a = doc["alignment"];
  a["scale"] = r.alignment.scale;
  a["rotation"] = nlohmann::ordered_json::array();
  for (int i = 0; i < 3; ++i) a["rotation"].push_back(vec(r.alignment.rotation.row(i).transpose()));
  a["translation"] = vec(r.alignment.translation);
  a["meaning"] = "thesis-frame point = scale * rotation * input point + translation";
  const auto& ar = r.alignment.report;
  a["method"] = to_string(ar.method);
  a["axis"] = vec(ar.axis);
  a["angle_deg"] = ar.angle_deg;
  a["confidence"] = ar.confidence;
  a["symmetry_error"] = ar.symmetry_error;
  a["symmetry_margin"] = ar.symmetry_margin;
  a["match_cost"] = ar.match_cost;
  a["orientation_margin"] = ar.orientation_margin;
  a["landmark_offset"] = ar.landmark_offset;
  a["nose_on_plane"] = ar.nose_on_plane;
  a["top_on_plane"] = ar.top_on_plane;
  a["hints_used"] = ar.hints_used;
  a["snapped"] = ar.snapped;
  a["pitch_correction_deg"] = ar.pitch_correction_deg;
  a["refined"] = ar.refined;  // 1.4
  a["refine_points"] = ar.refine_points;
  a["refine_angle_deg"] = ar.refine_angle_deg;
  a["refine_scale"] = ar.refine_scale;
  a["message"] = ar.message;
  doc["length_scale"] = r.length_scale;
  auto& lm = doc["landmarks"];
  lm = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < r.landmark_names.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    nlohmann::ordered_json l;
    l["name"] = r.landmark_names[i];
    l["detected"] = static_cast<bool>(r.detected[i]);
    l["source"] = vec(r.source_landmarks.row(k).transpose());
    l["initial"] = vec(r.initial_landmarks.row(k).transpose());
    l["final"] = vec(r.target_landmarks.row(k).transpose());
    lm.push_back(l);
  }
  auto& g = doc["ga"];
  g["status"] = r.ga.status;
  g["message"] = r.ga.message;
  g["generations"] = r.ga.generations;
  g["evaluations"] = r.ga.evaluations;
  g["initial_error"] = r.ga.initial_error;
  g["best_error"] = r.ga.best_error;
  g["error_curve"] = r.ga.error_curve;
  g["mutation_curve"] = r.ga.mutation_curve;
  if (include_time) g["seconds"] = r.ga.seconds;
  if (r.refine.ran) {
    auto& f = doc["refine"];
    f["status"] = r.refine.status;
    f["iterations"] = r.refine.iterations;
    f["initial_error"] = r.refine.initial_error;
    f["final_error"] = r.refine.final_error;
    if (include_time) f["seconds"] = r.refine.seconds;
  }
  return doc;
}
}  // namespace

std::string format_report(const RetargetResult& r, bool include_time) { return report_json(r, include_time).dump(2) + "\n"; }

void write_report(const std::string& path, const RetargetResult& result, bool include_time) {
  core::write_file_atomic(path, format_report(result, include_time));
}

}  // namespace emoface::retarget

namespace emoface::retarget {

std::string format_transfer_report(const TransferResult& result, bool include_time) {
  auto doc = report_json(result.fit, include_time);
  doc["mode"] = "transfer";
  const auto& r = result.report;
  auto& t = doc["transfer"];
  const auto& fr = result.face.rig.frame;
  t["frame"]["scale"] = fr.scale;
  t["frame"]["rotation"] = nlohmann::ordered_json::array();
  for (int i = 0; i < 3; ++i) t["frame"]["rotation"].push_back(vec(fr.rotation.row(i).transpose()));
  t["frame"]["translation"] = vec(fr.translation);
  t["frame"]["meaning"] = "rig-frame point = scale * rotation * mesh-file point + translation";
  t["vertices"] = result.face.mesh.vertices.rows();
  t["components"] = r.components;
  t["head_height"] = r.head_height;
  t["head_height_meaning"] = "top of head to chin of the registered generic face, input units";
  t["user_landmarks"] = r.user_landmarks;
  t["replaced_landmarks"] = r.replaced_landmarks;  // 1.3
  auto& g = t["registration"];
  g["iterations"] = r.registration.iterations;
  g["correspondences"] = r.registration.correspondences;
  g["initial_rms"] = r.registration.initial_rms / fr.scale;
  g["final_rms"] = r.registration.final_rms / fr.scale;
  g["units"] = "input units";
  auto& res = t["residuals"];
  res = nlohmann::ordered_json::array();
  for (const auto& rr : r.residuals) {
    nlohmann::ordered_json j;
    j["region"] = rr.region;
    j["vertices"] = rr.vertices;
    j["mean"] = rr.mean, j["p95"] = rr.p95, j["max"] = rr.max;
    j["mean_percent"] = rr.mean_percent, j["p95_percent"] = rr.p95_percent, j["max_percent"] = rr.max_percent;
    res.push_back(j);
  }
  auto& lm = t["ibug68"];
  lm = nlohmann::ordered_json::array();
  for (const auto& l : r.landmarks) {
    nlohmann::ordered_json j;
    j["index"] = l.index, j["vertex"] = l.vertex, j["source"] = l.source;
    j["distance"] = l.distance, j["confidence"] = l.confidence;
    lm.push_back(j);
  }
  auto& parts = t["parts"];
  parts = nlohmann::ordered_json::array();
  for (const auto& p : r.parts) {
    nlohmann::ordered_json j;
    j["name"] = p.name, j["kind"] = facemesh::to_string(p.kind), j["side"] = p.side, j["vertices"] = p.vertices;
    j["found_by"] = p.found_by;
    if (p.kind == facemesh::PartKind::Eyeball && p.radius > 0) j["centre"] = vec(p.centre), j["radius"] = p.radius, j["sphere_rms"] = p.rms;
    parts.push_back(j);
  }
  auto& c = t["counts"];
  c["lip_bound"] = r.lip_bound, c["lip_full"] = r.lip_full, c["jaw"] = r.jaw_vertices, c["mouth_bag"] = r.mouth_bag;
  c["lip_bag_bound"] = r.lip_bag_bound;
  c["lid_right"] = r.lid_vertices[0], c["lid_left"] = r.lid_vertices[1];
  c["eye_hole_right"] = r.eye_hole_vertices[0], c["eye_hole_left"] = r.eye_hole_vertices[1];
  c["mouth_slit_points"] = r.mouth_slit_points;  // 1.3
  auto& lids = t["lids"];  // 1.3
  lids = nlohmann::ordered_json::array();
  for (int e = 0; e < 2; ++e) {
    nlohmann::ordered_json j;
    j["eye"] = e == 0 ? "right" : "left";
    j["method"] = r.lid_method[static_cast<std::size_t>(e)];
    j["margin_upper"] = r.lid_margin_upper[static_cast<std::size_t>(e)];
    j["margin_lower"] = r.lid_margin_lower[static_cast<std::size_t>(e)];
    j["close_angle"] = result.face.rig.eyes[static_cast<std::size_t>(e)].close_angle;
    lids.push_back(j);
  }
  t["warnings"] = r.warnings;
  if (include_time) {
    t["seconds"]["fit"] = r.fit_seconds;
    t["seconds"]["registration"] = r.registration_seconds;
    t["seconds"]["transfer"] = r.transfer_seconds;
  }
  return doc.dump(2) + "\n";
}

void write_transfer_report(const std::string& path, const TransferResult& result, bool include_time) {
  core::write_file_atomic(path, format_transfer_report(result, include_time));
}

UserLandmarks parse_landmarks(std::string_view text, const std::string& source) {
  // The unknown-field rule of docs/formats.md: a newer 1.x may add fields; 1.0 may not.
  const core::JsonReader reader(text, source, "landmarks",
                                {kLandmarksFormatMajor, kLandmarksFormatMinor});
  const core::JsonValue doc = reader.root();
  doc.only_keys({"scheme", "points"});
  const core::JsonValue scheme = doc.at("scheme");
  if (!scheme.is_string() || scheme.string() != "ibug68") scheme.fail("must be \"ibug68\"");
  const core::JsonValue pts = doc.at("points").expect_array();
  if (pts.size() != static_cast<std::size_t>(UserLandmarks::kCount))
    pts.fail("expected 68 iBUG points, got " + std::to_string(pts.size()));
  UserLandmarks out;
  out.points.resize(pts.size());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const core::JsonValue e = pts[k];
    auto& p = out.points[k];
    if (e.is_null()) continue;
    if (e.is_array()) {
      p.point = {e.expect_array(3)[0].number(), e[1].number(), e[2].number()};
      p.kind = UserLandmarkKind::Point;
    } else if (e.is_number()) {
      p.vertex = static_cast<int>(e.integer(0, 2147483647));
      p.kind = UserLandmarkKind::Vertex;
    } else {
      e.fail("expected a vertex id, [x, y, z] or null");
    }
  }
  return out;
}

std::string format_landmarks(const UserLandmarks& landmarks) {
  if (landmarks.points.size() != static_cast<std::size_t>(UserLandmarks::kCount))
    throw InvalidInput("format_landmarks: needs exactly 68 points");
  auto doc = core::make_envelope("landmarks", {kLandmarksFormatMajor, kLandmarksFormatMinor});
  doc["scheme"] = "ibug68";
  auto& pts = doc["points"];
  pts = nlohmann::ordered_json::array();
  for (const auto& p : landmarks.points) {
    if (p.kind == UserLandmarkKind::Missing) pts.push_back(nullptr);
    else if (p.kind == UserLandmarkKind::Vertex) pts.push_back(p.vertex);
    else {
      if (!p.point.allFinite()) throw InvalidInput("format_landmarks: non-finite point");
      pts.push_back(vec(p.point));
    }
  }
  return doc.dump(2) + "\n";
}

UserLandmarks read_landmarks(const std::string& path) { return parse_landmarks(core::read_file(path), path); }

void write_landmarks(const std::string& path, const UserLandmarks& landmarks) {
  core::write_file_atomic(path, format_landmarks(landmarks));
}

}  // namespace emoface::retarget
