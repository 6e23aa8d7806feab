#include "emoface/fuzzyexpr/fuzzy_set.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "emoface/core/errors.hpp"

namespace emoface::fuzzyexpr {
namespace {

TEST(FuzzySet, TriangleAndTrapezoidMembership) {
  auto t = FuzzySet::triangle("t", 0.0, 1.0, 3.0);
  EXPECT_DOUBLE_EQ(t.membership(-1.0), 0.0);
  EXPECT_DOUBLE_EQ(t.membership(0.5), 0.5);
  EXPECT_DOUBLE_EQ(t.membership(1.0), 1.0);
  EXPECT_DOUBLE_EQ(t.membership(2.0), 0.5);
  EXPECT_DOUBLE_EQ(t.membership(3.0), 0.0);
  auto z = FuzzySet::trapezoid("z", 0.0, 0.0, 1.0, 2.0);  // left shoulder
  EXPECT_DOUBLE_EQ(z.membership(0.0), 1.0);
  EXPECT_DOUBLE_EQ(z.membership(1.5), 0.5);
  auto r = FuzzySet::trapezoid("r", 0.0, 1.0, 2.0, 2.0);  // right shoulder
  EXPECT_DOUBLE_EQ(r.membership(2.0), 1.0);
  EXPECT_DOUBLE_EQ(r.membership(2.0000001), 0.0);
}

TEST(FuzzySet, ValidateRejectsIllFormedSets) {
  EXPECT_THROW(FuzzySet::triangle("a", 1.0, 0.5, 2.0).validate(), InvalidInput);
  EXPECT_THROW(FuzzySet::triangle("a", 1.0, 1.0, 1.0).validate(), InvalidInput);
  EXPECT_THROW(FuzzySet::triangle("a", NAN, 1.0, 2.0).validate(), InvalidInput);
  EXPECT_THROW(FuzzySet::trapezoid("a", 0.0, 1.0, INFINITY, 2.0).validate(), InvalidInput);
  FuzzySet bad = FuzzySet::trapezoid("a", 0, 1, 2, 3);
  bad.shape = SetShape::Triangle;  // b != c
  EXPECT_THROW(bad.validate(), InvalidInput);
  EXPECT_NO_THROW(FuzzySet::trapezoid("ok", 0, 0, 1, 1).validate());
}

TEST(FuzzySet, ShapeNamesRoundTrip) {
  for (auto s : {SetShape::Triangle, SetShape::Trapezoid})
    EXPECT_EQ(set_shape_from_string(to_string(s)), s);
  EXPECT_FALSE(set_shape_from_string("gauss"));
}

TEST(CoversUnitInterval, DetectsGaps) {
  std::vector<FuzzySet> ok{FuzzySet::triangle("a", -1, 0, 0.6), FuzzySet::triangle("b", 0.5, 1, 2)};
  EXPECT_TRUE(covers_unit_interval(ok));
  std::vector<FuzzySet> gap{FuzzySet::triangle("a", -1, 0, 0.5), FuzzySet::triangle("b", 0.5, 1, 2)};
  EXPECT_FALSE(covers_unit_interval(gap));  // 0.5 has membership 0 in both
  std::vector<FuzzySet> left{FuzzySet::triangle("a", 0, 0.5, 1.5)};
  EXPECT_FALSE(covers_unit_interval(left));  // 0 itself is uncovered
}

// Hand-computed centres of area.
TEST(CentreOfArea, SingleSetsClosedForm) {
  auto t = FuzzySet::triangle("t", 0.0, 1.0, 2.0);
  ClippedSet c{&t, 1.0};
  auto r = centre_of_area(&c, 1);
  EXPECT_NEAR(r.centroid, 1.0, 1e-15);
  EXPECT_NEAR(r.area, 1.0, 1e-15);
  c.height = 0.5;  // trapezoid (0, .5, 1.5, 2) of height .5: area .75
  r = centre_of_area(&c, 1);
  EXPECT_NEAR(r.centroid, 1.0, 1e-15);
  EXPECT_NEAR(r.area, 0.75, 1e-15);
  auto right = FuzzySet::triangle("r", 0.0, 0.0, 3.0);  // vertical left edge: centroid a + (d-a)/3
  ClippedSet cr{&right, 1.0};
  r = centre_of_area(&cr, 1);
  EXPECT_NEAR(r.centroid, 1.0, 1e-15);
  EXPECT_NEAR(r.area, 1.5, 1e-15);
  // Asymmetric triangle (0, 1, 4): centroid (0 + 1 + 4) / 3.
  auto a = FuzzySet::triangle("a", 0.0, 1.0, 4.0);
  ClippedSet ca{&a, 1.0};
  EXPECT_NEAR(centre_of_area(&ca, 1).centroid, 5.0 / 3.0, 1e-15);
}

TEST(CentreOfArea, TwoSetsHandComputed) {
  // VerySmall (-.25, 0, .25) and Small (0, .25, .5) both clipped at 0.5: the union is the trapezoid
  // (-.25, -.125, .375, .5) of height .5, whose centre is (-.25 + .5) / 2 = .125 and area
  // .5 * (.75 + .5) / 2 = .3125.
  auto vs = FuzzySet::triangle("vs", -0.25, 0.0, 0.25);
  auto s = FuzzySet::triangle("s", 0.0, 0.25, 0.5);
  ClippedSet c[2] = {{&vs, 0.5}, {&s, 0.5}};
  auto r = centre_of_area(c, 2);
  EXPECT_NEAR(r.centroid, 0.125, 1e-14);
  EXPECT_NEAR(r.area, 0.3125, 1e-14);
  // Asymmetric: Small (0, .23, .5) alone at height 1 has centroid (0 + .23 + .5) / 3.
  auto s23 = FuzzySet::triangle("s23", 0.0, 0.23, 0.5);
  ClippedSet one{&s23, 1.0};
  EXPECT_NEAR(centre_of_area(&one, 1).centroid, 0.73 / 3.0, 1e-15);
  // Disjoint sets: centroid is the area-weighted mean of the two centroids.
  auto far = FuzzySet::triangle("far", 10.0, 11.0, 12.0);
  ClippedSet d[2] = {{&vs, 1.0}, {&far, 1.0}};
  r = centre_of_area(d, 2);
  EXPECT_NEAR(r.centroid, (0.0 * 0.25 + 11.0 * 1.0) / 1.25, 1e-13);
}

TEST(CentreOfArea, EmptyIsNaN) {
  auto t = FuzzySet::triangle("t", 0.0, 1.0, 2.0);
  ClippedSet c{&t, 0.0};
  EXPECT_TRUE(std::isnan(centre_of_area(&c, 1).centroid));
  EXPECT_TRUE(std::isnan(centre_of_area(nullptr, 0).centroid));
}

// Independent check: the aggregate evaluated pointwise and integrated with a fine midpoint rule.
TEST(CentreOfArea, MatchesFineNumericalIntegration) {
  std::mt19937_64 gen(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 120; ++trial) {
    const int n = 1 + static_cast<int>(gen() % 5);
    std::vector<FuzzySet> sets;
    std::vector<ClippedSet> clips;
    for (int k = 0; k < n; ++k) {
      double p[4];
      for (double& v : p) v = u(gen) * 2.0 - 0.5;
      std::sort(p, p + 4);
      if (gen() % 3 == 0) p[1] = p[0];  // sometimes a vertical edge
      if (p[3] - p[0] < 1e-3) p[3] = p[0] + 0.1;
      sets.push_back(FuzzySet::trapezoid("s", p[0], p[1], p[2], p[3]));
    }
    for (int k = 0; k < n; ++k) clips.push_back({&sets[k], 0.05 + 0.95 * u(gen)});
    const auto exact = centre_of_area(clips.data(), clips.size());
    const double lo = -0.5, hi = 1.6;
    const int steps = 200000;
    const double h = (hi - lo) / steps;
    double area = 0.0, moment = 0.0;
    for (int i = 0; i < steps; ++i) {
      const double y = lo + (i + 0.5) * h;
      double mu = 0.0;
      for (const auto& c : clips) mu = std::max(mu, std::min(c.height, c.set->membership(y)));
      area += mu * h;
      moment += mu * y * h;
    }
    ASSERT_NEAR(exact.area, area, 4e-5) << "trial " << trial;
    ASSERT_NEAR(exact.centroid, moment / area, 4e-5) << "trial " << trial;
  }
}

}  // namespace
}  // namespace emoface::fuzzyexpr
