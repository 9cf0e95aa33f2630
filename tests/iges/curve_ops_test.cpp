// Exact curve operations used by the IGES reader: each must leave the curve's geometry unchanged.
#include "iges/curve_ops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.h"

namespace hm {
namespace {

// A rational cubic with interior knots (one double), parameter range [0, 1].
NurbsCurve sample_curve() {
  NurbsCurve c;
  c.degree = 3;
  c.knots = {0, 0, 0, 0, 0.2, 0.5, 0.5, 1, 1, 1, 1};
  c.points = {{0, 0, 0}, {1, 2, 0}, {2, -1, 1}, {3, 3, 0}, {4, 0, 2}, {5, 1, 1}, {6, 0, 0}};
  c.weights = {1, 0.5, 2, 1, 0.7, 1.5, 1};
  c.t0 = 0;
  c.t1 = 1;
  return c;
}

double max_difference(const NurbsCurve& a, const NurbsCurve& b, double t0, double t1) {
  double e = 0;
  for (int k = 0; k <= 200; ++k) {
    const double t = t0 + (t1 - t0) * k / 200;
    e = std::max(e, norm(evaluate(a, t) - evaluate(b, t)));
  }
  return e;
}

TEST(CurveOps, KnotRefinementKeepsTheCurve) {
  const NurbsCurve c = sample_curve();
  NurbsCurve r = c;
  iges::refine_knots(r, {0.1, 0.3, 0.3, 0.5, 0.75});
  EXPECT_EQ(r.count(), c.count() + 5);
  EXPECT_EQ(r.knots.size(), c.knots.size() + 5);
  EXPECT_TRUE(std::is_sorted(r.knots.begin(), r.knots.end()));
  EXPECT_LT(max_difference(c, r, 0, 1), 1e-12);
}

TEST(CurveOps, DegreeElevationKeepsTheCurve) {
  const NurbsCurve c = sample_curve();
  NurbsCurve e = c;
  ASSERT_TRUE(iges::elevate_degree(e, 5, 1000));
  EXPECT_EQ(e.degree, 5);
  EXPECT_EQ(e.knots.size(), e.points.size() + 6);
  EXPECT_LT(max_difference(c, e, 0, 1), 1e-12);
  NurbsCurve small = c;
  EXPECT_FALSE(iges::elevate_degree(small, 5, 10)) << "size limit respected";
}

TEST(CurveOps, ClampToAnInnerRangeKeepsTheCurveThere) {
  NurbsCurve c = sample_curve();
  c.t0 = 0.15;
  c.t1 = 0.8;
  NurbsCurve k = c;
  iges::clamp_to_range(k);
  EXPECT_DOUBLE_EQ(k.knots.front(), 0.15);
  EXPECT_DOUBLE_EQ(k.knots.back(), 0.8);
  EXPECT_LT(norm(k.points.front() - evaluate(c, 0.15)), 1e-12);
  EXPECT_LT(norm(k.points.back() - evaluate(c, 0.8)), 1e-12);
  EXPECT_LT(max_difference(c, k, 0.15, 0.8), 1e-12);
}

TEST(CurveOps, CompatibleCurvesShareDegreeAndKnots) {
  NurbsCurve a = sample_curve();
  NurbsCurve b;
  b.degree = 2;
  b.knots = {0, 0, 0, 0.4, 1, 1, 1};
  b.points = {{0, 5, 0}, {2, 6, 0}, {4, 5, 1}, {6, 5, 0}};
  b.weights = {1, 1, 1, 1};
  const NurbsCurve a0 = a, b0 = b;
  ASSERT_TRUE(iges::make_compatible(a, b, 1000));
  EXPECT_EQ(a.degree, b.degree);
  EXPECT_EQ(a.knots, b.knots);
  EXPECT_LT(max_difference(a0, a, 0, 1), 1e-12);
  EXPECT_LT(max_difference(b0, b, 0, 1), 1e-12);
}

// Two rails on ranges whose mapping to [0, 1] rounds ((1.7 - 0.1) / (1.7 - 0.1) is not 1): the end
// knots must still match exactly, or the union of the knot vectors inserts a knot a rounding
// error from the end, beyond the curve's domain (a heap overflow in knot refinement, found by
// the fuzzer on a ruled surface).
TEST(CurveOps, RailsOnRoundedRangesStillBecomeCompatible) {
  NurbsCurve a = sample_curve();
  for (double& k : a.knots) k = 0.1 + 1.6 * k;
  a.t0 = 0.1;
  a.t1 = 1.7;
  a.knots.back() = a.knots[a.knots.size() - 2] = a.knots[a.knots.size() - 3] = 1.7;
  NurbsCurve b;
  b.degree = 2;
  b.knots = {0.35, 0.35, 0.35, 0.41, 1.1, 1.1, 1.1};
  b.points = {{0, 5, 0}, {2, 6, 0}, {4, 5, 1}, {6, 5, 0}};
  b.weights = {1, 1, 1, 1};
  b.t0 = 0.35;
  b.t1 = 1.1;
  const NurbsCurve a0 = a, b0 = b;
  iges::reparametrize(a, 0, 1);
  iges::reparametrize(b, 0, 1);
  EXPECT_EQ(a.knots.back(), 1.0);
  EXPECT_EQ(b.knots.back(), 1.0);
  ASSERT_TRUE(iges::make_compatible(a, b, 1000));
  EXPECT_EQ(a.knots, b.knots);
  for (int k = 0; k <= 50; ++k) {
    const double t = k / 50.0;
    EXPECT_LT(norm(evaluate(a, t) - evaluate(a0, 0.1 + 1.6 * t)), 1e-12);
    EXPECT_LT(norm(evaluate(b, t) - evaluate(b0, 0.35 + 0.75 * t)), 1e-12);
  }
}

// Knot refinement checks its input instead of writing past its arrays.
TEST(CurveOps, KnotsOutsideTheDomainAreRefused) {
  NurbsCurve c = sample_curve();
  EXPECT_THROW(iges::refine_knots(c, {1.5}), GeometryError);
  EXPECT_THROW(iges::refine_knots(c, {0.6, 0.3}), GeometryError);
  EXPECT_EQ(c.count(), 7);
}

TEST(CurveOps, JoinChainsPiecesEndToEnd) {
  NurbsCurve a = sample_curve();
  NurbsCurve b;
  b.degree = 1;
  b.knots = {0, 0, 2, 2};
  b.points = {{6, 0, 0}, {6, 4, 0}};
  b.weights = {1, 1};
  b.t0 = 0;
  b.t1 = 2;
  NurbsCurve j;
  ASSERT_TRUE(iges::join_chain({a, b}, 1000, j));
  EXPECT_DOUBLE_EQ(j.t0, 0);
  EXPECT_DOUBLE_EQ(j.t1, 3);
  EXPECT_LT(max_difference(a, j, 0, 1), 1e-12);
  EXPECT_LT(norm(evaluate(j, 2.0) - Vec3d{6, 2, 0}), 1e-12);
}

TEST(CurveOps, ReverseAndReparametrize) {
  const NurbsCurve c = sample_curve();
  NurbsCurve r = c;
  iges::reverse_curve(r);
  iges::reparametrize(r, 2, 4);
  for (int k = 0; k <= 20; ++k) {
    const double t = k / 20.0;
    EXPECT_LT(norm(evaluate(r, 4 - 2 * t) - evaluate(c, t)), 1e-12);
  }
}

TEST(CurveOps, RationalArcIsExact) {
  const NurbsCurve a =
      iges::rational_arc({1, 2, 3}, {2, 0, 0}, {0, 2, 0}, 0.3, 0.3 + 1.9 * std::numbers::pi);
  EXPECT_EQ(a.points.size(), 9u);  // four segments of at most a quarter turn
  for (int k = 0; k <= 100; ++k) {
    const Vec3d p = evaluate(a, a.t0 + (a.t1 - a.t0) * k / 100);
    EXPECT_NEAR(std::hypot(p.x - 1, p.y - 2), 2, 1e-12);
    EXPECT_NEAR(p.z, 3, 1e-12);
  }
}

}  // namespace
}  // namespace hm
