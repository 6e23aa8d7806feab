// The muscle-driven face (thesis §2.4).
#include "emoface/muscles/solver.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "emoface/core/errors.hpp"
#include "fast_math.hpp"

namespace emoface::muscles {
namespace {

constexpr double kHalfPi = 1.5707963267948966;
constexpr double kPi = 3.14159265358979323846;

// Rotation about the x axis through `pivot` by angle a (right-handed: +a moves +z towards -y).
inline Eigen::Vector3d rotate_x(const Eigen::Vector3d& p, const Eigen::Vector3d& pivot, double a) {
  const double c = std::cos(a), s = std::sin(a);
  const Eigen::Vector3d q = p - pivot;
  return pivot + Eigen::Vector3d(q.x(), q.y() * c - q.z() * s, q.y() * s + q.z() * c);
}

}  // namespace

std::string to_string(EyelidCoupling coupling) {
  switch (coupling) {
    case EyelidCoupling::OneEye: return "one_eye";
    case EyelidCoupling::Thesis: return "thesis";
    case EyelidCoupling::Off: return "off";
  }
  return "one_eye";
}

EyelidCoupling eyelid_coupling_from_string(std::string_view name) {
  if (name == "one_eye") return EyelidCoupling::OneEye;
  if (name == "thesis") return EyelidCoupling::Thesis;
  if (name == "off") return EyelidCoupling::Off;
  throw InvalidInput("unknown eyelid coupling '" + std::string(name) + "' (one_eye, thesis or off)");
}

void SolverOptions::validate() const {
  auto check = [](bool ok, const char* what) {
    if (!ok) throw InvalidInput(std::string("SolverOptions: ") + what);
  };
  check(delta_c > 0.0 && delta_c <= 1.0, "delta_c must be in (0, 1]");
  check(zone_margin >= 0.0 && zone_margin <= 4.0, "zone_margin must be in [0, 4]");
  check(funnel_rotation >= 0.0 && funnel_rotation <= kHalfPi, "funnel_rotation must be in [0, pi/2]");
  check(press_rotation >= 0.0 && press_rotation <= kHalfPi, "press_rotation must be in [0, pi/2]");
  check(lid_closing_exponent >= 1.0 && lid_closing_exponent <= 5.0, "lid_closing_exponent must be in [1, 5]");
  check(funnel_extrusion >= 0.0 && funnel_extrusion <= 0.05, "funnel_extrusion must be in [0, 0.05]");
}

FaceSolver::FaceSolver(facemesh::Mesh mesh, facemesh::Rig rig, SolverOptions options)
    : mesh_(std::move(mesh)),
      rig_(std::move(rig)),
      options_(options),
      lip_sampler_(std::max(rig_.lips.samples_around, facemesh::LipGrid::kAround),
                   std::max(rig_.lips.samples_across, facemesh::LipGrid::kAcross)) {
  options_.validate();
  try {
    facemesh::validate_rig(rig_, "<rig>");
    facemesh::validate_mesh(mesh_, "<mesh>");
  } catch (const FormatError& e) {
    throw InvalidInput(std::string("FaceSolver: ") + e.what());
  }
  if (rig_.vertex_count != mesh_.vertex_count()) {
    throw InvalidInput("FaceSolver: the rig expects " + std::to_string(rig_.vertex_count) + " vertices, the mesh has " +
                       std::to_string(mesh_.vertex_count()));
  }
  // vertex -> incident faces (CSR), for the normals under the wrinkles
  vertex_face_start_.assign(mesh_.vertex_count() + 1, 0);
  for (long f = 0; f < mesh_.faces.rows(); ++f) {
    for (int k = 0; k < 3; ++k) ++vertex_face_start_[static_cast<std::size_t>(mesh_.faces(f, k)) + 1];
  }
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) vertex_face_start_[v + 1] += vertex_face_start_[v];
  vertex_faces_.resize(static_cast<std::size_t>(vertex_face_start_.back()));
  {
    std::vector<int> fill(vertex_face_start_.begin(), vertex_face_start_.end() - 1);
    for (long f = 0; f < mesh_.faces.rows(); ++f) {
      for (int k = 0; k < 3; ++k) vertex_faces_[static_cast<std::size_t>(fill[static_cast<std::size_t>(mesh_.faces(f, k))]++)] = static_cast<int>(f);
    }
  }
  const auto regions = facemesh::region_vertices(rig_);
  const auto& cps = rig_.lips.control_points;
  // Region cut-off (thesis §2.4.1): a muscle visits only vertices of its regions; we further keep those
  // whose neutral position is near the zone (Rf·(1 + margin)), so vertices can still move in and out.
  for (const auto& spec : rig_.muscles) {
    Muscle m;
    m.kind = spec.kind;
    m.geometry = {spec.head, spec.tail, spec.omega, spec.rs, spec.rf, spec.k};
    m.axis = spec.kind == facemesh::MuscleKind::Vector ? Eigen::Vector3d((spec.tail - spec.head).normalized()) : Eigen::Vector3d::Zero();
    m.semi_axes = spec.semi_axes;
    m.parameter = parameter_index(spec.parameter);
    m.wrinkle_count = spec.wrinkle_count;
    m.wrinkle_height = spec.wrinkle_height;
    auto near = [&](const Eigen::Vector3d& p) {
      if (spec.kind == facemesh::MuscleKind::Vector) {
        const Eigen::Vector3d b = p - spec.head;
        const double d = b.norm();
        if (d > spec.rf * (1.0 + options_.zone_margin)) return false;
        if (d <= 1e-12) return true;
        const double alpha = std::acos(std::min(1.0, std::max(-1.0, b.dot(m.axis) / d)));
        return alpha <= std::min(kPi, spec.omega * (1.0 + options_.zone_margin));
      }
      const double dx = (p.x() - spec.head.x()) / spec.semi_axes.x(), dy = (p.y() - spec.head.y()) / spec.semi_axes.y();
      return std::sqrt(dx * dx + dy * dy) <= 1.0 + options_.zone_margin;
    };
    for (auto region : spec.regions) {
      for (int v : regions[static_cast<std::size_t>(region)]) {
        if (near(mesh_.vertices.row(v).transpose())) m.vertices.push_back(v);
      }
    }
    std::sort(m.vertices.begin(), m.vertices.end());
    m.vertices.erase(std::unique(m.vertices.begin(), m.vertices.end()), m.vertices.end());
    if (spec.moves_lips) {
      for (std::size_t i = 0; i < cps.size(); ++i) {
        if (near(cps[i])) m.control_points.push_back(static_cast<int>(i));
      }
    }
    muscles_.push_back(std::move(m));
  }
  for (int e = 0; e < 2; ++e) {
    const std::string s = e == 0 ? "_r" : "_l";
    closing_param_[static_cast<std::size_t>(e)] = parameter_index("orbicularis_oculi_palpebralis" + s);
    squeezing_param_[static_cast<std::size_t>(e)] = parameter_index("orbicularis_oculi_orbitalis" + s);
    opening_param_[static_cast<std::size_t>(e)] = parameter_index("levator_palpebrae_superioris" + s);
  }
  funneler_param_ = parameter_index("orbicularis_oris_funneler");
  pressor_param_ = parameter_index("orbicularis_oris_pressor");
  masseter_param_ = parameter_index("masseter");

