#include "emoface/retarget/retarget.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "emoface/core/errors.hpp"
#include "emoface/retarget/surface.hpp"
#include "refine.hpp"
#include "surface_index.hpp"

namespace emoface::retarget {
namespace {
Eigen::Vector3d map_point(const RbfNetwork& net, const Eigen::Vector3d& p) { return net.evaluate(p); }

int landmark_vertex(const facemesh::Rig& rig, const std::string& name) {
  for (const auto& l : rig.retarget_landmarks)
    if (l.name == name) return l.vertex;
  throw InvalidInput("the source rig has no retarget landmark \"" + name + "\"");
}
// RetargetOptions::refine_alignment: the alignment refined on the face. The source's stable face
// (skin of the upper and middle face regions, not moved by the jaw or the lids, not the socket caps
// behind the eyeballs) is pulled back into the aligned target's frame, each point paired with its
// closest point on the target (pairs farther apart than 2 % of the source's height rejected), and
// the least-squares similarity between the pairs (Umeyama 1991, "Least-squares estimation of
// transformation parameters between two point patterns", IEEE PAMI 13(4), eqs. 40–42;
// Eigen::umeyama) composed onto the alignment; repeated until it stops moving (≤ 200 times).
void refine_alignment(Alignment& a, const facemesh::Face& source, const facemesh::Mesh& target,
                      bool scale, double max_degrees) {
  namespace fm = facemesh;
  const auto& rig = source.rig;
  const auto nv = static_cast<std::size_t>(source.mesh.vertices.rows());
  if (rig.regions.size() != nv || rig.materials.size() != nv) return;
  std::vector<std::uint8_t> moving(nv, 0);
  for (int v : rig.jaw.vertices) moving[static_cast<std::size_t>(v)] = 1;
  for (const auto& e : rig.eyes) {
    for (int v : e.upper_lid) moving[static_cast<std::size_t>(v)] = 1;
    for (int v : e.lower_lid) moving[static_cast<std::size_t>(v)] = 1;
  }
  std::vector<Eigen::Vector3d> stable;
  for (std::size_t v = 0; v < nv; ++v) {
    const fm::Region g = rig.regions[v];
    const Eigen::Vector3d p = source.mesh.vertices.row(static_cast<Eigen::Index>(v)).transpose();
    bool socket = false;
    for (const auto& e : rig.eyes)
      socket = socket || ((p - e.centre).norm() < 2.0 * e.radius && p.z() < e.centre.z());
    if (rig.materials[v] == fm::Material::Skin && !moving[v] && !socket &&
        (g == fm::Region::RightMiddleFace || g == fm::Region::RightUpperFace ||
         g == fm::Region::LeftMiddleFace || g == fm::Region::LeftUpperFace))
      stable.push_back(p);
  }
  if (stable.size() < 20) return;
  const double height =
      source.mesh.vertices.col(1).maxCoeff() - source.mesh.vertices.col(1).minCoeff();
  const detail::SurfaceIndex index(fm::Mesh{a.apply(target.vertices), target.faces});
  double s = 1.0;  // aligned target → source: p ↦ s·R·p + t
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  std::size_t used = 0;
  for (int iteration = 0; iteration < 200; ++iteration) {
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> pairs;
    for (const auto& x : stable) {
      const auto h = index.closest(R.transpose() * (x - t) / s);
      if (h.face >= 0 && h.distance < 0.02 * height) pairs.emplace_back(h.point, x);
    }
    if (pairs.size() < 20) break;
    used = pairs.size();
    Eigen::Matrix3Xd from(3, static_cast<Eigen::Index>(used)),
        to(3, static_cast<Eigen::Index>(used));
    for (std::size_t k = 0; k < used; ++k)
      from.col(static_cast<Eigen::Index>(k)) = pairs[k].first,
      to.col(static_cast<Eigen::Index>(k)) = pairs[k].second;
    const Eigen::Matrix4d M = Eigen::umeyama(from, to, scale);
    const Eigen::Matrix3d sR = M.topLeftCorner<3, 3>();
    const double s1 = std::cbrt(sR.determinant());
    const Eigen::Matrix3d R1 = sR / s1;
    const Eigen::Vector3d t1 = M.topRightCorner<3, 1>();
    const double change = Eigen::AngleAxisd(R1 * R.transpose()).angle() + std::abs(s1 / s - 1.0) +
                          (t1 - t).norm() / height;
    s = s1, R = R1, t = t1;
    if (change < 1e-9) break;
  }
  if (used < 20) return;
  auto& rep = a.report;
  rep.refine_points = used;
  rep.refine_angle_deg = Eigen::AngleAxisd(R).angle() * 180.0 / 3.14159265358979323846;
  rep.refine_scale = s;
  if (rep.refine_angle_deg > max_degrees) {
    // a face shaped unlike the source: the ICP's pose is a compromise between shapes, not a
    // correction of the alignment's (MakeHuman: 7.7° against the pitch found on E, and its mouth
    // fitted worse); the alignment is kept
    rep.message +=
        "; refinement on the face (" + std::to_string(rep.refine_angle_deg) + " deg) not applied";
    return;
  }
  a.translation = s * (R * a.translation) + t;
  a.rotation = R * a.rotation;
  a.scale *= s;
  rep.refined = true;
  const Eigen::AngleAxisd aa(a.rotation);
  rep.axis = aa.axis();
  rep.angle_deg = aa.angle() * 180.0 / 3.14159265358979323846;
  rep.message += "; refined on the face by " + std::to_string(rep.refine_angle_deg) + " deg";
}
}  // namespace

void RefineOptions::validate() const {
  if (max_iterations < 1 || max_iterations > 1000) throw InvalidInput("RefineOptions::max_iterations must be in [1, 1000]");
  if (!(step > 0.0 && step <= 0.01)) throw InvalidInput("RefineOptions::step must be in (0, 0.01] m");
}

void RetargetOptions::validate() const {
  clean.validate();
  refine.validate();
  align.validate();
  rbf.validate();
  error.validate();
  ga.validate();
  if (mouth_samples < 0 || mouth_samples > 1000) throw InvalidInput("RetargetOptions::mouth_samples must be in [0, 1000]");
  if (!(pitch_search_degrees >= 0.0 && pitch_search_degrees <= 60.0)) throw InvalidInput("RetargetOptions::pitch_search_degrees must be in [0, 60]");
  if (!(prior_weight >= 0.0) || !std::isfinite(prior_weight)) throw InvalidInput("RetargetOptions::prior_weight must be finite and >= 0");
  if (!(refine_max_degrees >= 0.0 && refine_max_degrees <= 30.0))
    throw InvalidInput("RetargetOptions::refine_max_degrees must be in [0, 30]");
  if (std::find(detected.begin(), detected.end(), "top_of_head") == detected.end())
    throw InvalidInput("RetargetOptions::detected must contain top_of_head (it defines the centreline, thesis §3.5)");
}

Eigen::Vector3d landmark_position(const facemesh::Face& face, const std::string& name) {
  const int v = landmark_vertex(face.rig, name);
  if (v < 0 || v >= face.mesh.vertices.rows()) throw InvalidInput("landmark \"" + name + "\" is out of range");
  return face.mesh.vertices.row(v);
}

facemesh::Face transfer_face(const facemesh::Face& source, const RbfNetwork& net, double s) {
  if (!(s > 0.0) || !std::isfinite(s)) throw InvalidInput("transfer_face: length_scale must be finite and > 0");
  facemesh::Face out = source;
  net.evaluate(source.mesh.vertices, out.mesh.vertices);
  auto& rig = out.rig;
  for (auto& m : rig.muscles) {  // thesis §3.7: the muscles are transferred with the same networks
    m.head = map_point(net, m.head);
    m.tail = map_point(net, m.tail);
    m.rs *= s;
    m.rf *= s;
    m.k *= s;
    m.wrinkle_height *= s;
    m.semi_axes *= s;
  }
  for (auto& c : rig.lips.control_points) c = map_point(net, c);
  rig.lips.centre = map_point(net, rig.lips.centre);
  rig.jaw.pivot = map_point(net, rig.jaw.pivot);
  for (auto& e : rig.eyes) {
    e.centre = map_point(net, e.centre);
    e.radius *= s;
  }
  rig.head_pivot = map_point(net, rig.head_pivot);
  return out;
}

RetargetResult retarget_face(const facemesh::Face& source, const facemesh::Mesh& input,
                             const RetargetOptions& options, const std::function<void(const GaProgress&)>& progress) {
  options.validate();
  RetargetResult r;
  const facemesh::Mesh target = clean_target(input, options.clean, &r.cleaning);
  const auto& rig = source.rig;
  if (rig.retarget_landmarks.size() < 3) throw InvalidInput("the source rig needs at least three retarget landmarks");
  const int source_top = landmark_vertex(rig, "top_of_head");
  // Error options of the pipeline: sampling down to the source chin (no neck), the mouth band.
  const auto error_setup = [&](ErrorOptions eo) {
    bool has_chin = false;
    for (const auto& l : rig.retarget_landmarks) has_chin = has_chin || l.name == "chin";
    if (!has_chin) return eo;
    const double chin_y = landmark_position(source, "chin").y(), nose_y = landmark_position(source, "nose_tip").y();
    if (eo.bottom_y <= -1e299) eo.bottom_y = chin_y;
    if (eo.band_samples == 0 && options.mouth_samples > 0 && nose_y > chin_y) {
      eo.band_samples = options.mouth_samples;
      eo.band_bottom = chin_y;
      eo.band_top = nose_y;
    }
    return eo;
  };
  const Eigen::Vector3d top = landmark_position(source, "top_of_head"), nose = landmark_position(source, "nose_tip");
  r.alignment = align_to_frame(target, source.mesh, top, nose, options.align);
  const auto& ar = r.alignment.report;
  if (options.align.mode == AlignMode::Auto && ar.confidence < options.align.min_confidence)
    throw InvalidInput("cannot orient the target reliably (alignment confidence " + std::to_string(ar.confidence) + " < " +
                       std::to_string(options.align.min_confidence) + "; " + ar.message +
                       "): give --up/--front hints, or --align axes if the mesh is already axis-aligned");
  if (options.align.mode == AlignMode::Auto && options.pitch_search_degrees > 0) {
    // E of the source deformed by the RBF on the detected landmarks, for the target aligned by `a`.
    const ErrorOptions eo = error_setup(options.error);
    facemesh::Vertices deformed;
    auto initial_error = [&](const Alignment& a) {
      facemesh::Mesh aligned = target;
      aligned.vertices = a.apply(target.vertices);
      try {
        const auto found = detect_landmarks(aligned, options.detected);
        Eigen::MatrixX3d src(static_cast<Eigen::Index>(found.size()), 3), dst(static_cast<Eigen::Index>(found.size()), 3);
        int top_vertex = -1;
        for (std::size_t k = 0; k < found.size(); ++k) {
          src.row(static_cast<Eigen::Index>(k)) = landmark_position(source, found[k].name).transpose();
          dst.row(static_cast<Eigen::Index>(k)) = aligned.vertices.row(found[k].vertex);
          if (found[k].name == "top_of_head") top_vertex = found[k].vertex;
        }
        const ErrorFunction e(aligned, top_vertex, source.mesh.faces, source.mesh.vertex_count(), eo);
        fit_rbf(src, dst, options.rbf).evaluate(source.mesh.vertices, deformed);
        const double v = e.evaluate(deformed, source_top);
        return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
      } catch (const InvalidInput&) {
        return std::numeric_limits<double>::infinity();
      }
    };
    const Alignment base = r.alignment;
    double best_e = initial_error(base), best_deg = 0.0;
    auto try_pitch = [&](double deg) {
      Alignment a = base;
      a.rotation = Eigen::AngleAxisd(deg * 3.14159265358979323846 / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix() * base.rotation;
      try {
        place_in_frame(a, target, top, nose, options.align.scale);
      } catch (const InvalidInput&) {
        return;
      }
      const double e = initial_error(a);
      if (e < best_e) {
        best_e = e;
        best_deg = deg;
        r.alignment = a;
      }
    };
    const double range = options.pitch_search_degrees;
    for (double deg = -range; deg <= range + 1e-9; deg += 2.0)
      if (deg != 0.0) try_pitch(deg);
    const double centre = best_deg;
    for (double deg = centre - 1.5; deg <= centre + 1.5 + 1e-9; deg += 0.5)
      if (deg != centre) try_pitch(deg);
    r.alignment.report.pitch_correction_deg = best_deg;
    const Eigen::AngleAxisd aa(r.alignment.rotation);
    r.alignment.report.axis = aa.axis();
    r.alignment.report.angle_deg = aa.angle() * 180.0 / 3.14159265358979323846;
    if (best_deg != 0.0) r.alignment.report.message += "; pitch corrected by " + std::to_string(best_deg) + " deg on the initial error E";
  }
  if (options.refine_alignment)
    refine_alignment(r.alignment, source, target, options.align.scale, options.refine_max_degrees);
  r.aligned_target = target;
  r.aligned_target.vertices = r.alignment.apply(target.vertices);
  const auto found = detect_landmarks(r.aligned_target, options.detected);

  const auto count = static_cast<Eigen::Index>(rig.retarget_landmarks.size());
  r.source_landmarks.resize(count, 3);
  r.detected.assign(static_cast<std::size_t>(count), false);
  Eigen::MatrixX3d detected_target(count, 3);
  for (Eigen::Index i = 0; i < count; ++i) {
    const auto& l = rig.retarget_landmarks[static_cast<std::size_t>(i)];
    r.landmark_names.push_back(l.name);
    r.source_landmarks.row(i) = landmark_position(source, l.name).transpose();
    for (const auto& d : found)
      if (d.name == l.name) {
        r.detected[static_cast<std::size_t>(i)] = true;
        detected_target.row(i) = r.aligned_target.vertices.row(d.vertex);
      }
  }
  for (const auto& d : found)
    if (std::find(r.landmark_names.begin(), r.landmark_names.end(), d.name) == r.landmark_names.end())
      throw InvalidInput("detected landmark \"" + d.name + "\" is not a retarget landmark of the source rig");
  std::vector<Eigen::Index> fixed, free;
  for (Eigen::Index i = 0; i < count; ++i) (r.detected[static_cast<std::size_t>(i)] ? fixed : free).push_back(i);
  if (fixed.size() < 2) throw InvalidInput("need at least two detected landmarks");
  auto rows = [](const Eigen::MatrixX3d& m, const std::vector<Eigen::Index>& ids) {
    Eigen::MatrixX3d out(static_cast<Eigen::Index>(ids.size()), 3);
    for (std::size_t k = 0; k < ids.size(); ++k) out.row(static_cast<Eigen::Index>(k)) = m.row(ids[k]);
    return out;
  };

  // thesis §3.3: initial non-detected landmarks from the RBF trained on the detected ones, then put on
  // the target surface by cylindrical projection (§3.2.1).
  const int target_top = found[static_cast<std::size_t>(std::find(options.detected.begin(), options.detected.end(), "top_of_head") - options.detected.begin())].vertex;
  if (MeshWalker(r.aligned_target.faces, r.aligned_target.vertex_count()).on_boundary(target_top))
    throw InvalidInput("the target's highest vertex lies on an open boundary: the mesh has no top of head (a face mask "
                       "or a scan open at the top?); the error function of thesis §3.5 walks down from the top of the head");
  const CylindricalProjector projector(r.aligned_target, r.aligned_target.vertices.row(target_top));
  const RbfNetwork initial_net = fit_rbf(rows(r.source_landmarks, fixed), rows(detected_target, fixed), options.rbf);
  r.initial_landmarks = detected_target;
  for (auto i : free) {
    Eigen::Vector3d p = initial_net.evaluate(Eigen::Vector3d(r.source_landmarks.row(i)));
    Eigen::Vector3d q;
    if (projector.project(p, q)) p = q;
    r.initial_landmarks.row(i) = p.transpose();
  }

  ErrorOptions error_options = error_setup(options.error);
  const ErrorFunction error(r.aligned_target, target_top, source.mesh.faces, source.mesh.vertex_count(), error_options);

  // Mirror partner of every searched landmark (index into `free`, −1 = on the symmetry plane).
  const double mirror_x = r.aligned_target.vertices(target_top, 0);
  std::vector<int> partner(free.size(), -1);
  for (std::size_t k = 0; k < free.size(); ++k) {
    const std::string& name = r.landmark_names[static_cast<std::size_t>(free[k])];
    if (name.size() < 2 || (name.compare(name.size() - 2, 2, "_l") != 0 && name.compare(name.size() - 2, 2, "_r") != 0)) continue;
    const std::string other = name.substr(0, name.size() - 1) + (name.back() == 'l' ? "r" : "l");
    for (std::size_t j = 0; j < free.size(); ++j)
      if (r.landmark_names[static_cast<std::size_t>(free[j])] == other) partner[k] = static_cast<int>(j);
    if (partner[k] < 0) partner[k] = static_cast<int>(k);  // partner is detected: leave it alone
  }
  auto symmetrize = [&](Eigen::MatrixX3d& p) {
    const Eigen::MatrixX3d in = p;
    for (std::size_t k = 0; k < free.size(); ++k) {
      const auto i = static_cast<Eigen::Index>(k);
      if (partner[k] < 0) {
        p(i, 0) = mirror_x;
      } else if (partner[k] != static_cast<int>(k)) {
        const auto j = static_cast<Eigen::Index>(partner[k]);
        p.row(i) = 0.5 * (in.row(i) + in.row(j));
        p(i, 0) = 0.5 * (in(i, 0) + 2 * mirror_x - in(j, 0));
      }
    }
  };
  if (options.symmetric) {
    Eigen::MatrixX3d initial_free = rows(r.initial_landmarks, free);
    symmetrize(initial_free);
    for (std::size_t k = 0; k < free.size(); ++k) r.initial_landmarks.row(free[k]) = initial_free.row(static_cast<Eigen::Index>(k));
  }
  const Eigen::MatrixX3d prior = rows(r.initial_landmarks, free);

  Eigen::MatrixX3d all = r.initial_landmarks;
  facemesh::Vertices deformed;
  const bool project = options.ga.projection != ProjectionMode::Off;
  const GaEvaluate evaluate = [&](Eigen::MatrixX3d& positions) {
    if (options.symmetric) symmetrize(positions);
    for (Eigen::Index k = 0; k < positions.rows(); ++k) {
      Eigen::Vector3d q;
      if (project && projector.project(positions.row(k).transpose(), q)) positions.row(k) = q.transpose();
      all.row(free[static_cast<std::size_t>(k)]) = positions.row(k);
    }
    const RbfNetwork net = fit_rbf(r.source_landmarks, all, options.rbf);
    net.evaluate(source.mesh.vertices, deformed);
    // fitness = 1/E (thesis §3.6.2), E of §3.5 plus the optional prior (beyond the thesis)
    return error.evaluate(deformed, source_top) + options.prior_weight * (positions - prior).squaredNorm();
  };
  // Residual form of the same objective for the optional refinement.
  const detail::ResidualFunction residuals = [&](Eigen::MatrixX3d& positions, std::vector<double>& out) {
    evaluate(positions);  // symmetrise, project, deform (fills `deformed`)
    error.residuals(deformed, source_top, out);
    const double w = std::sqrt(options.prior_weight);
    for (Eigen::Index k = 0; k < positions.rows(); ++k)
      for (int c = 0; c < 3; ++c) out.push_back(w * (positions(k, c) - prior(k, c)));
  };
  r.target_landmarks = r.initial_landmarks;
  if (!free.empty()) {
    const GaResult ga = run_ga(rows(r.initial_landmarks, free), evaluate, options.ga, progress);
    Eigen::MatrixX3d best = ga.positions;
    r.ga = ga.report;
    if (options.refine.enabled) best = detail::refine_landmarks(best, residuals, options.refine, r.refine);
    for (std::size_t k = 0; k < free.size(); ++k) r.target_landmarks.row(free[k]) = best.row(static_cast<Eigen::Index>(k));
  }
  const RbfNetwork final_net = fit_rbf(r.source_landmarks, r.target_landmarks, options.rbf);
  // Length scale: RMS spread of the target landmarks over that of the source landmarks.
  auto spread = [](const Eigen::MatrixX3d& m) { return (m.rowwise() - m.colwise().mean()).squaredNorm(); };
  r.length_scale = std::sqrt(spread(r.target_landmarks) / spread(r.source_landmarks));
  r.face = transfer_face(source, final_net, r.length_scale);
  return r;
}

}  // namespace emoface::retarget
