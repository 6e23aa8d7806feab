#include "emoface/retarget/io.hpp"

#include <nlohmann/json.hpp>

#include "emoface/core/io.hpp"

namespace emoface::retarget {
namespace {
nlohmann::ordered_json vec(const Eigen::Vector3d& v) { return nlohmann::ordered_json::array({v.x(), v.y(), v.z()}); }
}  // namespace

std::string format_report(const RetargetResult& r, bool include_time) {
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
  return doc.dump(2) + "\n";
}

void write_report(const std::string& path, const RetargetResult& result, bool include_time) {
  core::write_file_atomic(path, format_report(result, include_time));
}

}  // namespace emoface::retarget