  // Orbicularis Oris on the lip control points (thesis §2.4.2 after King et al. 2000):
  // funneler p' = o(θ + e(p) + x), pressor p' = o(θ + e(p)) with θ = 20° in opposite senses.
  // Per control point we precompute the displacement at o = 1; row weight r/(kAcross−1) keeps the
  // border (row 0, stitched to the skin) in place, |sin t| keeps the corners continuous.
  constexpr int na = facemesh::LipGrid::kAround, nr = facemesh::LipGrid::kAcross;
  funnel_delta_.assign(cps.size(), Eigen::Vector3d::Zero());
  press_delta_.assign(cps.size(), Eigen::Vector3d::Zero());
  lip_jaw_weight_.assign(cps.size(), 0.0);
  const Eigen::Vector3d& centre = rig_.lips.centre;
  // contact line height: mean y of the middle row's corners
  if (cps.empty()) return;  // a face without the lip model
  const double contact_y = 0.5 * (cps[static_cast<std::size_t>((nr - 2) * na)].y() + cps[static_cast<std::size_t>((nr - 2) * na + na / 2)].y());
  // jaw weight of the skin next to each border control point (nearest jaw vertex, else 0)
  std::vector<double> border_jaw(na, 0.0);
  for (int c = 0; c < na; ++c) {
    double best = 1e300;
    for (std::size_t j = 0; j < rig_.jaw.vertices.size(); ++j) {
      const double d = (mesh_.vertices.row(rig_.jaw.vertices[j]).transpose() - cps[static_cast<std::size_t>(c)]).squaredNorm();
      if (d < best) best = d, border_jaw[static_cast<std::size_t>(c)] = rig_.jaw.weights[j];
    }
    if (best > 0.004 * 0.004) border_jaw[static_cast<std::size_t>(c)] = 0.0;
  }
  for (int r = 0; r < nr; ++r) {
    const double wr = static_cast<double>(r) / (nr - 1);
    for (int c = 0; c < na; ++c) {
      const std::size_t i = static_cast<std::size_t>(r * na + c);
      const double t = 2.0 * kPi * c / na;
      const double st = std::sin(t);
      const double side = st >= 0.0 ? 1.0 : -1.0;  // +1 upper lip, −1 lower lip
      const double corner = std::sqrt(std::abs(st));
      const Eigen::Vector3d& p = cps[i];
      const Eigen::Vector3d& root = cps[static_cast<std::size_t>(c)];
      // funneler: lips turn outwards (upper up/forward, lower down/forward), pucker inwards, extrude
      Eigen::Vector3d f = rotate_x(p, root, -side * options_.funnel_rotation * wr * corner) - p;
      f.x() += -0.35 * (p.x() - centre.x()) * wr;
      f.y() += 0.0025 * st * wr;
      f.z() += options_.funnel_extrusion * wr;
      funnel_delta_[i] = f;
      // pressor: lips roll in (opposite rotation), are pressed thin towards the contact line
      Eigen::Vector3d q = rotate_x(p, root, side * options_.press_rotation * wr * corner) - p;
      q.y() += -0.55 * (p.y() - contact_y) * wr;
      q.z() += -0.0015 * wr;
      press_delta_[i] = q;
      // jaw (thesis §2.4.4): lower lip middle rotates fully, corners by one third; upper lip pulled
      // down, zero in the middle, more towards the corners. Border row follows the skin next to it.
      const double thesis = st < 0.0 ? 1.0 / 3.0 + 2.0 / 3.0 * std::abs(st) : (1.0 / 3.0) * (1.0 - st);
      lip_jaw_weight_[i] = (1.0 - wr) * border_jaw[static_cast<std::size_t>(c)] + wr * thesis;
    }
  }
}

