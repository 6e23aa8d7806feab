#pragma once
// The muscle-driven face (thesis §2.4): named parameters -> deformed mesh.
//
//   FaceSolver solver(face.mesh, face.rig);          // precomputes per-muscle vertex lists etc.
//   Deformation d = solver.deform(values);           // many times; values in parameter_names() order
//   Deformation e = deform_face(mesh, rig, {{"zygomatic_major_l", 1.0}});   // one-off
//
// Per call: parallel contraction of all vector and sphincter muscles and the Orbicularis Oris lip
// actions in steps δc (§2.4.1), eyelids (§2.4.3), jaw (§2.4.4), lip B-spline re-sampling (§2.3.2) and
// the vertices bound to the lip surface (rig 1.1 LipBinding),
// wrinkles along the normals (§2.4.1), eyeball rotation with the eye-hole limit (§2.4.5), head pose.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "emoface/facemesh/bspline.hpp"
#include "emoface/facemesh/io.hpp"
#include "emoface/facemesh/mesh.hpp"
#include "emoface/facemesh/rig.hpp"
#include "emoface/muscles/parameters.hpp"
#include "emoface/muscles/waters.hpp"

namespace emoface::muscles {

/// How the Orbicularis Oculi pars palpebralis (the thesis' "closing" level; here the lid tightener,
/// AU7) and pars orbitalis (squeezing) levels of one eye are coupled (thesis §2.4.3; see
/// couple_eyelids()). No coupling closes the eye: closure is eye_blink_* only.
enum class EyelidCoupling {
  OneEye,  ///< only the second branch: closing one eye alone squeezes it (c_sq = ½·c_cl)
  Thesis,  ///< the full printed rule: squeezing also closes the lid (c_cl = min(1, 2·c_sq))
  Off      ///< levels used as given
};
std::string to_string(EyelidCoupling coupling);
EyelidCoupling eyelid_coupling_from_string(std::string_view name);

struct SolverOptions {
  double delta_c = 0.2;        ///< contraction step δc (thesis §2.4.1: 0.2), (0, 1]
  bool parallel = true;        ///< false: Waters' plain sum of full displacements (thesis Fig. 2.12 g–j)
  bool wrinkles = true;        ///< bulges and wrinkles along the normals (thesis §2.4.1)
  /// Extra slack, as a fraction of the muscle's Rf, on the distance at which a vertex becomes a
  /// candidate of a muscle, [0, 4]. The candidate lists are complete without it (a vertex is listed
  /// when the muscles that can reach it could carry it into the zone, see docs/muscles.md), so the
  /// default 0 changes no result; larger values only cost time. Zone membership is re-evaluated at the
  /// current positions every step.
  double zone_margin = 0.0;
  double funnel_rotation = 0.349065850398866;  ///< lip funneler rotation θ, radians (thesis §2.4.2: 20°), [0, π/2]
  double funnel_extrusion = 0.006;  ///< lip funneler extrusion x at the lip edge, m, [0, 0.05]
  double press_rotation = 0.349065850398866;   ///< lip pressor rotation (opposite sense), radians, [0, π/2]
  /// Default OneEye: the first branch of the thesis rule raises the palpebralis level of every
  /// expression whose fuzzy rules squeeze at ≥ 0.5 (sadness, happiness, anger, ...); it stays
  /// available as Thesis (docs/muscles.md, deviations).
  EyelidCoupling eyelid_coupling = EyelidCoupling::OneEye;
  /// Orbicularis oculi pars palpebralis is the lid *tightener* (FACS AU7: narrows the eye aperture
  /// and raises the lower lid; Ekman, Friesen & Hager 2002); closing the eye is a blink (AU45,
  /// eye_blink_*). At palpebralis level t the upper lid turns down by tighten_upper·a·t and the
  /// lower lid up by tighten_lower·a·t (linear; a = facemesh::Eye::tighten_angle, which is at most
  /// close_angle and is close_angle when the rig has none), both fractions in [0, 0.6], their
  /// sum ≤ 0.8 so that t = 1 never shuts the eye (close_angle + 0.2·close_angle does). Defaults: on
  /// the default face t = 1 leaves about a third of the neutral aperture, mostly by raising the
  /// lower lid (docs/muscles.md, deviations).
  double lid_tighten_upper = 0.20;
  double lid_tighten_lower = 0.50;
  /// Orbicularis oculi pars orbitalis (FACS AU6, the cheek raiser) bunches the cheek against the
  /// lower lid and pushes it up (Ekman & Friesen 1975: "lower eyelid is pushed up ... by the
  /// cheek"): at orbitalis level s the lower lid turns up by a further
  /// lid_cheek_raise·a·s, in [0, 0.6]. The lower lid's total (tightener + cheek) is
  /// capped at 0.8 − lid_tighten_upper of a, so the two together never shut the eye
  /// either (issue 14). Default 0.15: on the default face (the MakeHuman head) the smile then reads
  /// as happiness to the expression oracle; 0 gives the generic face's old lids (docs/muscles.md).
  double lid_cheek_raise = 0.15;
  /// A wrinkle foot is flagged in Deformation::crease only where the mesh resolves it: the vertex's
  /// mean edge length ≤ crease_resolution·b (b = the wrinkle's half-period, see wrinkle_foot()),
  /// [0, 1e6]. Default 0.3, the width of the foot's band (u within 0.15·b of a valley): no creases
  /// on the generic and default faces (edges 4–7 mm against b ≈ 9 mm), where face-normal shading
  /// made faceted foreheads (issue 14); 1e6 flags every foot as before; 0 none.
  double crease_resolution = 0.3;
  void validate() const;
};

/// Result of one deformation.
struct Deformation {
  facemesh::Vertices vertices;       ///< #V by 3, m
  std::vector<std::uint8_t> crease;  ///< per vertex, 1 = wrinkle foot: shade with the face normal (§2.4.1)
  std::vector<Eigen::Vector3d> lip_control_points;  ///< deformed 24×6 lip grid
  int steps = 0;                     ///< contraction steps taken
};

/// Scratch memory of FaceSolver::deform (contents unspecified). Keep one per thread and pass it to
/// every call: after the first call on a solver, deform() then allocates nothing.
struct DeformWorkspace {
  std::vector<double> level;        ///< per muscle
  std::vector<double> step_amount;  ///< per step and muscle: contraction δ times elasticity k
  std::vector<double> wrinkle_amplitude;
  std::vector<double> wrinkle_normal;
  std::vector<double> position, moved2, displacement;  ///< per candidate point (vertices, then lip control points), SoA
};

/// Thread safety: a FaceSolver is immutable after construction, so one solver may be shared by any
/// number of threads, each calling deform() with its own Deformation (and DeformWorkspace).
class FaceSolver {
 public:
  /// Validates the rig against the mesh (InvalidInput on mismatch) and precomputes per-muscle data.
  FaceSolver(facemesh::Mesh mesh, facemesh::Rig rig, SolverOptions options = {});

