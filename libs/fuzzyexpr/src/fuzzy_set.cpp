#include "emoface/fuzzyexpr/fuzzy_set.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emoface/core/errors.hpp"

namespace emoface::fuzzyexpr {

std::string_view to_string(SetShape s) noexcept {
  return s == SetShape::Triangle ? "triangle" : "trapezoid";
}

std::optional<SetShape> set_shape_from_string(std::string_view name) noexcept {
  if (name == "triangle") return SetShape::Triangle;
  if (name == "trapezoid") return SetShape::Trapezoid;
  return std::nullopt;
}

FuzzySet FuzzySet::triangle(std::string name, double a, double b, double c) {
  return FuzzySet{std::move(name), SetShape::Triangle, {a, b, b, c}};
}

FuzzySet FuzzySet::trapezoid(std::string name, double a, double b, double c, double d) {
  return FuzzySet{std::move(name), SetShape::Trapezoid, {a, b, c, d}};
}

void FuzzySet::validate() const {
  const auto& p = points;
  for (double v : p)
    if (!std::isfinite(v)) throw InvalidInput("fuzzy set \"" + name + "\": breakpoint is not finite");
  if (!(p[0] <= p[1] && p[1] <= p[2] && p[2] <= p[3]))
    throw InvalidInput("fuzzy set \"" + name + "\": breakpoints must satisfy a <= b <= c <= d");
  if (!(p[3] > p[0])) throw InvalidInput("fuzzy set \"" + name + "\": zero width (a == d)");
  if (shape == SetShape::Triangle && p[1] != p[2])
    throw InvalidInput("fuzzy set \"" + name + "\": a triangle has b == c");
}

// The union of the supports is a union of intervals: check every breakpoint and each gap between
// consecutive breakpoints at its midpoint.
bool covers_unit_interval(const std::vector<FuzzySet>& sets) {
  std::vector<double> xs{0.0, 1.0};
  for (const auto& s : sets)
    for (double p : s.points)
      if (p >= 0.0 && p <= 1.0) xs.push_back(p);
  std::sort(xs.begin(), xs.end());
  auto covered = [&](double x) {
    for (const auto& s : sets)
      if (s.membership(x) > 0.0) return true;
    return false;
  };
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!covered(xs[i])) return false;
    if (i + 1 < xs.size() && xs[i + 1] > xs[i] && !covered(0.5 * (xs[i] + xs[i + 1]))) return false;
  }
  return true;
}

