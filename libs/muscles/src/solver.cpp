// The muscle-driven face (thesis §2.4).
#include "emoface/muscles/solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

// Per vertex: the mean length of the edges it shares with its triangles (an interior edge counts
// once per triangle); 0 for a vertex in no triangle. The mesh resolution for wrinkle_foot().
std::vector<double> mean_edge_lengths(const facemesh::Mesh& mesh) {
  const auto nv = static_cast<std::size_t>(mesh.vertices.rows());
  std::vector<double> sum(nv, 0.0);
  std::vector<int> count(nv, 0);
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
      const double l = (mesh.vertices.row(a) - mesh.vertices.row(b)).norm();
      for (int v : {a, b}) {
        sum[static_cast<std::size_t>(v)] += l;
        ++count[static_cast<std::size_t>(v)];
      }
    }
  for (std::size_t v = 0; v < nv; ++v)
    if (count[v] > 0) sum[v] /= count[v];
  return sum;
}

// The thesis' region cut-off (§2.3, §2.4.1: a muscle moves only the vertices of its regions of
// influence) carried to the lip surface: the upper lip's control points count as the middle face
// (the regions meet at the lips' contact line), the lower lip's as the lower face, the corners'
// (the columns within 15° of the mouth's horizontal axis) as both. A lip-moving muscle moves a
// control point (index `column`, any row: taken modulo kAround) only when its regions include that
// part of the face; one with no face region at all moves every control point, as before. Without it
// the upper-lip raisers (levator labii superioris, levator labii superioris alaeque nasi: middle
// and upper face) lifted the lower lip as well (issue 14, session 8).
bool reaches_lip_column(const facemesh::MuscleSpec& spec, int column) {
  using R = facemesh::Region;
  bool upper = false, lower = false;
  for (R r : spec.regions) {
    upper |= r == R::RightMiddleFace || r == R::LeftMiddleFace || r == R::RightUpperFace ||
             r == R::LeftUpperFace;
    lower |= r == R::RightLowerFace || r == R::LeftLowerFace;
  }
  if (!upper && !lower) return true;
  const int around = facemesh::LipGrid::kAround, c = ((column % around) + around) % around;
  // the corners and the columns next to them (within 15°), so that the control net does not step
  // between neighbours where the corner muscles pull hardest
  if (c <= 1 || c >= around - 1 || std::abs(2 * c - around) <= 2) return true;
  return 2 * c < around ? upper : lower;  // columns 2 .. kAround/2−2: the upper lip
}

}  // namespace

// FaceSolver's state and hot path (see solver.hpp: FaceSolver::Impl).
struct FaceSolver::Impl {
  Impl(facemesh::Mesh mesh, facemesh::Rig rig, SolverOptions options);
  void deform(const std::vector<double>& values, Deformation& out,
              DeformWorkspace& workspace) const;
  void deform_reference(const std::vector<double>& values, Deformation& out) const;

  struct Muscle {
    facemesh::MuscleKind kind;
    VectorMuscle geometry;
    Eigen::Vector3d axis;  // unit v1->v2
    Eigen::Vector2d semi_axes;
    std::size_t parameter;
    std::vector<int> vertices;        // candidates (region cut-off ∩ reachable zone), ascending
    std::vector<int> control_points;  // lip control points it may move
    int wrinkle_count;
    double wrinkle_height;
  };
  // Hot-loop form of one muscle (solver.cpp, build_fast_path): constants and the fitted polynomial
  // factors of fast_math.hpp ({centre, 1/half-width, c0..cN} each, within detail::kFitTolerance).
  static constexpr int kAngularDegree = 7;  // A(cos α)
  static constexpr int kRadialDegree =
      6;  // cos(π/2·√s), s = u², R = cos(π/2·u) (see fast_math.hpp)
  static constexpr int kSphincterDegree = 9;  // sin(π·e) on [0, 1]
  struct MusclePlan {
    bool sphincter;
    bool exact;         // a fit missed detail::kFitTolerance: use the exact <cmath> factors
    double hx, hy, hz;  // v1 (vector) or centre (sphincter), m
    double ax, ay, az;  // unit axis v1->v2
    double rf2, cos_omega, rs, rf, omega, k;
    double inv_a2, inv_b2;                           // sphincter: 1/semi-axis²
    double inv_rs, inv_span;                         // 1/Rs, 1/(Rf − Rs)
    std::array<double, kAngularDegree + 3> angular;  // packed A(cos α)
    std::array<double, kRadialDegree + 3> radial;    // packed cos(π/2·√s) on s ∈ [0, 1]
    std::array<double, kSphincterDegree + 3> sphincter_falloff;
    // the vector-muscle constants and both packed polynomials, each value twice (one per SSE2 lane)
    alignas(16) std::array<double, 2 * (13 + kAngularDegree + 3 + kRadialDegree + 3)> lanes;
  };
  // Per point (vertex or lip control point) candidate muscles, built once; deform() runs on their
  // muscle-major copy muscle_slots_. A point's displacement depends only on its own position.
  struct CandidateLists {
    std::vector<int> point;   // vertex (or control point) ids, ascending
    std::vector<int> start;   // CSR offsets into muscle, size point.size() + 1
    std::vector<int> muscle;  // muscle indices, per point sorted by reach2 (ties: muscle order)
    // per entry: squared distance from the neutral position to the muscle's zone (less a 1e-9 m
    // slack); the muscle cannot act on the point before it has moved that far from its neutral
    // position
    std::vector<double> reach2;
  };
  // Muscle-major copy of vertex_lists_ and control_point_lists_ for the two-lane (SSE2) pass: per
  // muscle the slots (vertex_lists_.point indices, then nv + control point) and the entries'
  // reach2, ascending, padded to an even length with a dummy slot (the last slot, reach2 = +inf).
  struct MuscleSlots {
    std::vector<int> slot;
    std::vector<double> reach2;
  };
  std::vector<MuscleSlots> muscle_slots_;
  std::vector<double> slot_neutral_;  // neutral positions of the slots, SoA (x | y | z), dummy = 0
  // Wrinkles depend only on the neutral positions: per muscle, (compact vertex, amplitude at level
  // 1).
  struct WrinkleEntry {
    int slot;       // index into wrinkle_vertices_
    double height;  // A·f(l) at full contraction, m
    bool crease;
  };
  void build_fast_path();
  static double zone_distance(const Muscle& m, const Eigen::Vector3d& p);
  // Shared by deform() and deform_reference(): validation, eyelid coupling, muscle levels, steps.
  int prepare(const std::vector<double>& values, Deformation& out,
              std::array<EyelidLevels, 2>& lids, std::vector<double>& level) const;
  // Eyelids, jaw and lip re-sampling (after the contraction), then eyeballs and head pose (last).
  void apply_lids_jaw_lips(const std::vector<double>& values,
                           const std::array<EyelidLevels, 2>& lids, Deformation& out) const;
  void apply_gaze_and_pose(const std::vector<double>& values, Deformation& out) const;
  facemesh::Mesh mesh_;
  facemesh::Rig rig_;
  SolverOptions options_;
  std::vector<Muscle> muscles_;
  std::vector<MusclePlan> muscle_plans_;
  CandidateLists vertex_lists_, control_point_lists_;
  std::vector<std::vector<WrinkleEntry>> wrinkles_;  // per muscle
  std::vector<int> wrinkle_vertices_;                // ascending
  facemesh::LipSampler lip_sampler_;
  std::vector<int> bound_start_;                         // rig_.lips.bound -> bound_terms_ (CSR)
  std::vector<facemesh::LipSampler::Term> bound_terms_;  // ≤ 16 basis terms of S(u, v) per binding
  std::vector<Eigen::Vector3d> funnel_delta_,
      press_delta_;                                    // per control point, per unit contraction
  std::vector<double> lip_jaw_weight_;                 // per control point
  std::vector<int> vertex_face_start_, vertex_faces_;  // vertex -> incident faces (CSR)
  std::array<std::size_t, 2> closing_param_{}, squeezing_param_{}, opening_param_{}, blink_param_{};
  std::size_t funneler_param_ = 0, pressor_param_ = 0, masseter_param_ = 0;
};