  /// Deforms for `values` (kParameterCount entries in parameter_names() order). Reuses `out`'s storage
  /// and `workspace`'s scratch memory (no allocation once both have been used with this solver).
  void deform(const std::vector<double>& values, Deformation& out, DeformWorkspace& workspace) const;
  /// As above with a temporary workspace (allocates a few small buffers per call).
  void deform(const std::vector<double>& values, Deformation& out) const;
  Deformation deform(const std::vector<double>& values) const;
  /// Named values (missing = 0); unknown names throw InvalidInput.
  Deformation deform(const std::map<std::string, double>& named) const;

  /// The same deformation computed the plain way, for tests and as executable documentation of the
  /// fast path: every vertex of the muscle's regions (region cut-off only), exact <cmath> cos/acos
  /// through waters.hpp, per-step displacement buffers, wrinkles recomputed from the band geometry.
  /// deform() agrees with it to ~1e-10 m (solver_test: FastPathMatchesReference). ~15 ms on the
  /// default face (vertex normals by a scan of all faces), some 40× slower than deform().
  void deform_reference(const std::vector<double>& values, Deformation& out) const;

  const facemesh::Mesh& neutral() const noexcept;
  const facemesh::Rig& rig() const noexcept;
  const SolverOptions& options() const noexcept;
  /// Number of candidate vertices visited per step by muscle i (after the region cut-off).
  std::size_t candidate_count(std::size_t muscle) const;

 private:
  // The precomputed muscle data and the hot path (solver.cpp): immutable after construction and
  // shared by copies, so that a copy is cheap and this header exposes none of the fast path's
  // layout (issue 18: 26 files recompiled with every change of it).
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

/// The jaw weight of the skin beside each border control point of the lip grid (thesis §2.4.4), as
/// the solver derives it when the rig carries none (`LipGrid::border_jaw` empty): per column c of
/// row 0, the weight of the jaw vertex nearest to the control point, 0 when none lies within 4 mm.
/// kAround values; empty for a rig without lips. It depends on which vertices the mesh has, so a
/// rig transferred onto another mesh stores the source's values. Throws InvalidInput for jaw ids
/// outside the mesh or a lip grid with fewer than kAround control points.
std::vector<double> lip_border_jaw_weights(const facemesh::Mesh& mesh, const facemesh::Rig& rig);

/// One-off: builds a FaceSolver and deforms once (same code path, so they cannot drift apart).
Deformation deform_face(const facemesh::Mesh& mesh, const facemesh::Rig& rig,
                        const std::map<std::string, double>& named, const SolverOptions& options = {});

/// Vertical eye aperture (m) of eye `eye` (0 = right, 1 = left) in the vertex positions X: the
/// lowest upper-lid margin point minus the highest lower-lid margin point (lid vertices of weight
/// ≥ 0.999) within 0.3·radius of the eye centre's x; 0 when the lids meet or overlap. Measured along
/// y, so meaningful with the head upright (head pose 0). Throws InvalidInput for a bad eye index, X
/// smaller than the rig's vertices or an eye without margin vertices in that column.
double eye_aperture(const facemesh::Rig& rig, const facemesh::Vertices& X, int eye);

}  // namespace emoface::muscles
