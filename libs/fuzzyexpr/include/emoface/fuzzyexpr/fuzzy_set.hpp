#pragma once
// Piecewise-linear fuzzy sets and the exact centre-of-area defuzzifier (thesis §6.4.1–6.4.2).
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace emoface::fuzzyexpr {

/// Shape of a fuzzy set as written in rule files. Both are stored as four breakpoints a ≤ b ≤ c ≤ d.
enum class SetShape : std::uint8_t { Triangle, Trapezoid };
std::string_view to_string(SetShape s) noexcept;
std::optional<SetShape> set_shape_from_string(std::string_view name) noexcept;

/// A trapezoidal membership function (triangle when b == c): 0 up to a, rising linearly to 1 at b,
/// 1 up to c, falling linearly to 0 at d. a == b (c == d) gives a vertical left (right) edge, which is
/// how shoulders at the end of a universe are written. Units: those of the variable (intensity or
/// contraction level, both dimensionless).
struct FuzzySet {
  std::string name;
  SetShape shape = SetShape::Triangle;
  std::array<double, 4> points{};  ///< a, b, c, d

  static FuzzySet triangle(std::string name, double a, double b, double c);
  static FuzzySet trapezoid(std::string name, double a, double b, double c, double d);

  double membership(double x) const noexcept {
    const double a = points[0], b = points[1], c = points[2], d = points[3];
    if (x < a || x > d) return 0.0;
    if (x < b) return (x - a) / (b - a);
    if (x <= c) return 1.0;
    if (x < d) return (d - x) / (d - c);
    return c == d ? 1.0 : 0.0;  // x == d: 1 only on a vertical right edge
  }
  /// Throws InvalidInput unless the breakpoints are finite, ordered and span a positive width, and
  /// (for a triangle) b == c.
  void validate() const;
};

/// One activated output set: μ(y) = min(height, set.membership(y)) (Mamdani min implication).
/// A plain aggregate (no default initialisers, so arrays of it are free): write ClippedSet{&set, h}.
struct ClippedSet {
  const FuzzySet* set;
  double height;  ///< activation in (0, 1]; ≤ 0 means not activated
};

/// True if every x in [0, 1] has positive membership in at least one of `sets` (exact: checks every
/// breakpoint and every gap between breakpoints).
bool covers_unit_interval(const std::vector<FuzzySet>& sets);

struct CentreOfArea {
  double centroid = 0.0;  ///< ∫ y μ(y) dy / ∫ μ(y) dy; NaN when the area is 0
  double area = 0.0;      ///< ∫ μ(y) dy
};

/// Exact centre of area of the max-aggregation of the clipped sets (thesis §6.4.2, the COA formula
/// y = ∫ μ(y) y dy / ∫ μ(y) dy). The aggregate is piecewise linear; this splits the line at every
/// breakpoint and at every crossing of two pieces and integrates each linear piece in closed form, so
/// the result is exact up to rounding (no sampling). At most 16 sets.
CentreOfArea centre_of_area(const ClippedSet* clips, std::size_t count) noexcept;

}  // namespace emoface::fuzzyexpr