// Distance from p to a muscle's zone of influence (0 inside): the vector muscle's zone is the cone
// of half-angle Ω about the axis at v1 capped at Rf (a 2-D sector in axial/radial coordinates); for
// the sphincter (x/y only) min(semi-axes)·(e − 1), e the elliptic radius, is a lower bound (enough
// here).
double FaceSolver::Impl::zone_distance(const Muscle& m, const Eigen::Vector3d& p) {
  if (m.kind != facemesh::MuscleKind::Vector) {
    const double dx = (p.x() - m.geometry.head.x()) / m.semi_axes.x(), dy = (p.y() - m.geometry.head.y()) / m.semi_axes.y();
    const double e = std::sqrt(dx * dx + dy * dy);
    return e <= 1.0 ? 0.0 : (e - 1.0) * std::min(m.semi_axes.x(), m.semi_axes.y());
  }
  const Eigen::Vector3d b = p - m.geometry.head;
  const double along = b.dot(m.axis);
  const double across = (b - along * m.axis).norm();
  const double d = b.norm();
  const double omega = m.geometry.omega;
  if (std::atan2(across, along) <= omega) return std::max(0.0, d - m.geometry.rf);
  // outside the cone: nearest point of the boundary ray segment (length Rf) at angle Ω
  const double t = std::min(m.geometry.rf, std::max(0.0, along * std::cos(omega) + across * std::sin(omega)));
  return std::hypot(along - t * std::cos(omega), across - t * std::sin(omega));
}

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
  check(lid_tighten_upper >= 0.0 && lid_tighten_upper <= 0.6,
        "lid_tighten_upper must be in [0, 0.6]");
  check(lid_tighten_lower >= 0.0 && lid_tighten_lower <= 0.6,
        "lid_tighten_lower must be in [0, 0.6]");
  check(lid_cheek_raise >= 0.0 && lid_cheek_raise <= 0.6, "lid_cheek_raise must be in [0, 0.6]");
  check(lid_tighten_upper + lid_tighten_lower <= 0.8,
        "lid_tighten_upper + lid_tighten_lower must be <= 0.8 (the tightener never shuts the eye)");
  check(funnel_extrusion >= 0.0 && funnel_extrusion <= 0.05, "funnel_extrusion must be in [0, 0.05]");
  check(crease_resolution >= 0.0 && crease_resolution <= 1e6,
        "crease_resolution must be in [0, 1e6]");
}

FaceSolver::Impl::Impl(facemesh::Mesh mesh, facemesh::Rig rig, SolverOptions options)
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
  const auto& cps = rig_.lips.control_points;
  // Lip bindings: per bound vertex the ≤ 16 (control point, weight) terms of S(u, v) (CSR).
  bound_start_.assign(1, 0);
  bound_terms_.clear();
  for (const auto& b : rig_.lips.bound) {
    for (const auto& t : facemesh::lip_surface_terms(b.u, b.v)) bound_terms_.push_back(t);
    bound_start_.push_back(static_cast<int>(bound_terms_.size()));
  }
  for (const auto& spec : rig_.muscles) {
    Muscle m;
    m.kind = spec.kind;
    m.geometry = {spec.head, spec.tail, spec.omega, spec.rs, spec.rf, spec.k};
    m.axis = spec.kind == facemesh::MuscleKind::Vector ? Eigen::Vector3d((spec.tail - spec.head).normalized()) : Eigen::Vector3d::Zero();
    m.semi_axes = spec.semi_axes;
    m.parameter = parameter_index(spec.parameter);
    if (m.parameter >= kSideParameterCount) {
      throw InvalidInput("FaceSolver: muscle '" + spec.name + "' is driven by '" + spec.parameter +
                         "', which is not a contraction parameter");
    }
    m.wrinkle_count = spec.wrinkle_count;
    m.wrinkle_height = spec.wrinkle_height;
    muscles_.push_back(std::move(m));
  }
  for (int e = 0; e < 2; ++e) {
    const std::string s = e == 0 ? "_r" : "_l";
    closing_param_[static_cast<std::size_t>(e)] = parameter_index("orbicularis_oculi_palpebralis" + s);
    squeezing_param_[static_cast<std::size_t>(e)] = parameter_index("orbicularis_oculi_orbitalis" + s);
    opening_param_[static_cast<std::size_t>(e)] = parameter_index("levator_palpebrae_superioris" + s);
    blink_param_[static_cast<std::size_t>(e)] = parameter_index("eye_blink" + s);
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
  if (cps.empty()) {  // a face without the lip model
    build_fast_path();
    return;
  }
  const double contact_y = 0.5 * (cps[static_cast<std::size_t>((nr - 2) * na)].y() + cps[static_cast<std::size_t>((nr - 2) * na + na / 2)].y());
  // jaw weight of the skin next to each border control point: the rig's own (a transferred rig),
  // else the nearest jaw vertex's
  const std::vector<double> border_jaw =
      rig_.lips.border_jaw.empty() ? lip_border_jaw_weights(mesh_, rig_) : rig_.lips.border_jaw;
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
  build_fast_path();
}

std::vector<double> lip_border_jaw_weights(const facemesh::Mesh& mesh, const facemesh::Rig& rig) {
  const auto& cps = rig.lips.control_points;
  if (cps.empty()) return {};
  constexpr int na = facemesh::LipGrid::kAround;
  if (cps.size() < static_cast<std::size_t>(na))
    throw InvalidInput("lip_border_jaw_weights: the rig's lip grid is incomplete");
  std::vector<double> out(na, 0.0);
  for (int c = 0; c < na; ++c) {
    double best = 1e300;
    for (std::size_t j = 0; j < rig.jaw.vertices.size(); ++j) {
      const int v = rig.jaw.vertices[j];
      if (v < 0 || v >= mesh.vertices.rows() || j >= rig.jaw.weights.size())
        throw InvalidInput("lip_border_jaw_weights: jaw vertex or weight out of range");
      const double d =
          (mesh.vertices.row(v).transpose() - cps[static_cast<std::size_t>(c)]).squaredNorm();
      if (d < best) best = d, out[static_cast<std::size_t>(c)] = rig.jaw.weights[j];
    }
    if (best > 0.004 * 0.004) out[static_cast<std::size_t>(c)] = 0.0;
  }
  return out;
}

