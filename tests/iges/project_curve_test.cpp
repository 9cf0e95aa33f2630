// Trim curves given in model space become (u, v) polylines by projection onto their surface.
#include "iges/project_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace hm {
namespace {

// A quarter cylinder of radius 2 about the x axis, u along x in [0, 4], v the angle: degree 1 in
// u, rational degree 2 in v (exact circle).
NurbsSurface quarter_cylinder() {
  NurbsSurface s;
  s.degree_u = 1;
  s.degree_v = 2;
  s.count_u = 2;
  s.count_v = 3;
  s.knots_u = {0, 0, 1, 1};
  s.knots_v = {0, 0, 0, 1, 1, 1};
  const double w = std::sqrt(0.5);
  for (int j = 0; j < 3; ++j) {
    const Vec3d yz = j == 0 ? Vec3d{0, 2, 0} : (j == 1 ? Vec3d{0, 2, 2} : Vec3d{0, 0, 2});
    for (int i = 0; i < 2; ++i) {
      s.points.push_back(Vec3d{4.0 * i, 0, 0} + yz);
      s.weights.push_back(j == 1 ? w : 1.0);
    }
  }
  return s;
}

// The line from (0.5, y0, z0) to (3.5, y1, z1).
NurbsCurve line(const Vec3d& a, const Vec3d& b) {
  NurbsCurve c;
  c.degree = 1;
  c.knots = {0, 0, 1, 1};
  c.points = {a, b};
  c.weights = {1, 1};
  c.t0 = 0;
  c.t1 = 1;
  return c;
}

// Largest distance between the (u, v) polyline mapped through the surface and the curve.
double deviation(const NurbsSurface& s, const NurbsCurve& uv, const NurbsCurve& c) {
  double e = 0;
  for (int k = 0; k <= 400; ++k) {
    const double t = uv.t0 + (uv.t1 - uv.t0) * k / 400;
    const Vec3d p = evaluate(uv, t);
    const Vec3d on_s = evaluate(s, p.x, p.y);
    // The matching curve point: the closest of a fine sampling.
    double best = 1e300;
    for (int m = 0; m <= 2000; ++m) best = std::min(best, norm(evaluate(c, m / 2000.0) - on_s));
    e = std::max(e, best);
  }
  return e;
}

TEST(ProjectCurve, CurveOnTheSurfaceIsFollowedToTolerance) {
  const NurbsSurface s = quarter_cylinder();
  // A helix-like arc on the cylinder: x from 0.5 to 3.5 while the angle turns 80 degrees.
  NurbsCurve c;
  c.degree = 1;
  for (int k = 0; k <= 64; ++k) {
    const double t = k / 64.0;
    const double a = (5 + 80 * t) * std::numbers::pi / 180;
    c.points.push_back({0.5 + 3 * t, 2 * std::cos(a), 2 * std::sin(a)});
    c.weights.push_back(1);
  }
  c.knots.push_back(0);
  for (int k = 0; k <= 64; ++k) c.knots.push_back(k / 64.0);
  c.knots.push_back(1);
  c.t0 = 0;
  c.t1 = 1;
  double dist = 0;
  std::uint64_t budget = 100000;
  const NurbsCurve uv = iges::project_to_uv(s, c, 1e-4, dist, budget);
  EXPECT_LT(dist, 1e-3);  // the curve's points are on the surface, up to its own chords
  EXPECT_GT(budget, 0u);
  EXPECT_LT(deviation(s, uv, c), 2e-3);
}

// A curve that lies well off its surface (a broken file) keeps its offset along the way. That
// must not look like a curve leaving its polyline everywhere: the refinement would split every
// segment to full depth, with a global search at each sample. That took seconds per curve, and
// the fuzzer's budget was spent on one file.
TEST(ProjectCurve, CurveOffTheSurfaceCostsNoMoreThanOneOnIt) {
  const NurbsSurface s = quarter_cylinder();
  // Parallel to the axis at radius 5: 3 m off the surface, projecting onto the line at 45 deg.
  const double r = 5 * std::sqrt(0.5);
  const NurbsCurve c = line({0.5, r, r}, {3.5, r, r});
  double dist = 0;
  std::uint64_t budget = 100000;
  const NurbsCurve uv = iges::project_to_uv(s, c, 1e-4, dist, budget);
  EXPECT_NEAR(dist, 3.0, 1e-6);
  const std::uint64_t used = 100000 - budget;
  EXPECT_LT(used, 20u);  // the 5 samples of one span; no refinement
  // Every sample projects to the 45-degree line of the cylinder.
  for (const Vec3d& p : uv.points) {
    const Vec3d q = evaluate(s, p.x, p.y);
    EXPECT_NEAR(q.y, q.z, 1e-6);
  }
}

}  // namespace
}  // namespace hm
