// Curves: evaluation, exact constructors and chord-bounded sampling.
#include "nurbs/nurbs_curve.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>

#include "core/error.h"

namespace hm {
namespace {

double distance_to_polyline(const Vec3d& p, const std::vector<Vec3d>& poly) {
  double best = INFINITY;
  for (std::size_t i = 0; i + 1 < poly.size(); ++i) {
    const Vec3d ab = poly[i + 1] - poly[i];
    const double len2 = squared_norm(ab);
    const double t = len2 > 0 ? std::clamp(dot(p - poly[i], ab) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, norm(p - (poly[i] + t * ab)));
  }
  return best;
}

TEST(NurbsCurve, LineAndPolylineAreExact) {
  const NurbsCurve line = make_line({1, 2, 3}, {4, 6, 3});
  validate_curve(line);
  Vec3d p, dp;
  evaluate_derivs(line, 0.25, p, dp);
  EXPECT_NEAR(p.x, 1.75, 1e-15);
  EXPECT_NEAR(p.y, 3.0, 1e-15);
  EXPECT_NEAR(dp.x, 3.0, 1e-14);
  EXPECT_NEAR(dp.y, 4.0, 1e-14);
  const NurbsCurve poly = make_polyline({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  validate_curve(poly);
  EXPECT_EQ(poly.t1, 3.0);
  const Vec3d at = evaluate(poly, 1.5);
  EXPECT_NEAR(at.x, 1.0, 1e-15);
  EXPECT_NEAR(at.y, 0.5, 1e-15);
  // The end is the last point, from inside the last span.
  EXPECT_EQ(evaluate(poly, 3.0), (Vec3d{0, 1, 0}));
  // Degree 1: sampling returns exactly the vertices.
  EXPECT_EQ(sample_curve(poly, 1e-9).size(), 4u);
  EXPECT_THROW(make_polyline({{0, 0, 0}}), GeometryError);
}

TEST(NurbsCurve, CircularArcIsExactWithQuarterPieces) {
  const Vec3d c{1, -2, 0.5};
  const double r = 1.7;
  for (const double sweep_deg : {30.0, 90.0, 135.0, 270.0, 359.0}) {
    const double a0 = 0.3;
    const double a1 = a0 + sweep_deg * std::numbers::pi / 180;
    const Vec3d a{c.x + r * std::cos(a0), c.y + r * std::sin(a0), c.z};
    const Vec3d b{c.x + r * std::cos(a1), c.y + r * std::sin(a1), c.z};
    const NurbsCurve arc = make_circular_arc(c, a, b);
    validate_curve(arc);
    const int pieces = static_cast<int>(std::ceil(sweep_deg / 90.0 - 1e-9));
    EXPECT_EQ(arc.count(), 2 * pieces + 1) << sweep_deg;
    EXPECT_EQ(evaluate(arc, arc.t0), a);
    EXPECT_EQ(evaluate(arc, arc.t1), b);
    double prev_angle = a0;
    for (int k = 0; k <= 200; ++k) {
      const Vec3d p = evaluate(arc, k / 200.0);
      EXPECT_NEAR(std::hypot(p.x - c.x, p.y - c.y), r, 1e-14 * r);
      EXPECT_NEAR(p.z, c.z, 1e-15);
      // Counter-clockwise: the unwrapped angle grows.
      double ang = std::atan2(p.y - c.y, p.x - c.x);
      while (ang < prev_angle - 1e-12) ang += 2 * std::numbers::pi;
      EXPECT_GE(ang, prev_angle - 1e-12);
      prev_angle = ang;
    }
  }
  // a == b: the full circle.
  const NurbsCurve full = make_circular_arc({0, 0, 0}, {2, 0, 0}, {2, 0, 0});
  EXPECT_EQ(full.count(), 9);
  const Vec3d half = evaluate(full, 0.5);
  EXPECT_NEAR(half.x, -2.0, 1e-14);
  EXPECT_NEAR(half.y, 0.0, 1e-14);
  EXPECT_THROW(make_circular_arc({0, 0, 0}, {0, 0, 0}, {1, 0, 0}), GeometryError);
}

TEST(NurbsCurve, DerivativeMatchesCentralDifference) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(-1, 1), w(0.5, 2);
  NurbsCurve c;
  c.degree = 3;
  for (int i = 0; i < 7; ++i) {
    c.points.push_back({x(rng), x(rng), x(rng)});
    c.weights.push_back(w(rng));
  }
  c.knots = {0, 0, 0, 0, 0.2, 0.5, 0.7, 1, 1, 1, 1};
  validate_curve(c);
  for (double t = 0.05; t < 1; t += 0.1) {
    Vec3d p, dp;
    evaluate_derivs(c, t, p, dp);
    const Vec3d fd = (evaluate(c, t + 1e-6) - evaluate(c, t - 1e-6)) / 2e-6;
    EXPECT_LT(norm(fd - dp), 1e-6 * (1 + norm(dp)));
  }
}

TEST(NurbsCurve, SampleCurveHoldsItsChordBound) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> x(-1, 1);
  NurbsCurve wavy;
  wavy.degree = 3;
  for (int i = 0; i < 9; ++i) {
    wavy.points.push_back({double(i), 3 * x(rng), x(rng)});
    wavy.weights.push_back(1.0 + 0.5 * (i % 2));
  }
  wavy.knots = {0, 0, 0, 0, 0.1, 0.3, 0.35, 0.6, 0.8, 1, 1, 1, 1};
  wavy.t0 = 0;
  wavy.t1 = 1;
  const NurbsCurve arc = make_circular_arc({0, 0, 0}, {1, 0, 0}, {0, -1, 0});
  for (const NurbsCurve* c : {&std::as_const(wavy), &arc}) {
    for (const double tol : {1e-2, 1e-3, 1e-5}) {
      const std::vector<Vec3d> poly = sample_curve(*c, tol, 3);
      ASSERT_GE(poly.size(), 4u);
      EXPECT_EQ(poly.front(), evaluate(*c, c->t0));
      EXPECT_EQ(poly.back(), evaluate(*c, c->t1));
      double worst = 0;
      for (int k = 0; k <= 2000; ++k) {
        const double t = c->t0 + (c->t1 - c->t0) * k / 2000.0;
        worst = std::max(worst, distance_to_polyline(evaluate(*c, t), poly));
      }
      EXPECT_LE(worst, tol) << "tol " << tol << " points " << poly.size();
    }
    // Deterministic.
    EXPECT_EQ(sample_curve(*c, 1e-5), sample_curve(*c, 1e-5));
  }
  EXPECT_THROW(sample_curve(arc, 0.0), GeometryError);
}

TEST(NurbsCurve, ValidateRejectsBadCurves) {
  NurbsCurve c = make_line({0, 0, 0}, {1, 0, 0});
  c.weights[1] = 0;
  EXPECT_THROW(validate_curve(c), GeometryError);
  c = make_line({0, 0, 0}, {1, 0, 0});
  c.knots = {0, 1, 0.5, 1};
  EXPECT_THROW(validate_curve(c), GeometryError);
  c = make_line({0, 0, 0}, {1, 0, 0});
  c.degree = 2;
  EXPECT_THROW(validate_curve(c), GeometryError);
}

}  // namespace
}  // namespace hm
