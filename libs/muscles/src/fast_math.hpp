#pragma once
// Polynomial cos and acos for the hot loop of the vector muscles (profiling showed libm's cos/acos
// at ~60 % of a deformation). Accuracy is far below anything visible: |error| < 1e-9 (cos), 2e-8 (acos),
// i.e. < 1e-10 m of displacement for k = 1 cm. Tested against <cmath> in waters_test.
#include <cmath>

namespace emoface::muscles::detail {

/// cos(t) for t in [0, π/2]: even Taylor polynomial to t^14 (truncation < 4e-11 at π/2).
inline double cos_quadrant(double t) {
  const double u = t * t;
  return 1.0 + u * (-1.0 / 2 + u * (1.0 / 24 + u * (-1.0 / 720 + u * (1.0 / 40320 + u * (-1.0 / 3628800 +
         u * (1.0 / 479001600 + u * (-1.0 / 87178291200.0)))))));
}

/// acos(x) for x in [-1, 1]: Abramowitz & Stegun 4.4.46 (|error| <= 2e-8 on [0, 1]), mirrored for x < 0.
inline double acos_fast(double x) {
  const bool negative = x < 0.0;
  const double a = negative ? -x : x;
  const double p = 1.5707963050 + a * (-0.2145988016 + a * (0.0889789874 + a * (-0.0501743046 + a * (0.0308918810 +
                   a * (-0.0170881256 + a * (0.0066700901 + a * -0.0012624911))))));
  const double r = std::sqrt(1.0 - a) * p;
  return negative ? 3.14159265358979323846 - r : r;
}

}  // namespace emoface::muscles::detail
