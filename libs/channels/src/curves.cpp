#include "emoface/channels/curves.hpp"

#include <cmath>
#include <string>

#include "emoface/core/errors.hpp"

namespace emoface::channels {

namespace {
constexpr double kLn2 = 0.69314718055994530942;
}

// thesis §4.4: φ+(x, Do) = exp(ln2/Do · x) − 1
double phi_plus(double x, double duration) noexcept { return std::exp(kLn2 * x / duration) - 1.0; }

// thesis §4.4: φ−(x, Dr) = exp(ln2 − ln2/Dr · x) − 1
double phi_minus(double x, double duration) noexcept {
  return std::exp(kLn2 - kLn2 * x / duration) - 1.0;
}

// φ+(x, D) = y  <=>  x = D·ln(1+y)/ln2
double phi_plus_inverse(double y, double duration) noexcept {
  return duration * std::log1p(y) / kLn2;
}

void Timing::validate() const {
  const auto fail = [](const std::string& m) { throw InvalidInput("movement timing: " + m); };
  if (!std::isfinite(start) || !std::isfinite(end) || !std::isfinite(onset) || !std::isfinite(offset))
    fail("times must be finite");
  if (start < 0.0) fail("start time " + std::to_string(start) + " s is negative");
  if (!(end > start)) fail("end time must be after the start time");
  if (!(onset > 0.0)) fail("onset duration must be > 0 s");
  if (!(offset > 0.0)) fail("offset duration must be > 0 s");
  if (onset + offset > end - start + 1e-9)
    fail("onset + offset (" + std::to_string(onset + offset) + " s) exceeds the duration (" +
         std::to_string(end - start) + " s)");
}

// thesis §4.4, the four-case definition of F^m_p(t).
double activity(double target, const Timing& m, double t) noexcept {
  if (t <= m.start || t >= m.end) return 0.0;
  if (t < m.start + m.onset) return target * phi_plus(t - m.start, m.onset);
  if (t <= m.end - m.offset) return target;
  return target * phi_minus(t - m.end + m.offset, m.offset);
}

}  // namespace emoface::channels
