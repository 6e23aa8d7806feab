#pragma once
// The formulas of the muscle model, free functions so they can be tested on their own.
// Units: metres, radians; contraction levels in [0, 1].
#include <Eigen/Core>

namespace emoface::muscles {

/// Waters' linear muscle (thesis §2.2.3, §2.4.1; reading in seeds/README.md): from the bony
/// attachment `head` (v1) to the skin insertion `tail` (v2).
struct VectorMuscle {
  Eigen::Vector3d head = Eigen::Vector3d::Zero();
  Eigen::Vector3d tail = Eigen::Vector3d::UnitZ();
  double omega = 0.5;  ///< zone half-angle Ω, radians, (0, π)
  double rs = 0.5;     ///< fall-off start Rs, m
  double rf = 1.0;     ///< fall-off end Rf, m (> rs)
  double k = 0.01;     ///< elasticity constant: displacement at c = 1 where A = R = 1, m
};

/// A = cos((α/Ω)·π/2) for α < Ω, else 0 (Waters 1987 / Parke & Waters 1996 angular fall-off; the thesis
/// prints cos α, which does not vanish at the zone edge — see seeds/README.md).
double angular_factor(double alpha, double omega);

/// R = cos((1 − D/Rs)·π/2) for D ≤ Rs, cos(((D − Rs)/(Rf − Rs))·π/2) for Rs < D ≤ Rf, else 0.
double radial_factor(double distance, double rs, double rf);

/// Displacement of point p for contraction c: c·k·A·R·(v1 − p)/|v1 − p| (zero outside the zone or at v1).
Eigen::Vector3d vector_muscle_displacement(const VectorMuscle& m, const Eigen::Vector3d& p, double c);

/// Waters' elliptical sphincter in the x/y plane (Orbicularis Oculi orbitalis, thesis §2.4.3): with
/// e = sqrt((dx/ax)² + (dy/ay)²) < 1 the point moves towards the centre in x/y by c·k·sin(π·e)
/// (zero at the centre and at the ellipse, largest half-way); outside, zero.
Eigen::Vector3d sphincter_displacement(const Eigen::Vector3d& centre, const Eigen::Vector2d& semi_axes, double k,
                                       const Eigen::Vector3d& p, double c);

/// The wrinkle function of thesis §2.4.1 (seeds/README.md): b = L/(2·Nw), u(l) = l − 2b·⌊l/(2b)⌋,
/// f(l) = a·(1 − (u − b)²/b²). Zero outside 0 ≤ l ≤ L. Requires L > 0, Nw ≥ 1.
double wrinkle_function(double l, double length, int count, double height);

/// Whether a band point is a wrinkle *foot* (a valley of f, thesis §2.4.1: there "the vertex normal
/// is unrepresentative", so renderers shade it with the face normal): u within 0.15·b of a valley,
/// outside the band's first and last half-period, and the mesh there fine enough to resolve the
/// valley as a row of vertices: `mean_edge` (the mean length of the vertex's edges) ≤
/// `resolution`·b. On a coarser mesh (the generic and default faces: edges 4–7 mm, b ≈ 9 mm) a foot
/// is a scattered vertex, and its face normal shades whole triangles flat (faceted, blotchy
/// foreheads); there the vertex normal of the displaced mesh already shows the wrinkle. False when
/// L ≤ 0 or Nw < 1.
bool wrinkle_foot(double l, double length, int count, double mean_edge, double resolution);

/// Wrinkle band of a vector muscle (our reading of the lost Fig. 2.15): the part of the zone of
/// influence between the line through v3 (on the axis, |v1v3| = Rf·cos Ω) perpendicular to the axis
/// and a parallel line L = ¾·Rf·cos Ω closer to v1. `l` is the distance from p to the v3 line, measured
/// along the axis towards v1. Returns the band coordinate l (any value; in the band when 0 ≤ l ≤ L).
double wrinkle_coordinate(const VectorMuscle& m, const Eigen::Vector3d& p);
/// L = ¾·Rf·cos Ω.
double wrinkle_band_length(const VectorMuscle& m);

/// Orbicularis Oculi coupling of one eye (thesis §2.4.3). The thesis prints
/// "cclosing = max(1.0, 2·csqueezing)", which would always close fully; we read it as min(1, 2·s).
/// `other_closing` is the closing level of the other eye (one-eye closing when it is 0).
struct EyelidLevels {
  double closing = 0.0;
  double squeezing = 0.0;
};
EyelidLevels couple_eyelids(double closing, double squeezing, double other_closing);

/// Eye-hole limit (thesis §2.4.5): if (yaw/Y)² + (pitch/P)² > 1, both are scaled onto the ellipse.
Eigen::Vector2d limit_gaze(double yaw, double pitch, double yaw_limit, double pitch_limit);

}  // namespace emoface::muscles
