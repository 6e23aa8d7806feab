#include "emoface/muscles/waters.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace emoface::muscles {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Waters, AngularFactorValues) {
  EXPECT_DOUBLE_EQ(angular_factor(0.0, 0.5), 1.0);
  EXPECT_NEAR(angular_factor(0.25, 0.5), std::cos(kPi / 4), 1e-15);  // α/Ω = ½ → cos(π/4)
  EXPECT_EQ(angular_factor(0.5, 0.5), 0.0);
  EXPECT_EQ(angular_factor(0.7, 0.5), 0.0);
  // continuous at the zone edge
  EXPECT_LT(angular_factor(0.5 - 1e-9, 0.5), 1e-8);
}

TEST(Waters, RadialFactorValuesAndContinuity) {
  const double rs = 0.02, rf = 0.05;
  EXPECT_NEAR(radial_factor(0.0, rs, rf), 0.0, 1e-15);               // cos(π/2)
  EXPECT_NEAR(radial_factor(0.01, rs, rf), std::cos(kPi / 4), 1e-15);  // 1 − D/Rs = ½
  EXPECT_DOUBLE_EQ(radial_factor(rs, rs, rf), 1.0);
  EXPECT_NEAR(radial_factor(0.035, rs, rf), std::cos(kPi / 4), 1e-15);  // (D − Rs)/(Rf − Rs) = ½
  EXPECT_NEAR(radial_factor(rf, rs, rf), 0.0, 1e-15);
  EXPECT_EQ(radial_factor(rf + 1e-9, rs, rf), 0.0);
  EXPECT_NEAR(radial_factor(rs - 1e-9, rs, rf), radial_factor(rs + 1e-9, rs, rf), 1e-6);
  EXPECT_LT(radial_factor(rf - 1e-9, rs, rf), 1e-6);
}

TEST(Waters, DisplacementAgainstHandComputedValue) {
  // v1 at origin, v2 on +x. Point p = (0.03, 0.01, 0): D = √0.001, α = atan(1/3).
  VectorMuscle m;
  m.head = {0, 0, 0};
  m.tail = {0.04, 0, 0};
  m.omega = 0.6;
  m.rs = 0.02;
  m.rf = 0.05;
  m.k = 0.01;
  const Eigen::Vector3d p(0.03, 0.01, 0.0);
  const double d = std::sqrt(0.001), alpha = std::atan(1.0 / 3.0);
  const double a = std::cos(alpha / 0.6 * kPi / 2), r = std::cos((d - 0.02) / 0.03 * kPi / 2);
  const Eigen::Vector3d expected = 0.7 * 0.01 * a * r * (-p / d);
  const Eigen::Vector3d got = vector_muscle_displacement(m, p, 0.7);
  EXPECT_NEAR((got - expected).norm(), 0.0, 1e-15);
  // numbers, for the record: |Δp| = 0.7·0.01·A·R
  EXPECT_NEAR(got.norm(), 0.7 * 0.01 * a * r, 1e-15);
  // outside: behind the head, beyond Rf, outside the angle
  EXPECT_EQ(vector_muscle_displacement(m, {-0.01, 0, 0}, 1.0).norm(), 0.0);
  EXPECT_EQ(vector_muscle_displacement(m, {0.06, 0, 0}, 1.0).norm(), 0.0);
  EXPECT_EQ(vector_muscle_displacement(m, {0.01, 0.02, 0}, 1.0).norm(), 0.0);
  EXPECT_EQ(vector_muscle_displacement(m, m.head, 1.0).norm(), 0.0);
  EXPECT_EQ(vector_muscle_displacement(m, p, 0.0).norm(), 0.0);
}

TEST(Waters, ZoneBoundariesAreContinuous) {
  VectorMuscle m;
  m.head = {0, 0, 0};
  m.tail = {0, 0.04, 0};
  m.omega = 0.5;
  m.rs = 0.02;
  m.rf = 0.05;
  // walk along a path crossing the angular edge, the Rs sphere and the Rf sphere: no jumps
  Eigen::Vector3d prev = vector_muscle_displacement(m, {0.03, 0.0, 0.0}, 1.0);
  for (int i = 1; i <= 4000; ++i) {
    const double t = i / 4000.0;
    const Eigen::Vector3d p(0.03 * std::cos(t * kPi / 2) , 0.06 * std::sin(t * kPi / 2), 0.0);
    const Eigen::Vector3d d = vector_muscle_displacement(m, p, 1.0);
    EXPECT_LT((d - prev).norm(), 2e-5) << t;
    prev = d;
  }
}

TEST(Sphincter, PullsTowardsTheCentreInsideTheEllipse) {
  const Eigen::Vector3d c(0, 0, 0);
  const Eigen::Vector2d ax(0.03, 0.02);
  const Eigen::Vector3d d = sphincter_displacement(c, ax, 0.004, {0.015, 0.0, 0.01}, 1.0);  // e = ½ → sin(π/2) = 1
  EXPECT_NEAR(d.x(), -0.004, 1e-15);
  EXPECT_EQ(d.y(), 0.0);
  EXPECT_EQ(d.z(), 0.0);
  EXPECT_EQ(sphincter_displacement(c, ax, 0.004, {0.0, 0.021, 0.0}, 1.0).norm(), 0.0);
  EXPECT_EQ(sphincter_displacement(c, ax, 0.004, c, 1.0).norm(), 0.0);
}