void FaceSolver::Impl::build_fast_path() {
  // Region cut-off (thesis §2.4.1, performance): a muscle visits only vertices of its regions, and of
  // those only the ones that can ever enter its zone of influence. A muscle moves a point by at most
  // its k over the whole deformation (|c·k·A·R| <= δ·k per step, Σδ <= 1; sphincter likewise), so a
  // point whose muscles (those it can reach) sum to K never gets further than K (+ the lip funneler
  // and pressor motion for control points) from its neutral position. Per point, the smallest set S
  // of its region's muscles that contains every muscle whose zone lies within Σ_S k of the neutral
  // position is a proof that no other muscle can ever move it: the first step in which another
  // muscle moved it would find it within Σ_S k of its start and inside that muscle's zone. S is found
  // by walking the muscles by increasing distance. Membership itself is re-tested exactly every step.
  const auto regions = facemesh::region_vertices(rig_);
  const auto& lip_cps = rig_.lips.control_points;
  auto select = [&](const Eigen::Vector3d& p, std::vector<std::pair<double, int>>& reach, double extra_motion) {
    std::sort(reach.begin(), reach.end());
    double bound = extra_motion;
    std::size_t n = 0;
    for (; n < reach.size(); ++n) {
      const Muscle& m = muscles_[static_cast<std::size_t>(reach[n].second)];
      // slack: polynomial factors may exceed 1 by ~1e-9; rounding of the distances
      if (reach[n].first > bound * (1.0 + 1e-6) + 1e-9 + options_.zone_margin * m.geometry.rf) break;
      bound += m.geometry.k;
    }
    (void)p;
    reach.resize(n);
  };
  std::vector<std::pair<double, int>> reach;
  for (auto& m : muscles_) m.vertices.clear(), m.control_points.clear();
  std::vector<std::vector<int>> reached_by(mesh_.vertex_count());
  for (std::size_t i = 0; i < muscles_.size(); ++i) {
    for (auto region : rig_.muscles[i].regions) {
      for (int v : regions[static_cast<std::size_t>(region)]) {
        auto& list = reached_by[static_cast<std::size_t>(v)];
        if (list.empty() || list.back() != static_cast<int>(i)) list.push_back(static_cast<int>(i));
      }
    }
  }
  for (std::size_t v = 0; v < reached_by.size(); ++v) {
    if (reached_by[v].empty()) continue;
    const Eigen::Vector3d p = mesh_.vertices.row(static_cast<long>(v)).transpose();
    reach.clear();
    for (int i : reached_by[v]) reach.push_back({zone_distance(muscles_[static_cast<std::size_t>(i)], p), i});
    select(p, reach, 0.0);
    for (const auto& r : reach) muscles_[static_cast<std::size_t>(r.second)].vertices.push_back(static_cast<int>(v));
  }
  for (std::size_t c = 0; c < lip_cps.size(); ++c) {
    reach.clear();
    for (std::size_t i = 0; i < muscles_.size(); ++i) {
      if (rig_.muscles[i].moves_lips && reaches_lip_column(rig_.muscles[i], static_cast<int>(c)))
        reach.push_back({zone_distance(muscles_[i], lip_cps[c]), static_cast<int>(i)});
    }
    const double lips = funnel_delta_.empty() ? 0.0 : funnel_delta_[c].norm() + press_delta_[c].norm();
    select(lip_cps[c], reach, lips);
    for (const auto& r : reach) muscles_[static_cast<std::size_t>(r.second)].control_points.push_back(static_cast<int>(c));
  }

  // Hot-loop plans (fast_math.hpp): per muscle its constants and the polynomial Waters factors.
  muscle_plans_.clear();
  for (const Muscle& m : muscles_) {
    MusclePlan q{};
    const VectorMuscle& g = m.geometry;
    q.sphincter = m.kind != facemesh::MuscleKind::Vector;
    q.hx = g.head.x(), q.hy = g.head.y(), q.hz = g.head.z();
    q.ax = m.axis.x(), q.ay = m.axis.y(), q.az = m.axis.z();
    q.rf2 = g.rf * g.rf, q.cos_omega = std::cos(g.omega), q.rs = g.rs, q.rf = g.rf, q.omega = g.omega, q.k = g.k;
    double worst = 0.0;
    if (q.sphincter) {
      q.inv_a2 = 1.0 / (m.semi_axes.x() * m.semi_axes.x());
      q.inv_b2 = 1.0 / (m.semi_axes.y() * m.semi_axes.y());
      auto s = [](double e) { return std::sin(kPi * e); };  // Waters sphincter fall-off (waters.hpp)
      const auto ps = detail::fit_chebyshev<kSphincterDegree>(s, 0.0, 1.0);
      worst = detail::max_fit_error(ps, s, 0.0, 1.0);
      q.sphincter_falloff = detail::pack(ps);
    } else {
      // A(cos α) on [cos Ω, 1]; R(D) on [0, Rs] and [Rs, Rf] (thesis §2.2.3, seeds/README.md)
      const double omega = g.omega, rs = g.rs, rf = g.rf;
      auto a = [omega](double x) { return detail::angular_of_cos(x, omega); };
      auto inner = [rs](double d) { return std::cos((1.0 - d / rs) * kHalfPi); };
      auto outer = [rs, rf](double d) { return std::cos((d - rs) / (rf - rs) * kHalfPi); };
      const auto pa = detail::fit_chebyshev<kAngularDegree>(a, q.cos_omega, 1.0);
      const auto pr = detail::fit_chebyshev<kRadialDegree>(detail::radial_of_square, 0.0, 1.0);
      // R as fitted, on the distances it is used at (both pieces), against the formula itself
      auto fitted_r = [&](double d) {
        const double u = std::abs(d - rs) * (d <= rs ? 1.0 / rs : 1.0 / (rf - rs));
        return pr(u * u);
      };
      worst = std::max(detail::max_fit_error(pa, a, q.cos_omega, 1.0), detail::max_fit_error(pr, detail::radial_of_square, 0.0, 1.0));
      for (int i = 0; i <= 4000; ++i) {
        const double d = rf * i / 4000.0;
        worst = std::max(worst, std::abs(fitted_r(d) - (d <= rs ? inner(d) : outer(d))));
      }
      q.angular = detail::pack(pa);
      q.radial = detail::pack(pr);
      q.inv_rs = 1.0 / rs;
      q.inv_span = 1.0 / (rf - rs);
    }
    q.exact = !(worst <= detail::kFitTolerance);
    const double constants[13] = {q.hx, q.hy, q.hz, q.ax, q.ay, q.az, q.rf2, q.cos_omega, q.rs, q.inv_rs, q.inv_span, 1.0, -0.0};
    std::size_t at = 0;
    auto put = [&](double x) { q.lanes[at++] = x, q.lanes[at++] = x; };
    for (double c : constants) put(c);
    for (double c : q.angular) put(c);
    for (double c : q.radial) put(c);
    muscle_plans_.push_back(q);
  }

  // Per-point candidate lists. The lip samples are skipped: LipSampler::evaluate overwrites them
  // from the control points after the contraction (and the jaw), so moving them would be dead work;
  // so are vertices bound to the lip surface with weight 1 (apply_lids_jaw_lips overwrites them).
  const std::size_t nv = mesh_.vertex_count();
  const auto& cps = rig_.lips.control_points;
  const long lip_begin = cps.empty() || !rig_.lips.samples_in_mesh ? 0 : rig_.lips.first_vertex;
  const long lip_end = cps.empty() || !rig_.lips.samples_in_mesh ? 0 : lip_begin + lip_sampler_.sample_count();
  std::vector<char> overwritten(nv, 0);
  for (long v = lip_begin; v < lip_end; ++v) overwritten[static_cast<std::size_t>(v)] = 1;
  for (const auto& b : rig_.lips.bound) {
    if (b.weight == 1.0) overwritten[static_cast<std::size_t>(b.vertex)] = 1;
  }
  auto build = [&](std::size_t points, auto&& ids_of, auto&& neutral, bool skip_lips, CandidateLists& lists, bool keep_empty) {
    std::vector<std::vector<int>> per(points);
    for (std::size_t i = 0; i < muscles_.size(); ++i) {
      for (int v : ids_of(muscles_[i])) {
        if (skip_lips && overwritten[static_cast<std::size_t>(v)]) continue;
        per[static_cast<std::size_t>(v)].push_back(static_cast<int>(i));
      }
    }
    lists = {};
    lists.start.push_back(0);
    for (std::size_t v = 0; v < points; ++v) {
      if (per[v].empty() && !keep_empty) continue;
      lists.point.push_back(static_cast<int>(v));
      std::vector<std::pair<double, int>> entries;
      for (int i : per[v]) {
        const double dist = std::max(0.0, zone_distance(muscles_[static_cast<std::size_t>(i)], neutral(v)) - 1e-9);
        entries.push_back({dist * dist, i});
      }
      std::sort(entries.begin(), entries.end());  // nearest zones first (ties: muscle order)
      for (const auto& [r2, i] : entries) {
        lists.muscle.push_back(i);
        lists.reach2.push_back(r2);
      }
      lists.start.push_back(static_cast<int>(lists.muscle.size()));
    }
  };
  build(nv, [](const Muscle& m) -> const std::vector<int>& { return m.vertices; },
        [&](std::size_t v) -> Eigen::Vector3d { return mesh_.vertices.row(static_cast<long>(v)).transpose(); }, true, vertex_lists_, false);
  build(cps.size(), [](const Muscle& m) -> const std::vector<int>& { return m.control_points; },
        [&](std::size_t c) -> Eigen::Vector3d { return cps[c]; }, false, control_point_lists_, true);

  // Muscle-major view (two-lane pass): slots [0, nv) are the candidate vertices, then the lip control
  // points, then one dummy slot that pads odd lists; ascending slots keep the reads local.
  muscle_slots_.assign(muscles_.size(), {});
  std::size_t offset = 0;
  for (const CandidateLists* lists : {&vertex_lists_, &control_point_lists_}) {
    for (std::size_t j = 0; j < lists->point.size(); ++j) {
      for (int e = lists->start[j]; e < lists->start[j + 1]; ++e) {
        auto& m = muscle_slots_[static_cast<std::size_t>(lists->muscle[static_cast<std::size_t>(e)])];
        m.slot.push_back(static_cast<int>(offset + j));
        m.reach2.push_back(lists->reach2[static_cast<std::size_t>(e)]);
      }
    }
    offset += lists->point.size();
  }
  const std::size_t slots = offset + 1;
  slot_neutral_.assign(3 * slots, 0.0);
  for (std::size_t j = 0; j < offset; ++j) {
    const Eigen::Vector3d p = j < vertex_lists_.point.size() ? Eigen::Vector3d(mesh_.vertices.row(vertex_lists_.point[j]).transpose())
                                                             : cps[j - vertex_lists_.point.size()];
    for (int k = 0; k < 3; ++k) slot_neutral_[static_cast<std::size_t>(k) * slots + j] = p[k];
  }
  for (auto& m : muscle_slots_) {
    if (m.slot.size() % 2 != 0) {
      m.slot.push_back(static_cast<int>(offset));
      m.reach2.push_back(std::numeric_limits<double>::infinity());
    }
  }

  // Wrinkles (thesis §2.4.1): the amplitude A·f(l) of a vertex depends only on its original position
  // in the band, so it is tabulated once per muscle (exact cos/acos); deform() scales it by the level.
  wrinkles_.assign(muscles_.size(), {});
  const std::vector<double> edge = mean_edge_lengths(mesh_);
  std::vector<int> slot(nv, -1);
  std::vector<std::vector<std::pair<int, WrinkleEntry>>> raw(muscles_.size());
  for (std::size_t i = 0; i < muscles_.size(); ++i) {
    const Muscle& m = muscles_[i];
    if (m.kind != facemesh::MuscleKind::Vector || m.wrinkle_count <= 0 || m.wrinkle_height <= 0.0) continue;
    const double length = wrinkle_band_length(m.geometry);
    if (!(length > 0.0)) continue;
    for (int v : m.vertices) {
      const Eigen::Vector3d p0 = mesh_.vertices.row(v).transpose();
      const double l = wrinkle_coordinate(m.geometry, p0);
      if (l < 0.0 || l > length) continue;
      const Eigen::Vector3d to_p = p0 - m.geometry.head;
      const double d = to_p.norm();
      if (d <= 0.0 || d > m.geometry.rf) continue;
      const double cos_alpha = std::min(1.0, std::max(-1.0, to_p.dot(m.axis) / d));
      if (cos_alpha <= std::cos(m.geometry.omega)) continue;
      const double a = angular_factor(std::acos(cos_alpha), m.geometry.omega);
      const bool crease =
          wrinkle_foot(l, length, m.wrinkle_count, edge[static_cast<std::size_t>(v)],
                       options_.crease_resolution);
      raw[i].push_back({v, WrinkleEntry{0, a * wrinkle_function(l, length, m.wrinkle_count, m.wrinkle_height), crease}});
      slot[static_cast<std::size_t>(v)] = 0;
    }
  }
  wrinkle_vertices_.clear();
  for (std::size_t v = 0; v < nv; ++v) {
    if (slot[v] < 0) continue;
    slot[v] = static_cast<int>(wrinkle_vertices_.size());
    wrinkle_vertices_.push_back(static_cast<int>(v));
  }
  for (std::size_t i = 0; i < muscles_.size(); ++i) {
    for (auto& [v, e] : raw[i]) {
      e.slot = slot[static_cast<std::size_t>(v)];
      wrinkles_[i].push_back(e);
    }
  }
}