void FaceSolver::deform(const std::vector<double>& values, Deformation& out) const {
  validate_parameter_vector(values);
  const long nv = mesh_.vertices.rows();
  out.vertices = mesh_.vertices;
  out.crease.assign(static_cast<std::size_t>(nv), 0);
  out.lip_control_points = rig_.lips.control_points;
  auto& X = out.vertices;
  auto& C = out.lip_control_points;

  // Orbicularis Oculi coupling per eye (thesis §2.4.3).
  std::array<EyelidLevels, 2> lids;
  for (std::size_t e = 0; e < 2; ++e) {
    const double closing = values[closing_param_[e]], squeezing = values[squeezing_param_[e]];
    const double other = values[closing_param_[1 - e]];
    switch (options_.eyelid_coupling) {
      case EyelidCoupling::Thesis: lids[e] = couple_eyelids(closing, squeezing, other); break;
      case EyelidCoupling::OneEye:
        lids[e] = {closing, closing > 0.0 && other <= 0.0 ? std::max(squeezing, 0.5 * closing) : squeezing};
        break;
      case EyelidCoupling::Off: lids[e] = {closing, squeezing}; break;
    }
  }
  std::vector<double> level(muscles_.size());
  double max_level = 0.0;
  for (std::size_t i = 0; i < muscles_.size(); ++i) {
    const std::size_t p = muscles_[i].parameter;
    level[i] = p == squeezing_param_[0] ? lids[0].squeezing : p == squeezing_param_[1] ? lids[1].squeezing : values[p];
    max_level = std::max(max_level, level[i]);
  }
  const double funnel = values[funneler_param_], press = values[pressor_param_];
  max_level = std::max({max_level, funnel, press});

  // Parallel contraction (thesis §2.4.1, seeds/README.md): in steps δc every muscle with contraction
  // left displaces each vertex at its *current* position; displacements are summed, then applied.
  const double dc = options_.delta_c;
  const int steps = max_level <= 0.0 ? 0 : options_.parallel ? static_cast<int>(std::ceil(max_level / dc - 1e-9)) : 1;
  out.steps = steps;
  std::vector<Eigen::Vector3d> disp(static_cast<std::size_t>(nv), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> disp_c(C.size(), Eigen::Vector3d::Zero());
  std::vector<int> touched;
  std::vector<std::uint8_t> mark(static_cast<std::size_t>(nv), 0);
  for (int s = 0; s < steps; ++s) {
    const double done = s * dc;
    auto amount = [&](double lvl) { return options_.parallel ? std::min(dc, lvl - done) : lvl; };
    touched.clear();
    for (std::size_t i = 0; i < muscles_.size(); ++i) {
      const double c = amount(level[i]);
      if (c <= 0.0) continue;
      const Muscle& m = muscles_[i];
      if (m.kind == facemesh::MuscleKind::Vector) {
        const VectorMuscle& g = m.geometry;
        const double rf2 = g.rf * g.rf, cos_omega = std::cos(g.omega);
        const double angle_scale = kHalfPi / g.omega, inv_rs = 1.0 / g.rs, inv_span = 1.0 / (g.rf - g.rs);
        const double hx = g.head.x(), hy = g.head.y(), hz = g.head.z();
        const double ax = m.axis.x(), ay = m.axis.y(), az = m.axis.z();
        const double ck = c * g.k;
        auto displace = [&](const double* p, Eigen::Vector3d& acc) {
          const double tx = hx - p[0], ty = hy - p[1], tz = hz - p[2];  // v1 − p
          const double d2 = tx * tx + ty * ty + tz * tz;
          if (d2 > rf2 || d2 <= 0.0) return false;
          const double inv_d = 1.0 / std::sqrt(d2);
          const double cos_alpha = -(tx * ax + ty * ay + tz * az) * inv_d;
          if (cos_alpha <= cos_omega) return false;
          const double d = d2 * inv_d;
          // A = cos((α/Ω)·π/2), R = Waters radial fall-off; arguments stay in [0, π/2] so the
          // polynomial cos/acos of fast_math.hpp apply (error < 2e-8)
          const double a = detail::cos_quadrant(detail::acos_fast(std::min(1.0, cos_alpha)) * angle_scale);
          const double r = d <= g.rs ? detail::cos_quadrant((1.0 - d * inv_rs) * kHalfPi)
                                     : detail::cos_quadrant((d - g.rs) * inv_span * kHalfPi);
          const double f = ck * a * r * inv_d;  // c·k·A·R·(v1 − p)/|v1 − p|
          acc.x() += f * tx;
          acc.y() += f * ty;
          acc.z() += f * tz;
          return true;
        };
        for (int v : m.vertices) {
          if (displace(X.data() + 3 * static_cast<long>(v), disp[static_cast<std::size_t>(v)]) && !mark[static_cast<std::size_t>(v)]) {
            mark[static_cast<std::size_t>(v)] = 1;
            touched.push_back(v);
          }
        }
        for (int cp : m.control_points) displace(C[static_cast<std::size_t>(cp)].data(), disp_c[static_cast<std::size_t>(cp)]);
      } else {
        // Waters sphincter (waters.hpp), sin(π·e) = cos(|π·e − π/2|) through the polynomial cos
        const Eigen::Vector3d& centre = m.geometry.head;
        const double ia = 1.0 / m.semi_axes.x(), ib = 1.0 / m.semi_axes.y(), ck = c * m.geometry.k;
        auto squeeze = [&](const Eigen::Vector3d& p, Eigen::Vector3d& acc) {
          const double dx = p.x() - centre.x(), dy = p.y() - centre.y();
          const double e2 = dx * dx * ia * ia + dy * dy * ib * ib;
          const double r2 = dx * dx + dy * dy;
          if (e2 >= 1.0 || r2 <= 0.0) return false;
          const double s = ck * detail::cos_quadrant(std::abs(kPi * std::sqrt(e2) - kHalfPi)) / std::sqrt(r2);
          acc.x() -= s * dx;
          acc.y() -= s * dy;
          return true;
        };
        for (int v : m.vertices) {
          if (squeeze(X.row(v).transpose(), disp[static_cast<std::size_t>(v)]) && !mark[static_cast<std::size_t>(v)]) {
            mark[static_cast<std::size_t>(v)] = 1;
            touched.push_back(v);
          }
        }
        for (int cp : m.control_points) squeeze(C[static_cast<std::size_t>(cp)], disp_c[static_cast<std::size_t>(cp)]);
      }
    }
    const double f = amount(funnel), p = amount(press);
    for (std::size_t i = 0; i < C.size(); ++i) {
      if (f > 0.0) disp_c[i] += f * funnel_delta_[i];
      if (p > 0.0) disp_c[i] += p * press_delta_[i];
      C[i] += disp_c[i];
      disp_c[i].setZero();
    }
    for (int v : touched) {
      X.row(v) += disp[static_cast<std::size_t>(v)].transpose();
      disp[static_cast<std::size_t>(v)].setZero();
      mark[static_cast<std::size_t>(v)] = 0;
    }
  }

  // Eyelids (thesis §2.4.3, after Parke 1974): rotation of the lid about the eye's horizontal axis,
  // weighted from the lid margin outwards; closing lowers the upper lid, the levator raises it.
  for (std::size_t e = 0; e < 2; ++e) {
    const auto& eye = rig_.eyes[e];
    const double upper = std::pow(lids[e].closing, options_.lid_closing_exponent) * eye.close_angle -
                         values[opening_param_[e]] * eye.open_angle;
    const double lower = -0.2 * lids[e].closing * eye.close_angle;
    if (upper != 0.0) {
      for (std::size_t k = 0; k < eye.upper_lid.size(); ++k) {
        const int v = eye.upper_lid[k];
        X.row(v) = rotate_x(X.row(v).transpose(), eye.centre, upper * eye.upper_lid_weights[k]).transpose();
      }
    }
    if (lower != 0.0) {
      for (std::size_t k = 0; k < eye.lower_lid.size(); ++k) {
        const int v = eye.lower_lid[k];
        X.row(v) = rotate_x(X.row(v).transpose(), eye.centre, lower * eye.lower_lid_weights[k]).transpose();
      }
    }
  }

  // Jaw rotation about the pivot axis (thesis §2.4.4).
  const double jaw = values[masseter_param_] * rig_.jaw.max_angle;
  if (jaw != 0.0) {
    for (std::size_t k = 0; k < rig_.jaw.vertices.size(); ++k) {
      const int v = rig_.jaw.vertices[k];
      X.row(v) = rotate_x(X.row(v).transpose(), rig_.jaw.pivot, jaw * rig_.jaw.weights[k]).transpose();
    }
    for (std::size_t i = 0; i < C.size(); ++i) C[i] = rotate_x(C[i], rig_.jaw.pivot, jaw * lip_jaw_weight_[i]);
  }

  // Lips: re-polygonise the B-spline on its fixed sampling grid (thesis §2.3.2).
  if (!C.empty()) lip_sampler_.evaluate(C, X, rig_.lips.first_vertex);

  // Bulges and wrinkles (thesis §2.4.1): amplitude from the vertex's original position in the band,
  // largest amplitude where muscles overlap, applied along the normal after displacement; wrinkle feet
  // are flagged so renderers use the face normal there ("unrepresentative vertex normal").
  if (options_.wrinkles) {
    std::vector<double> amp;
    for (std::size_t i = 0; i < muscles_.size(); ++i) {
      const Muscle& m = muscles_[i];
      if (m.kind != facemesh::MuscleKind::Vector || m.wrinkle_count <= 0 || m.wrinkle_height <= 0.0 || level[i] <= 0.0) continue;
      if (amp.empty()) amp.assign(static_cast<std::size_t>(nv), 0.0);
      const double length = wrinkle_band_length(m.geometry);
      if (!(length > 0.0)) continue;
      const double b = length / (2.0 * m.wrinkle_count);
      for (int v : m.vertices) {
        const Eigen::Vector3d p0 = mesh_.vertices.row(v).transpose();
        const double l = wrinkle_coordinate(m.geometry, p0);
        if (l < 0.0 || l > length) continue;
        const Eigen::Vector3d to_p = p0 - m.geometry.head;
        const double d = to_p.norm();
        if (d <= 0.0 || d > m.geometry.rf) continue;
        const double cos_alpha = std::min(1.0, std::max(-1.0, to_p.dot(m.axis) / d));
        if (cos_alpha <= std::cos(m.geometry.omega)) continue;
        const double a = detail::cos_quadrant(detail::acos_fast(cos_alpha) / m.geometry.omega * kHalfPi);
        const double h = level[i] * a * wrinkle_function(l, length, m.wrinkle_count, m.wrinkle_height);
        auto& slot = amp[static_cast<std::size_t>(v)];
        if (h > slot) slot = h;
        const double u = l - 2.0 * b * std::floor(l / (2.0 * b));
        if ((u < 0.15 * b || u > 1.85 * b) && l > b && l < length - b) out.crease[static_cast<std::size_t>(v)] = 1;
      }
    }
    if (!amp.empty()) {
      // area-weighted vertex normals of the displaced mesh, only where there is a wrinkle
      std::vector<Eigen::Vector3d> normal;
      std::vector<int> lifted;
      for (long v = 0; v < nv; ++v) {
        if (amp[static_cast<std::size_t>(v)] <= 0.0) continue;
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        for (int k = vertex_face_start_[static_cast<std::size_t>(v)]; k < vertex_face_start_[static_cast<std::size_t>(v) + 1]; ++k) {
          const int f = vertex_faces_[static_cast<std::size_t>(k)];
          const Eigen::Vector3d a = X.row(mesh_.faces(f, 0)).transpose();
          n += (Eigen::Vector3d(X.row(mesh_.faces(f, 1)).transpose()) - a).cross(Eigen::Vector3d(X.row(mesh_.faces(f, 2)).transpose()) - a);
        }
        const double len = n.norm();
        if (len > 0.0) {
          normal.push_back(n / len);
          lifted.push_back(static_cast<int>(v));
        }
      }
      for (std::size_t i = 0; i < lifted.size(); ++i) {
        X.row(lifted[i]) += amp[static_cast<std::size_t>(lifted[i])] * normal[i].transpose();
      }
    }
  }

  // Eyeballs (thesis §2.4.5): rotate about the eye centre, limited by the elliptical eye hole.
  const double gaze_yaw = values[kSideParameterCount + 0], gaze_pitch = values[kSideParameterCount + 1];
  if (gaze_yaw != 0.0 || gaze_pitch != 0.0) {
    for (const auto& eye : rig_.eyes) {
      const Eigen::Vector2d g = limit_gaze(gaze_yaw, gaze_pitch, eye.yaw_limit, eye.pitch_limit);
      const Eigen::Matrix3d r = (Eigen::AngleAxisd(g.x(), Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(-g.y(), Eigen::Vector3d::UnitX())).toRotationMatrix();
      for (int v : eye.eyeball_vertices) X.row(v) = (eye.centre + r * (X.row(v).transpose() - eye.centre)).transpose();
    }
  }
  // Head pose: rigid rotation about the head pivot.
  const double hy = values[kSideParameterCount + 2], hp = values[kSideParameterCount + 3], hr = values[kSideParameterCount + 4];
  if (hy != 0.0 || hp != 0.0 || hr != 0.0) {
    const Eigen::Matrix3d r = (Eigen::AngleAxisd(hy, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(-hp, Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(hr, Eigen::Vector3d::UnitZ())).toRotationMatrix();
    const Eigen::Vector3d c = rig_.head_pivot;
    for (long v = 0; v < nv; ++v) X.row(v) = (c + r * (X.row(v).transpose() - c)).transpose();
  }
  if (!X.allFinite()) throw NumericalError("FaceSolver: deformation produced a non-finite vertex");
}

Deformation FaceSolver::deform(const std::vector<double>& values) const {
  Deformation out;
  deform(values, out);
  return out;
}

Deformation FaceSolver::deform(const std::map<std::string, double>& named) const {
  return deform(to_parameter_vector(named));
}

Deformation deform_face(const facemesh::Mesh& mesh, const facemesh::Rig& rig, const std::map<std::string, double>& named,
                        const SolverOptions& options) {
  return FaceSolver(mesh, rig, options).deform(named);
}

}  // namespace emoface::muscles