namespace {

constexpr std::size_t kMaxClips = 16;

struct Line {  // value = m*y + q; a plain aggregate so arrays of it cost nothing to declare
  double m;  // slope
  double q;  // intercept
  double at(double y) const noexcept { return m * y + q; }
};

// The clipped set min(h, trap(a,b,c,d)) is h * trap(a, a + h(b - a), d - h(d - c), d): a rising line on
// (a, b), the constant h on [b, c], a falling line on (c, d). The lines are precomputed once.
struct Trap {
  double a, b, c, d, h;
  Line rise, fall;
  Line piece(double mid) const noexcept {
    if (mid < b) return rise;
    if (mid <= c) return {0.0, h};
    return fall;
  }
};

inline Trap make_trap(const FuzzySet& set, double h) noexcept {
  const auto& [a, b, c, d] = set.points;
  Trap t{a, a + h * (b - a), d - h * (d - c), d, h, {0.0, 0.0}, {0.0, 0.0}};
  if (t.b > t.a) {
    const double m = h / (t.b - t.a);
    t.rise = {m, -m * t.a};
  }
  if (t.d > t.c) {
    const double m = -h / (t.d - t.c);
    t.fall = {m, -m * t.d};
  }
  return t;
}

// Closed form for one clipped trapezoid: split into rising triangle, rectangle, falling triangle.
inline CentreOfArea single_trap(const Trap& t) noexcept {
  const double a1 = 0.5 * (t.b - t.a) * t.h, a2 = (t.c - t.b) * t.h, a3 = 0.5 * (t.d - t.c) * t.h;
  const double m1 = a1 * (t.a + 2.0 * t.b) / 3.0, m2 = a2 * 0.5 * (t.b + t.c),
               m3 = a3 * (2.0 * t.c + t.d) / 3.0;
  const double area = a1 + a2 + a3;
  return {(m1 + m2 + m3) / area, area};
}

// ∫ over [x0, x1] of the upper envelope of `lines` (k ≥ 1), adding area and first moment.
void integrate_envelope(const Line* lines, std::size_t k, double x0, double x1, double& area,
                        double& moment) noexcept {
  // Start with the line that is highest at x0 (ties: larger slope, which stays highest after x0).
  std::size_t cur = 0;
  for (std::size_t j = 1; j < k; ++j) {
    double vj = lines[j].at(x0), vc = lines[cur].at(x0);
    if (vj > vc || (vj == vc && lines[j].m > lines[cur].m)) cur = j;
  }
  double x = x0;
  while (x < x1) {
    double next_x = x1;
    std::size_t next = cur;
    for (std::size_t j = 0; j < k; ++j) {
      if (lines[j].m <= lines[cur].m) continue;
      double xc = (lines[cur].q - lines[j].q) / (lines[j].m - lines[cur].m);
      if (xc < next_x || (xc == next_x && next != cur && lines[j].m > lines[next].m)) {
        if (xc >= x) {
          next_x = xc;
          next = j;
        } else {
          // Already above cur at x (should not happen after choosing the max); take it now.
          next_x = x;
          next = j;
        }
      }
    }
    if (next_x > x) {
      const double v0 = lines[cur].at(x), v1 = lines[cur].at(next_x), w = next_x - x;
      area += 0.5 * w * (v0 + v1);
      moment += w / 6.0 * (x * (2.0 * v0 + v1) + next_x * (v0 + 2.0 * v1));
    }
    x = next_x;
    if (next == cur) break;
    cur = next;
  }
}

// ∫ of a linear piece over [x0, x1] (exact: trapezoid rule for the area, Simpson for the moment).
inline void add_linear(const Line& l, double x0, double x1, double sign, double& area,
                       double& moment) noexcept {
  const double v0 = l.at(x0), v1 = l.at(x1), w = x1 - x0;
  area += sign * 0.5 * w * (v0 + v1);
  moment += sign * w / 6.0 * (x0 * (2.0 * v0 + v1) + x1 * (v0 + 2.0 * v1));
}

// Two sets, the common case (two adjacent input sets fire): ∫max(f, g) = ∫f + ∫g − ∫min(f, g), and the
// minimum is non-zero only where both supports overlap, so only that stretch needs splitting.
CentreOfArea two_traps(const Trap& f, const Trap& g) noexcept {
  const CentreOfArea cf = single_trap(f), cg = single_trap(g);
  double area = cf.area + cg.area, moment = cf.centroid * cf.area + cg.centroid * cg.area;
  const double lo = std::max(f.a, g.a), hi = std::min(f.d, g.d);
  if (hi > lo) {
    double xs[6] = {lo, 0, 0, 0, 0, 0};
    std::size_t nx = 1;
    for (double x : {f.b, f.c, g.b, g.c})
      if (x > lo && x < hi) xs[nx++] = x;
    xs[nx++] = hi;
    for (std::size_t i = 2; i + 1 < nx; ++i)  // insertion sort of the (at most 4) interior points
      for (std::size_t j = i; j > 1 && xs[j - 1] > xs[j]; --j) std::swap(xs[j - 1], xs[j]);
    for (std::size_t i = 0; i + 1 < nx; ++i) {
      const double x0 = xs[i], x1 = xs[i + 1];
      if (!(x1 > x0)) continue;
      const double mid = 0.5 * (x0 + x1);
      const Line lf = f.piece(mid), lg = g.piece(mid);
      // Lower of the two lines, split at their crossing if it lies inside.
      const double d0 = lf.at(x0) - lg.at(x0), d1 = lf.at(x1) - lg.at(x1);
      if ((d0 > 0.0 && d1 < 0.0) || (d0 < 0.0 && d1 > 0.0)) {
        const double xc = x0 + (x1 - x0) * d0 / (d0 - d1);
        add_linear(d0 < 0.0 ? lf : lg, x0, xc, -1.0, area, moment);
        add_linear(d0 < 0.0 ? lg : lf, xc, x1, -1.0, area, moment);
      } else {
        add_linear((d0 + d1) <= 0.0 ? lf : lg, x0, x1, -1.0, area, moment);
      }
    }
  }
  CentreOfArea out;
  out.area = area;
  out.centroid = area > 0.0 ? moment / area : std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace

CentreOfArea centre_of_area(const ClippedSet* clips, std::size_t count) noexcept {
  // Fast paths for one and two activated sets (the usual case: one or two input sets fire).
  std::size_t first = count, second = count, active = 0;
  for (std::size_t i = 0; i < count; ++i)
    if (clips[i].height > 0.0) {
      if (active == 0) first = i; else if (active == 1) second = i;
      ++active;
    }
  if (active == 1) return single_trap(make_trap(*clips[first].set, std::min(clips[first].height, 1.0)));
  if (active == 2)
    return two_traps(make_trap(*clips[first].set, std::min(clips[first].height, 1.0)),
                     make_trap(*clips[second].set, std::min(clips[second].height, 1.0)));
  Trap traps[kMaxClips];
  std::size_t n = 0;
  double xs[4 * kMaxClips];
  std::size_t nx = 0;
  for (std::size_t i = 0; i < count && n < kMaxClips; ++i) {
    const double h = std::min(clips[i].height, 1.0);
    if (!(h > 0.0)) continue;
    const Trap t = make_trap(*clips[i].set, h);
    traps[n++] = t;
    xs[nx++] = t.a;
    xs[nx++] = t.b;
    xs[nx++] = t.c;
    xs[nx++] = t.d;
  }
  CentreOfArea out;
  if (n == 0) {
    out.centroid = std::numeric_limits<double>::quiet_NaN();
    return out;
  }
  // Insertion sort: at most 64 breakpoints, usually 8.
  for (std::size_t i = 1; i < nx; ++i) {
    double v = xs[i];
    std::size_t j = i;
    while (j > 0 && xs[j - 1] > v) {
      xs[j] = xs[j - 1];
      --j;
    }
    xs[j] = v;
  }
  double area = 0.0, moment = 0.0;
  Line lines[kMaxClips];
  for (std::size_t i = 0; i + 1 < nx; ++i) {
    const double x0 = xs[i], x1 = xs[i + 1];
    if (!(x1 > x0)) continue;
    const double mid = 0.5 * (x0 + x1);
    std::size_t k = 0;
    for (std::size_t t = 0; t < n; ++t)
      if (mid > traps[t].a && mid < traps[t].d) lines[k++] = traps[t].piece(mid);
    if (k == 0) continue;  // a gap between sets: the aggregate is 0 there
    if (k == 1) {
      const double v0 = lines[0].at(x0), v1 = lines[0].at(x1), w = x1 - x0;
      area += 0.5 * w * (v0 + v1);
      moment += w / 6.0 * (x0 * (2.0 * v0 + v1) + x1 * (v0 + 2.0 * v1));
      continue;
    }
    integrate_envelope(lines, k, x0, x1, area, moment);
  }
  out.area = area;
  out.centroid = area > 0.0 ? moment / area : std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace emoface::fuzzyexpr