namespace {

// Displacement of a point at (px, py, pz) by one muscle for contraction·elasticity ck, added to
// (dx, dy, dz): Waters vector muscle p' = p + c·k·A·R·(v1 − p)/|v1 − p| (thesis §2.2.3, seeds/README.md)
// or the elliptical sphincter of waters.hpp. Zone membership is tested at the given (current) position.
template <class Plan>
inline void accumulate(const Plan& q, double ck, double px, double py, double pz, double& dx, double& dy, double& dz) {
  if (!q.sphincter) {
    const double tx = q.hx - px, ty = q.hy - py, tz = q.hz - pz;  // v1 − p
    const double d2 = tx * tx + ty * ty + tz * tz;
    if (d2 > q.rf2 || d2 <= 0.0) return;
    const double inv_d = 1.0 / std::sqrt(d2);
    const double cos_alpha = -(tx * q.ax + ty * q.ay + tz * q.az) * inv_d;
    if (cos_alpha <= q.cos_omega) return;
    const double d = d2 * inv_d;
    double ar;
    if (!q.exact) {
      // the same operations, in the same order, as the two-lane pass below
      const double u = std::abs(d - q.rs) * (d <= q.rs ? q.inv_rs : q.inv_span);
      ar = detail::eval_packed(q.angular, std::min(1.0, cos_alpha)) * detail::eval_packed(q.radial, u * u);
    } else {
      ar = detail::angular_of_cos(cos_alpha, q.omega) * radial_factor(d, q.rs, q.rf);
    }
    const double f = ck * ar * inv_d;
    dx += f * tx;
    dy += f * ty;
    dz += f * tz;
  } else {
    const double ex = px - q.hx, ey = py - q.hy;
    const double e2 = ex * ex * q.inv_a2 + ey * ey * q.inv_b2;
    const double r2 = ex * ex + ey * ey;
    if (e2 >= 1.0 || r2 <= 0.0) return;
    const double e = std::sqrt(e2);
    const double s = q.exact ? std::sin(kPi * e) : detail::eval_packed(q.sphincter_falloff, e);
    const double f = ck * s / std::sqrt(r2);
    dx -= f * ex;
    dy -= f * ey;
  }
}

#if defined(EMOFACE_MUSCLES_SSE2)
// The vector-muscle displacement of `accumulate` for two candidate vertices at a time (one per SSE2
// lane; SSE2 is part of x86-64, so no extra target flags). Lanes outside the zone are masked to a
// zero displacement. Operations and their order match the scalar code, so both give the same bits.
template <class Plan>
void vector_muscle_pass(const Plan& q, double ck, const int* slot, const double* reach2, std::size_t n,
                        const double* px, const double* py, const double* pz, const double* moved2, double* dx,
                        double* dy, double* dz) {
  // q.lanes: 13 constants, then the packed A and R polynomials, each as an aligned (x, x) pair
  const __m128d* L = reinterpret_cast<const __m128d*>(q.lanes.data());
  enum { kHx, kHy, kHz, kAx, kAy, kAz, kRf2, kCosOmega, kRs, kInvRs, kInvSpan, kOne, kSign, kAngular };
  constexpr int kA = static_cast<int>(std::tuple_size<decltype(q.angular)>::value);
  constexpr int kR = static_cast<int>(std::tuple_size<decltype(q.radial)>::value);
  constexpr int kRadial = kAngular + kA;
  const __m128d ckv = _mm_set1_pd(ck), zero = _mm_setzero_pd();
  for (std::size_t e = 0; e < n; e += 2) {
    const int a = slot[e], b = slot[e + 1];
    __m128d in = _mm_cmple_pd(_mm_loadu_pd(reach2 + e), _mm_set_pd(moved2[b], moved2[a]));
    if (_mm_movemask_pd(in) == 0) continue;  // both zones still out of reach
    const __m128d tx = _mm_sub_pd(L[kHx], _mm_set_pd(px[b], px[a]));  // v1 − p
    const __m128d ty = _mm_sub_pd(L[kHy], _mm_set_pd(py[b], py[a]));
    const __m128d tz = _mm_sub_pd(L[kHz], _mm_set_pd(pz[b], pz[a]));
    const __m128d d2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(tx, tx), _mm_mul_pd(ty, ty)), _mm_mul_pd(tz, tz));
    in = _mm_and_pd(in, _mm_and_pd(_mm_cmple_pd(d2, L[kRf2]), _mm_cmpgt_pd(d2, zero)));
    if (_mm_movemask_pd(in) == 0) continue;
    const __m128d inv_d = _mm_div_pd(L[kOne], _mm_sqrt_pd(d2));
    const __m128d dot = _mm_add_pd(_mm_add_pd(_mm_mul_pd(tx, L[kAx]), _mm_mul_pd(ty, L[kAy])), _mm_mul_pd(tz, L[kAz]));
    const __m128d cos_alpha = _mm_mul_pd(_mm_xor_pd(dot, L[kSign]), inv_d);
    in = _mm_and_pd(in, _mm_cmpgt_pd(cos_alpha, L[kCosOmega]));
    if (_mm_movemask_pd(in) == 0) continue;
    const __m128d d = _mm_mul_pd(d2, inv_d);
    // A(cos α)
    const __m128d t = _mm_mul_pd(_mm_sub_pd(_mm_min_pd(cos_alpha, L[kOne]), L[kAngular]), L[kAngular + 1]);
    __m128d pa = L[kAngular + kA - 1];
    for (int k = kA - 2; k >= 2; --k) pa = _mm_add_pd(_mm_mul_pd(pa, t), L[kAngular + k]);
    // R = g(u²), u = |D − Rs|·(D <= Rs ? 1/Rs : 1/(Rf − Rs))
    const __m128d inner = _mm_cmple_pd(d, L[kRs]);
    const __m128d w = _mm_or_pd(_mm_and_pd(inner, L[kInvRs]), _mm_andnot_pd(inner, L[kInvSpan]));
    const __m128d u = _mm_mul_pd(_mm_andnot_pd(L[kSign], _mm_sub_pd(d, L[kRs])), w);
    const __m128d tr = _mm_mul_pd(_mm_sub_pd(_mm_mul_pd(u, u), L[kRadial]), L[kRadial + 1]);
    __m128d pr = L[kRadial + kR - 1];
    for (int k = kR - 2; k >= 2; --k) pr = _mm_add_pd(_mm_mul_pd(pr, tr), L[kRadial + k]);
    // c·k·A·R·(v1 − p)/|v1 − p|, zero outside the zone
    const __m128d f = _mm_and_pd(in, _mm_mul_pd(_mm_mul_pd(ckv, _mm_mul_pd(pa, pr)), inv_d));
    const __m128d fx = _mm_mul_pd(f, tx), fy = _mm_mul_pd(f, ty), fz = _mm_mul_pd(f, tz);
    dx[a] += _mm_cvtsd_f64(fx), dx[b] += _mm_cvtsd_f64(_mm_unpackhi_pd(fx, fx));
    dy[a] += _mm_cvtsd_f64(fy), dy[b] += _mm_cvtsd_f64(_mm_unpackhi_pd(fy, fy));
    dz[a] += _mm_cvtsd_f64(fz), dz[b] += _mm_cvtsd_f64(_mm_unpackhi_pd(fz, fz));
  }
}
#endif

}  // namespace

