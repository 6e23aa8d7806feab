#pragma once
// Polynomial factors for the hot loop of the vector muscles.
//
// Profiling showed libm's cos/acos at ~60 % of a deformation, then a degree-14 Taylor cos plus an
// acos polynomial at ~30 % of the instructions. The Waters factors (thesis §2.2.3, seeds/README.md)
//   A(x) = cos((acos(x)/Ω)·π/2), x = cos α ∈ [cos Ω, 1],
//   R(D) = cos((1 − D/Rs)·π/2) on [0, Rs] and cos(((D − Rs)/(Rf − Rs))·π/2) on [Rs, Rf],
//        = g(u²), g(s) = cos(π/2·√s), u = |D − Rs|/Rs or |D − Rs|/(Rf − Rs),
//   S(e) = sin(π·e) on [0, 1] (sphincter),
// are smooth on their intervals (A is analytic in x up to x = −1, because cos(s·θ) is a function of
// θ² and acos(x)² is analytic at x = 1; g is entire), so each is replaced by one polynomial, fitted by
// interpolation at Chebyshev points (near-minimax, Trefethen, "Approximation Theory and Approximation
// Practice", ch. 8, 16). A is evaluated from cos α directly: no acos, no sqrt(1 − x); R needs no
// branch between its two pieces but the choice of 1/Rs or 1/(Rf − Rs).
// The solver measures every fit's maximum error on a dense grid when it is built and falls back to the
// exact <cmath> formulas of waters.hpp for a muscle whose fit is worse than kFitTolerance (only very
// wide zones, Ω close to π, can do that). Tested against std::cos/std::acos in solver_test.
#include <algorithm>
#include <array>
#include <cmath>
#if (defined(__SSE2__) || defined(_M_X64)) && !defined(EMOFACE_MUSCLES_NO_SIMD)  // the macro forces the scalar path
#include <emmintrin.h>
#define EMOFACE_MUSCLES_SSE2 1
#endif

namespace emoface::muscles::detail {

/// Largest accepted |fit − exact| of a dimensionless factor in [0, 1]: ≤ 1e-9·k of displacement per
/// muscle and step (1e-11 m for k = 1 cm).
inline constexpr double kFitTolerance = 5e-8;

/// p(x) = Σ c_k·t^k with t = (x − centre)·inv_half, i.e. t ∈ [−1, 1] on the fitted interval.
template <int N>
struct Poly {
  double centre;
  double inv_half;
  std::array<double, N + 1> c;
  double operator()(double x) const {
    const double t = (x - centre) * inv_half;
    double r = c[N];
    for (int k = N - 1; k >= 0; --k) r = r * t + c[k];
    return r;
  }
};

/// Interpolates f at the N+1 Chebyshev points of the first kind on [a, b] (a < b) and returns the
/// polynomial in monomial form of t (conversion is well conditioned for the small N used here).
template <int N, class F>
Poly<N> fit_chebyshev(F f, double a, double b) {
  constexpr double kPi = 3.14159265358979323846;
  std::array<double, N + 1> values{}, cheb{};
  for (int j = 0; j <= N; ++j) values[static_cast<std::size_t>(j)] = f(0.5 * (a + b) + 0.5 * (b - a) * std::cos(kPi * (j + 0.5) / (N + 1)));
  for (int k = 0; k <= N; ++k) {
    double s = 0.0;
    for (int j = 0; j <= N; ++j) s += values[static_cast<std::size_t>(j)] * std::cos(kPi * k * (j + 0.5) / (N + 1));
    cheb[static_cast<std::size_t>(k)] = (k == 0 ? 1.0 : 2.0) * s / (N + 1);
  }
  // Σ cheb_k·T_k(t) in monomials, T_{k+1} = 2t·T_k − T_{k−1}
  Poly<N> p{0.5 * (a + b), 2.0 / (b - a), {}};
  std::array<double, N + 1> t_prev{}, t_cur{}, t_next{};
  t_prev[0] = 1.0;               // T_0
  if (N >= 1) t_cur[1] = 1.0;    // T_1
  for (int k = 0; k <= N; ++k) {
    const auto& tk = k == 0 ? t_prev : t_cur;
    for (int i = 0; i <= N; ++i) p.c[static_cast<std::size_t>(i)] += cheb[static_cast<std::size_t>(k)] * tk[static_cast<std::size_t>(i)];
    if (k >= 1 && k < N) {
      for (int i = 0; i <= N; ++i) {
        t_next[static_cast<std::size_t>(i)] = (i > 0 ? 2.0 * t_cur[static_cast<std::size_t>(i - 1)] : 0.0) - t_prev[static_cast<std::size_t>(i)];
      }
      t_prev = t_cur;
      t_cur = t_next;
    }
  }
  return p;
}

/// max |p(x) − f(x)| over `samples` + 1 equally spaced points of [a, b].
template <int N, class F>
double max_fit_error(const Poly<N>& p, F f, double a, double b, int samples = 4000) {
  double worst = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const double x = a + (b - a) * i / samples;
    worst = std::max(worst, std::abs(p(x) - f(x)));
  }
  return worst;
}

/// Packed form {centre, inv_half, c0..cN} as stored in FaceSolver's muscle plans.
template <int N>
std::array<double, N + 3> pack(const Poly<N>& p) {
  std::array<double, N + 3> out{};
  out[0] = p.centre;
  out[1] = p.inv_half;
  for (int k = 0; k <= N; ++k) out[static_cast<std::size_t>(k + 2)] = p.c[static_cast<std::size_t>(k)];
  return out;
}

/// Horner evaluation of a packed polynomial (M = degree + 3 numbers).
template <std::size_t M>
inline double eval_packed(const std::array<double, M>& p, double x) {
  const double t = (x - p[0]) * p[1];
  double r = p[M - 1];
  for (std::size_t k = M - 2; k >= 2; --k) r = r * t + p[k];
  return r;
}

/// cos(π/2·√s) on s ∈ [0, 1]: the Waters radial factor as R = g(u²) with u = (Rs − D)/Rs for D <= Rs
/// and u = (D − Rs)/(Rf − Rs) beyond (both pieces of thesis §2.2.3 are cos(π/2·u)); g is entire in s.
inline double radial_of_square(double s) { return std::cos(1.5707963267948966 * std::sqrt(std::max(0.0, s))); }

/// The exact factors the polynomials replace (the same formulas as waters.cpp).
inline double angular_of_cos(double cos_alpha, double omega) {
  constexpr double kHalfPi = 1.5707963267948966;
  return std::cos(std::acos(std::min(1.0, std::max(-1.0, cos_alpha))) / omega * kHalfPi);
}

}  // namespace emoface::muscles::detail
