#include "emoface/motiongraph/similarity.hpp"

#include <cmath>

#include "emoface/core/errors.hpp"

namespace emoface::motiongraph {

void SimilarityOptions::validate() const {
  if (!(lambda >= 0.0) || !std::isfinite(lambda)) throw InvalidInput("similarity: lambda must be >= 0");
  if (!(still_speed >= 0.0) || !std::isfinite(still_speed))
    throw InvalidInput("similarity: still_speed must be >= 0");
}

// paper §4.2: vinfl = 1 − |V(PaLi)·V(PbLi)|, 0 for parallel or opposite, 1 at ±90°; the text's
// range [0, 1] needs unit vectors, so the velocities are normalised.
double velocity_influence(const double* va, const double* vb, int dimensions, double still_speed) {
  double aa = 0.0, bb = 0.0, ab = 0.0;
  for (int j = 0; j < dimensions; ++j) {
    aa += va[j] * va[j];
    bb += vb[j] * vb[j];
    ab += va[j] * vb[j];
  }
  const double s2 = still_speed * still_speed;
  const bool still_a = aa <= s2, still_b = bb <= s2;
  if (still_a && still_b) return 0.0;
  if (still_a || still_b) return 1.0;
  const double c = std::abs(ab) / std::sqrt(aa * bb);
  return c >= 1.0 ? 0.0 : 1.0 - c;
}

// paper §4.2, eq. (1).
double similarity(const double* pa, const double* va, const double* pb, const double* vb,
                  Eigen::Index landmark_count, int dimensions, const SimilarityOptions& options) {
  double sum = 0.0;
  for (Eigen::Index i = 0; i < landmark_count; ++i) {
    const Eigen::Index o = i * dimensions;
    double d2 = 0.0;
    for (int j = 0; j < dimensions; ++j) {
      const double d = pa[o + j] - pb[o + j];
      d2 += d * d;
    }
    const double dist = std::sqrt(d2);
    if (dist == 0.0) continue;
    const double infl =
        options.lambda == 0.0 ? 0.0
                              : velocity_influence(va + o, vb + o, dimensions, options.still_speed);
    sum += dist + options.lambda * infl * dist;
  }
  return sum;
}

double similarity(const Eigen::Ref<const Eigen::RowVectorXd>& pa,
                  const Eigen::Ref<const Eigen::RowVectorXd>& va,
                  const Eigen::Ref<const Eigen::RowVectorXd>& pb,
                  const Eigen::Ref<const Eigen::RowVectorXd>& vb, int dimensions,
                  const SimilarityOptions& options) {
  if (dimensions < 1) throw InvalidInput("similarity: dimensions must be >= 1");
  const Eigen::Index n = pa.size();
  if (pb.size() != n || va.size() != n || vb.size() != n || n % dimensions != 0)
    throw InvalidInput("similarity: poses and velocities must have equal length divisible by dimensions");
  return similarity(pa.data(), va.data(), pb.data(), vb.data(), n / dimensions, dimensions, options);
}

}  // namespace emoface::motiongraph