TEST(Wrinkles, ParabolaValues) {
  // L = 0.04, Nw = 2 → b = 0.01; peaks at l = b, 3b; zeros at 0, 2b, 4b.
  EXPECT_DOUBLE_EQ(wrinkle_function(0.01, 0.04, 2, 0.001), 0.001);
  EXPECT_DOUBLE_EQ(wrinkle_function(0.03, 0.04, 2, 0.001), 0.001);
  EXPECT_NEAR(wrinkle_function(0.02, 0.04, 2, 0.001), 0.0, 1e-18);
  EXPECT_NEAR(wrinkle_function(0.005, 0.04, 2, 0.001), 0.001 * (1 - 0.25), 1e-15);  // u = b/2
  EXPECT_NEAR(wrinkle_function(0.025, 0.04, 2, 0.001), 0.00075, 1e-15);
  EXPECT_EQ(wrinkle_function(-0.001, 0.04, 2, 0.001), 0.0);
  EXPECT_EQ(wrinkle_function(0.05, 0.04, 2, 0.001), 0.0);
  EXPECT_EQ(wrinkle_function(0.01, 0.04, 0, 0.001), 0.0);
  for (double l = 0; l <= 0.04; l += 0.0001) {
    const double f = wrinkle_function(l, 0.04, 2, 0.001);
    EXPECT_GE(f, -1e-18);
    EXPECT_LE(f, 0.001 + 1e-18);
  }
}

TEST(Wrinkles, FeetWhereTheMeshResolvesThem) {
  // L = 0.06, Nw = 3 → b = 0.01; valleys (u = 0) at l = 0.02, 0.04; a foot within 0.15·b = 1.5 mm
  // of one, not in the first or last half-period (l in (0.01, 0.05)), edges ≤ resolution·b.
  EXPECT_TRUE(wrinkle_foot(0.0205, 0.06, 3, 0.002, 0.3));  // u = 0.5 mm, edge 2 mm ≤ 3 mm
  EXPECT_TRUE(wrinkle_foot(0.0390, 0.06, 3, 0.003, 0.3));  // u = 1.9 mm > 1.85·b: before a valley
  EXPECT_FALSE(wrinkle_foot(0.0205, 0.06, 3, 0.0031, 0.3));  // edge 3.1 mm > 0.3·b
  EXPECT_TRUE(wrinkle_foot(0.0205, 0.06, 3, 0.0031, 1.0));
  EXPECT_TRUE(wrinkle_foot(0.0205, 0.06, 3, 0.0, 0.0));     // a point (edge 0) always resolves
  EXPECT_FALSE(wrinkle_foot(0.0220, 0.06, 3, 0.001, 0.3));  // u = 2 mm: on the slope
  EXPECT_FALSE(wrinkle_foot(0.0300, 0.06, 3, 0.001, 0.3));  // u = b: the crest
  EXPECT_FALSE(wrinkle_foot(0.0005, 0.06, 3, 0.001, 0.3));  // first half-period
  EXPECT_FALSE(wrinkle_foot(0.0595, 0.06, 3, 0.001, 0.3));  // last half-period
  EXPECT_FALSE(wrinkle_foot(0.0205, 0.0, 3, 0.001, 0.3));   // no band
  EXPECT_FALSE(wrinkle_foot(0.0205, 0.06, 0, 0.001, 0.3));  // no wrinkles
}

TEST(Wrinkles, BandGeometry) {
  VectorMuscle m;
  m.head = {0, 0, 0};
  m.tail = {0.04, 0, 0};
  m.omega = kPi / 3;  // cos Ω = ½
  m.rf = 0.08;
  EXPECT_NEAR(wrinkle_band_length(m), 0.75 * 0.08 * 0.5, 1e-15);  // L = ¾·Rf·cos Ω
  EXPECT_NEAR(wrinkle_coordinate(m, {0.04, 0.01, 0.0}), 0.0, 1e-15);  // on the v3 line (|v1v3| = 0.04)
  EXPECT_NEAR(wrinkle_coordinate(m, {0.01, -0.02, 0.0}), 0.03, 1e-15);
}

TEST(EyelidCoupling, ThesisRule) {
  // squeezing dominates: closing follows (read as min(1, 2·s))
  auto a = couple_eyelids(0.2, 0.3, 0.2);
  EXPECT_DOUBLE_EQ(a.closing, 0.6);
  EXPECT_DOUBLE_EQ(a.squeezing, 0.3);
  EXPECT_DOUBLE_EQ(couple_eyelids(0.0, 0.9, 0.0).closing, 1.0);
  // one eye closing alone: squeezing = ½ closing
  auto b = couple_eyelids(0.8, 0.1, 0.0);
  EXPECT_DOUBLE_EQ(b.closing, 0.8);
  EXPECT_DOUBLE_EQ(b.squeezing, 0.4);
  // both eyes closing: unchanged
  auto c = couple_eyelids(0.8, 0.1, 0.8);
  EXPECT_DOUBLE_EQ(c.squeezing, 0.1);
  auto z = couple_eyelids(0.0, 0.0, 0.0);
  EXPECT_EQ(z.closing, 0.0);
  EXPECT_EQ(z.squeezing, 0.0);
}

TEST(Gaze, EllipticalLimit) {
  const Eigen::Vector2d in = limit_gaze(0.2, 0.1, 0.5, 0.4);
  EXPECT_EQ(in, Eigen::Vector2d(0.2, 0.1));
  const Eigen::Vector2d out = limit_gaze(1.0, 0.0, 0.5, 0.4);
  EXPECT_NEAR(out.x(), 0.5, 1e-15);
  const Eigen::Vector2d diag = limit_gaze(1.0, 1.0, 0.5, 0.4);
  EXPECT_NEAR(std::pow(diag.x() / 0.5, 2) + std::pow(diag.y() / 0.4, 2), 1.0, 1e-12);
  EXPECT_NEAR(diag.x() / diag.y(), 1.0, 1e-12);  // direction kept
}

}  // namespace
}  // namespace emoface::muscles