int FaceSolver::Impl::prepare(const std::vector<double>& values, Deformation& out,
                              std::array<EyelidLevels, 2>& lids, std::vector<double>& level) const {
  validate_parameter_vector(values);
  out.vertices = mesh_.vertices;
  out.crease.assign(mesh_.vertex_count(), 0);
  out.lip_control_points = rig_.lips.control_points;
  // Orbicularis Oculi coupling per eye (thesis §2.4.3).
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
  level.resize(muscles_.size());
  double max_level = 0.0;
  for (std::size_t i = 0; i < muscles_.size(); ++i) {
    const std::size_t p = muscles_[i].parameter;
    level[i] = p == squeezing_param_[0] ? lids[0].squeezing : p == squeezing_param_[1] ? lids[1].squeezing : values[p];
    max_level = std::max(max_level, level[i]);
  }
  max_level = std::max({max_level, values[funneler_param_], values[pressor_param_]});
  const double dc = options_.delta_c;
  const int steps = max_level <= 0.0 ? 0 : options_.parallel ? static_cast<int>(std::ceil(max_level / dc - 1e-9)) : 1;
  out.steps = steps;
  return steps;
}

void FaceSolver::Impl::deform(const std::vector<double>& values, Deformation& out,
                              DeformWorkspace& ws) const {
  std::array<EyelidLevels, 2> lids;
  const int steps = prepare(values, out, lids, ws.level);
  const std::size_t nm = muscles_.size();
  auto& X = out.vertices;
  auto& C = out.lip_control_points;

  // Parallel contraction (thesis §2.4.1, seeds/README.md): in steps δc every muscle with contraction
  // left displaces each vertex at its *current* position; displacements are summed, then applied.
  // A point's displacement depends only on its own position, so only the candidate points are kept
  // (in SoA slots, for all steps) and each muscle adds to them in muscle order: the same sums as the
  // step over the whole mesh.
  const double dc = options_.delta_c;
  auto amount = [&](double lvl, int s) {
    const double c = options_.parallel ? std::min(dc, lvl - s * dc) : lvl;
    return c > 0.0 ? c : 0.0;
  };
  ws.step_amount.resize(static_cast<std::size_t>(steps) * (nm + 2));
  for (int s = 0; s < steps; ++s) {
    double* row = ws.step_amount.data() + static_cast<std::size_t>(s) * (nm + 2);
    for (std::size_t i = 0; i < nm; ++i) row[i] = amount(ws.level[i], s) * muscle_plans_[i].k;
    row[nm] = amount(values[funneler_param_], s);
    row[nm + 1] = amount(values[pressor_param_], s);
  }
  const MusclePlan* plans = muscle_plans_.data();
  // Per step: gather the candidate vertices and lip control points (SoA slots) and how far each has
  // moved, accumulate the muscles in muscle order (vector muscles two points at a time), add the
  // Orbicularis Oris lip actions, then apply. A point's displacement depends only on its own position.
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "control points are read as packed xyz triples");
  const std::size_t nu = vertex_lists_.point.size(), ncp = C.size(), slots = nu + ncp + 1;  // + dummy slot
  ws.position.resize(3 * slots);
  ws.moved2.resize(slots);
  ws.displacement.assign(3 * slots, 0.0);
  double* px = ws.position.data();
  double* py = px + slots;
  double* pz = py + slots;
  double* dx = ws.displacement.data();
  double* dy = dx + slots;
  double* dz = dy + slots;
  double* moved2 = ws.moved2.data();
  const double* nx = slot_neutral_.data();
  const double* ny = nx + slots;
  const double* nz = ny + slots;
  if (steps > 0) {  // gather once; the points stay in the SoA slots until the last step
    std::copy(slot_neutral_.begin(), slot_neutral_.end(), ws.position.begin());
  }
  for (int s = 0; s < steps; ++s) {
    for (std::size_t j = 0; j < slots; ++j) {
      const double mx = px[j] - nx[j], my = py[j] - ny[j], mz = pz[j] - nz[j];
      moved2[j] = mx * mx + my * my + mz * mz;
    }
    const double* ck = ws.step_amount.data() + static_cast<std::size_t>(s) * (nm + 2);
    for (std::size_t i = 0; i < nm; ++i) {
      if (ck[i] == 0.0) continue;
      const MusclePlan& q = plans[i];
      const MuscleSlots& list = muscle_slots_[i];
#if defined(EMOFACE_MUSCLES_SSE2)
      if (!q.sphincter && !q.exact) {
        vector_muscle_pass(q, ck[i], list.slot.data(), list.reach2.data(), list.slot.size(), px, py, pz, moved2, dx, dy, dz);
        continue;
      }
#endif
      // zones further than the point has moved from its neutral position cannot contain it yet
      for (std::size_t e = 0; e < list.slot.size(); ++e) {
        const auto j = static_cast<std::size_t>(list.slot[e]);
        if (list.reach2[e] <= moved2[j]) accumulate(q, ck[i], px[j], py[j], pz[j], dx[j], dy[j], dz[j]);
      }
    }
    // Orbicularis Oris (thesis §2.4.2): precomputed per-unit displacements of the control points
    const double funnel = ck[nm], press = ck[nm + 1];
    for (std::size_t c = 0; c < ncp; ++c) {
      const std::size_t j = nu + c;
      if (funnel > 0.0) dx[j] += funnel * funnel_delta_[c].x(), dy[j] += funnel * funnel_delta_[c].y(), dz[j] += funnel * funnel_delta_[c].z();
      if (press > 0.0) dx[j] += press * press_delta_[c].x(), dy[j] += press * press_delta_[c].y(), dz[j] += press * press_delta_[c].z();
    }
    for (std::size_t j = 0; j < 3 * slots; ++j) px[j] += dx[j], dx[j] = 0.0;  // apply the step
  }
  if (steps > 0) {
    for (std::size_t j = 0; j < nu; ++j) {
      double* p = X.data() + 3 * static_cast<std::ptrdiff_t>(vertex_lists_.point[j]);
      p[0] = px[j], p[1] = py[j], p[2] = pz[j];
    }
    for (std::size_t c = 0; c < ncp; ++c) C[c] = Eigen::Vector3d(px[nu + c], py[nu + c], pz[nu + c]);
  }

  apply_lids_jaw_lips(values, lids, out);

  // Bulges and wrinkles (thesis §2.4.1): tabulated amplitudes (build_fast_path) × level, largest
  // amplitude where muscles overlap, applied along the area-weighted normal of the displaced mesh;
  // wrinkle feet are flagged so renderers use the face normal there ("unrepresentative vertex normal").
  if (options_.wrinkles && !wrinkle_vertices_.empty()) {
    const std::size_t nw = wrinkle_vertices_.size();
    auto& amp = ws.wrinkle_amplitude;
    amp.assign(nw, 0.0);
    bool any = false;
    for (std::size_t i = 0; i < nm; ++i) {
      if (wrinkles_[i].empty() || ws.level[i] <= 0.0) continue;
      any = true;
      for (const WrinkleEntry& w : wrinkles_[i]) {
        const double h = ws.level[i] * w.height;
        double& slot = amp[static_cast<std::size_t>(w.slot)];
        if (h > slot) slot = h;
        if (w.crease) out.crease[static_cast<std::size_t>(wrinkle_vertices_[static_cast<std::size_t>(w.slot)])] = 1;
      }
    }
    if (any) {
      auto& normal = ws.wrinkle_normal;
      normal.assign(3 * nw, 0.0);
      for (std::size_t k = 0; k < nw; ++k) {
        if (amp[k] <= 0.0) continue;
        const int v = wrinkle_vertices_[k];
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        for (int q = vertex_face_start_[static_cast<std::size_t>(v)]; q < vertex_face_start_[static_cast<std::size_t>(v) + 1]; ++q) {
          const int f = vertex_faces_[static_cast<std::size_t>(q)];
          const Eigen::Vector3d a = X.row(mesh_.faces(f, 0)).transpose();
          n += (Eigen::Vector3d(X.row(mesh_.faces(f, 1)).transpose()) - a).cross(Eigen::Vector3d(X.row(mesh_.faces(f, 2)).transpose()) - a);
        }
        const double len = n.norm();
        if (len > 0.0) n /= len;
        else amp[k] = 0.0;
        normal[3 * k] = n.x(), normal[3 * k + 1] = n.y(), normal[3 * k + 2] = n.z();
      }
      for (std::size_t k = 0; k < nw; ++k) {
        if (amp[k] <= 0.0) continue;
        double* p = X.data() + 3 * static_cast<std::ptrdiff_t>(wrinkle_vertices_[k]);
        p[0] += amp[k] * normal[3 * k], p[1] += amp[k] * normal[3 * k + 1], p[2] += amp[k] * normal[3 * k + 2];
      }
    }
  }
  apply_gaze_and_pose(values, out);
}

