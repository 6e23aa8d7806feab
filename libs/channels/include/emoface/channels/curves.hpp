#pragma once
// Onset/offset curves and the activity of one atomic movement (thesis §4.4).
// Times are in seconds; activities are in the unit of the parameter (contraction in [0,1] for
// muscles, radians for gaze/head) and scale linearly with the movement's target value.
namespace emoface::channels {

/// Onset curve φ+(x, D) = exp(ln2·x/D) − 1 (thesis §4.4, derived from Essa's e^{bx} − 1 with
/// φ+(0)=0, φ+(D)=1). Defined for every real x (it keeps growing past x = D). D must be > 0.
double phi_plus(double x, double duration) noexcept;

/// Offset curve φ−(x, D) = exp(ln2 − ln2·x/D) − 1 (thesis §4.4, from Essa's e^{c−dx} − 1 with
/// φ−(0)=1, φ−(D)=0). D must be > 0.
double phi_minus(double x, double duration) noexcept;

/// Inverse of φ+: the x ≥ 0 with φ+(x, D) = y, i.e. D·log2(1 + y), for y ≥ 0 (thesis §4.5.2, the ξ of
/// the concatenation rule).
double phi_plus_inverse(double y, double duration) noexcept;

/// The timing of an atomic movement Γo = (PV, Ts, Te, Do, Dr) (thesis §4.4), seconds.
struct Timing {
  double start = 0.0;   ///< Ts
  double end = 1.0;     ///< Te > Ts
  double onset = 0.5;   ///< Do > 0
  double offset = 0.5;  ///< Dr > 0, Do + Dr <= Te − Ts
  /// Throws InvalidInput unless all values are finite, Ts >= 0, Do > 0, Dr > 0, Do + Dr <= Te − Ts
  /// (up to 1e-9 s).
  void validate() const;
};

/// Activity F_p(t) of a parameter with target value `target` in one movement (thesis §4.4):
/// PV·φ+(t−Ts, Do) during the onset, PV during the apex, PV·φ−(t−Te+Dr, Dr) during the offset and 0
/// outside (Ts, Te). Continuous in t.
double activity(double target, const Timing& timing, double t) noexcept;

}  // namespace emoface::channels