FaceSolver::FaceSolver(facemesh::Mesh mesh, facemesh::Rig rig, SolverOptions options)
    : impl_(std::make_shared<const Impl>(std::move(mesh), std::move(rig), options)) {}

void FaceSolver::deform(const std::vector<double>& values, Deformation& out,
                        DeformWorkspace& workspace) const {
  impl_->deform(values, out, workspace);
}

void FaceSolver::deform_reference(const std::vector<double>& values, Deformation& out) const {
  impl_->deform_reference(values, out);
}

const facemesh::Mesh& FaceSolver::neutral() const noexcept { return impl_->mesh_; }
const facemesh::Rig& FaceSolver::rig() const noexcept { return impl_->rig_; }
const SolverOptions& FaceSolver::options() const noexcept { return impl_->options_; }
std::size_t FaceSolver::candidate_count(std::size_t muscle) const {
  return impl_->muscles_.at(muscle).vertices.size();
}

void FaceSolver::deform(const std::vector<double>& values, Deformation& out) const {
  DeformWorkspace workspace;
  deform(values, out, workspace);
}

void FaceSolver::Impl::apply_lids_jaw_lips(const std::vector<double>& values,
                                           const std::array<EyelidLevels, 2>& lids,
                                           Deformation& out) const {
  auto& X = out.vertices;
  auto& C = out.lip_control_points;
  // Eyelids (thesis §2.4.3, after Parke 1974): rotation of the lid about the eye's horizontal axis,
  // weighted from the lid margin outwards. Pars palpebralis tightens (AU7: upper lid a little down,
  // lower lid up, never shut); a blink (eye_blink, AU45) closes the lid, linear in its level, and
  // takes over from the tightener and the levator (AU5) as it rises, so blink = 1 closes exactly
  // (upper lid by close_angle, lower lid up by 0.2 of it) whatever else is active. The tightener's
  // and the cheek's fractions are of Eye::tighten_angle (≤ close_angle; close_angle when absent).
  for (std::size_t e = 0; e < 2; ++e) {
    const auto& eye = rig_.eyes[e];
    const double blink = values[blink_param_[e]];
    const double tight = lids[e].closing;
    const double tighten_angle = eye.tighten_angle.value_or(eye.close_angle);
    const double upper = (1.0 - blink) * tighten_angle * options_.lid_tighten_upper * tight +
                         blink * eye.close_angle -
                         (1.0 - blink) * values[opening_param_[e]] * eye.open_angle;
    // lower lid: the tightener (AU7) and the cheek pushed up by the orbitalis (AU6), capped so
    // that they never meet the tightened upper lid
    const double lower_raise =
        std::min(options_.lid_tighten_lower * tight + options_.lid_cheek_raise * lids[e].squeezing,
                 0.8 - options_.lid_tighten_upper);
    const double lower =
        -((1.0 - blink) * tighten_angle * lower_raise + 0.2 * blink * eye.close_angle);
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
  if (!C.empty() && rig_.lips.samples_in_mesh) lip_sampler_.evaluate(C, X, rig_.lips.first_vertex);
  // Vertices bound to the lip surface (rig format 1.1): x = (1 − w)·x + w·(S(u, v) + offset), S from
  // the precomputed ≤ 16 basis terms of each binding.
  const auto& bound = rig_.lips.bound;
  for (std::size_t b = 0; b < bound.size(); ++b) {
    double sx = bound[b].offset.x(), sy = bound[b].offset.y(), sz = bound[b].offset.z();
    for (int t = bound_start_[b]; t < bound_start_[b + 1]; ++t) {
      const auto& term = bound_terms_[static_cast<std::size_t>(t)];
      const Eigen::Vector3d& c = C[static_cast<std::size_t>(term.control)];
      sx += term.weight * c.x(), sy += term.weight * c.y(), sz += term.weight * c.z();
    }
    double* p = X.data() + 3 * static_cast<std::ptrdiff_t>(bound[b].vertex);
    const double w = bound[b].weight;
    if (w == 1.0) {
      p[0] = sx, p[1] = sy, p[2] = sz;
    } else {
      p[0] = (1.0 - w) * p[0] + w * sx, p[1] = (1.0 - w) * p[1] + w * sy, p[2] = (1.0 - w) * p[2] + w * sz;
    }
  }
}

void FaceSolver::Impl::apply_gaze_and_pose(const std::vector<double>& values,
                                           Deformation& out) const {
  auto& X = out.vertices;
  const long nv = X.rows();
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
  // x·0 is NaN exactly for NaN/inf x; two accumulators keep the loop short (Eigen's allFinite was 2 % of a deformation)
  const double* x = X.data();
  double z0 = 0.0, z1 = 0.0;
  const long n = 3 * nv;
  for (long i = 0; i + 1 < n; i += 2) z0 += x[i] * 0.0, z1 += x[i + 1] * 0.0;
  if (n % 2 != 0) z0 += x[n - 1] * 0.0;
  if (z0 + z1 != 0.0) throw NumericalError("FaceSolver: deformation produced a non-finite vertex");
}

void FaceSolver::Impl::deform_reference(const std::vector<double>& values, Deformation& out) const {
  std::array<EyelidLevels, 2> lids;
  std::vector<double> level;
  const int steps = prepare(values, out, lids, level);
  const long nv = mesh_.vertices.rows();
  auto& X = out.vertices;
  auto& C = out.lip_control_points;
  const auto regions = facemesh::region_vertices(rig_);
  // Parallel contraction (thesis §2.4.1): per step, every muscle displaces every vertex of its regions
  // (and, if it moves the lips, every lip control point) at the current position; sum, then apply.
  const double dc = options_.delta_c;
  std::vector<Eigen::Vector3d> disp(static_cast<std::size_t>(nv)), disp_c(C.size());
  for (int s = 0; s < steps; ++s) {
    auto amount = [&](double lvl) { return options_.parallel ? std::min(dc, lvl - s * dc) : lvl; };
    std::fill(disp.begin(), disp.end(), Eigen::Vector3d::Zero());
    std::fill(disp_c.begin(), disp_c.end(), Eigen::Vector3d::Zero());
    for (std::size_t i = 0; i < muscles_.size(); ++i) {
      const double c = amount(level[i]);
      if (c <= 0.0) continue;
      const Muscle& m = muscles_[i];
      auto displacement = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
        if (m.kind == facemesh::MuscleKind::Vector) return vector_muscle_displacement(m.geometry, p, c);
        return sphincter_displacement(m.geometry.head, m.semi_axes, m.geometry.k, p, c);
      };
      const auto& spec = rig_.muscles[i];
      for (auto region : spec.regions) {
        for (int v : regions[static_cast<std::size_t>(region)]) disp[static_cast<std::size_t>(v)] += displacement(X.row(v).transpose());
      }
      if (spec.moves_lips) {
        for (std::size_t k = 0; k < C.size(); ++k)
          if (reaches_lip_column(spec, static_cast<int>(k))) disp_c[k] += displacement(C[k]);
      }
    }
    const double f = amount(values[funneler_param_]), p = amount(values[pressor_param_]);
    for (std::size_t k = 0; k < C.size(); ++k) {
      if (f > 0.0) disp_c[k] += f * funnel_delta_[k];
      if (p > 0.0) disp_c[k] += p * press_delta_[k];
      C[k] += disp_c[k];
    }
    for (long v = 0; v < nv; ++v) X.row(v) += disp[static_cast<std::size_t>(v)].transpose();
  }

  apply_lids_jaw_lips(values, lids, out);

  // Bulges and wrinkles (thesis §2.4.1), straight from the band geometry of waters.hpp.
  if (options_.wrinkles) {
    std::vector<double> amp(static_cast<std::size_t>(nv), 0.0);
    const std::vector<double> edge = mean_edge_lengths(mesh_);
    for (std::size_t i = 0; i < muscles_.size(); ++i) {
      const Muscle& m = muscles_[i];
      if (m.kind != facemesh::MuscleKind::Vector || m.wrinkle_count <= 0 || m.wrinkle_height <= 0.0 || level[i] <= 0.0) continue;
      const double length = wrinkle_band_length(m.geometry);
      if (!(length > 0.0)) continue;
      for (auto region : rig_.muscles[i].regions) {
        for (int v : regions[static_cast<std::size_t>(region)]) {
          const Eigen::Vector3d p0 = mesh_.vertices.row(v).transpose();
          const double l = wrinkle_coordinate(m.geometry, p0);
          const Eigen::Vector3d to_p = p0 - m.geometry.head;
          const double d = to_p.norm();
          if (l < 0.0 || l > length || d <= 0.0 || d > m.geometry.rf) continue;
          const double a = angular_factor(std::acos(std::min(1.0, std::max(-1.0, to_p.dot(m.axis) / d))), m.geometry.omega);
          if (a <= 0.0) continue;
          const double h = level[i] * a * wrinkle_function(l, length, m.wrinkle_count, m.wrinkle_height);
          amp[static_cast<std::size_t>(v)] = std::max(amp[static_cast<std::size_t>(v)], h);
          if (wrinkle_foot(l, length, m.wrinkle_count, edge[static_cast<std::size_t>(v)],
                           options_.crease_resolution))
            out.crease[static_cast<std::size_t>(v)] = 1;
        }
      }
    }
    const facemesh::Vertices displaced = X;
    for (long v = 0; v < nv; ++v) {
      if (amp[static_cast<std::size_t>(v)] <= 0.0) continue;
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      for (long f = 0; f < mesh_.faces.rows(); ++f) {
        if (mesh_.faces(f, 0) != v && mesh_.faces(f, 1) != v && mesh_.faces(f, 2) != v) continue;
        const Eigen::Vector3d a = displaced.row(mesh_.faces(f, 0)).transpose();
        n += (Eigen::Vector3d(displaced.row(mesh_.faces(f, 1)).transpose()) - a).cross(Eigen::Vector3d(displaced.row(mesh_.faces(f, 2)).transpose()) - a);
      }
      if (n.norm() > 0.0) X.row(v) += amp[static_cast<std::size_t>(v)] * n.normalized().transpose();
    }
  }
  apply_gaze_and_pose(values, out);
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

double eye_aperture(const facemesh::Rig& rig, const facemesh::Vertices& X, int eye) {
  if (eye < 0 || eye > 1) throw InvalidInput("eye_aperture: eye must be 0 (right) or 1 (left)");
  const auto& e = rig.eyes[static_cast<std::size_t>(eye)];
  const double half_width = 0.3 * e.radius;
  auto margin = [&](const std::vector<int>& ids, const std::vector<double>& weights, bool upper) {
    double best =
        upper ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < ids.size() && k < weights.size(); ++k) {
      if (weights[k] < 0.999) continue;
      if (ids[k] < 0 || ids[k] >= X.rows())
        throw InvalidInput("eye_aperture: lid vertex out of range");
      if (std::abs(X(ids[k], 0) - e.centre.x()) > half_width) continue;
      best = upper ? std::min(best, X(ids[k], 1)) : std::max(best, X(ids[k], 1));
    }
    if (!std::isfinite(best))
      throw InvalidInput("eye_aperture: no lid margin vertex in the eye's centre column");
    return best;
  };
  const double top = margin(e.upper_lid, e.upper_lid_weights, true);
  const double bottom = margin(e.lower_lid, e.lower_lid_weights, false);
  return std::max(0.0, top - bottom);
}

}  // namespace emoface::muscles
