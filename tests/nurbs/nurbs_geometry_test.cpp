// Closest points, principal curvatures, trim loops and patch areas.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "core/error.h"
#include "nurbs/nurbs_surface.h"
#include "nurbs/patch.h"
#include "nurbs_test_shapes.h"

namespace hm {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(ClosestPoint, RecoversParametersOfSurfacePoints) {
  for (std::uint32_t seed = 1; seed <= 4; ++seed) {
    const NurbsSurface s = test::random_bicubic(seed);
    std::mt19937 rng(seed * 31);
    std::uniform_real_distribution<double> t(0.0, 1.0);
    for (int k = 0; k < 25; ++k) {
      const double u = t(rng), v = t(rng);
      const SurfaceProjection pr = closest_point(s, evaluate(s, u, v));
      EXPECT_TRUE(pr.converged);
      EXPECT_NEAR(pr.u, u, 1e-9) << "seed " << seed << " k " << k;
      EXPECT_NEAR(pr.v, v, 1e-9) << "seed " << seed << " k " << k;
      EXPECT_LT(pr.distance, 1e-12);
    }
  }
}

TEST(ClosestPoint, ProjectsOffSurfacePointsAlongTheNormal) {
  const NurbsSurface s = test::random_bicubic(21, 0.2);
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> t(0.05, 0.95), off(-0.05, 0.05);
  for (int k = 0; k < 25; ++k) {
    const double u = t(rng), v = t(rng), d = off(rng);
    const Vec3d q = evaluate(s, u, v) + d * normal(s, u, v);
    const SurfaceProjection pr = closest_point(s, q);
    EXPECT_TRUE(pr.converged);
    EXPECT_NEAR(pr.u, u, 1e-9);
    EXPECT_NEAR(pr.v, v, 1e-9);
    EXPECT_NEAR(pr.distance, std::abs(d), 1e-12);
    // With a good hint the answer is the same.
    const SurfaceProjection hinted = closest_point(s, q, u + 0.01, v - 0.01);
    EXPECT_NEAR(hinted.u, u, 1e-9);
    EXPECT_NEAR(hinted.v, v, 1e-9);
  }
}

TEST(ClosestPoint, ClampsToTheDomainAndSlidesAlongEdges) {
  const NurbsSurface s = test::flat_rectangle(4, 2);
  // Beyond the edge x = 4: the projection lies on that edge, found by 1-D Newton along it.
  const SurfaceProjection pr = closest_point(s, {5.0, 1.5, 0.7});
  EXPECT_TRUE(pr.converged);
  EXPECT_DOUBLE_EQ(pr.u, 1.0);
  EXPECT_NEAR(pr.v, 0.75, 1e-12);
  EXPECT_NEAR(pr.distance, std::hypot(1.0, 0.7), 1e-12);
  // Beyond a corner.
  const SurfaceProjection corner = closest_point(s, {-1.0, -1.0, 0.0});
  EXPECT_TRUE(corner.converged);
  EXPECT_EQ(corner.u, 0.0);
  EXPECT_EQ(corner.v, 0.0);
}

TEST(ClosestPoint, RobustAtACollapsedEdge) {
  const double r = 2.0;
  const NurbsSurface s = test::sphere_octant(r);
  // Above the pole: the nearest point is the pole (the whole edge u = 1).
  const SurfaceProjection pole = closest_point(s, {0, 0, 3.5});
  EXPECT_TRUE(std::isfinite(pole.u) && std::isfinite(pole.v));
  EXPECT_NEAR(pole.distance, 1.5, 1e-9);
  EXPECT_NEAR(pole.point.z, r, 1e-9);
  // Points near the pole project radially onto the sphere.
  for (const double v : {0.1, 0.5, 0.9}) {
    const Vec3d p = evaluate(s, 0.97, v);
    const Vec3d q = 1.3 * p;
    const SurfaceProjection pr = closest_point(s, q);
    EXPECT_TRUE(pr.converged);
    EXPECT_NEAR(pr.distance, 0.3 * r, 1e-9);
    EXPECT_NEAR(norm(pr.point - p), 0.0, 1e-8);
  }
}

TEST(Curvature, QuarterCylinder) {
  const double r = 2.5;
  const NurbsSurface s = test::quarter_cylinder(r, 3.0);
  for (const double u : {0.0, 0.3, 0.5, 1.0}) {
    for (const double v : {0.0, 0.7}) {
      const PrincipalCurvature pc = principal_curvature(s, u, v);
      // Su x Sv points outwards and the cylinder bends away from it: k = -1/R around, 0 along.
      EXPECT_NEAR(pc.k1, 0.0, 1e-13);
      EXPECT_NEAR(pc.k2, -1.0 / r, 1e-13);
      EXPECT_NEAR(std::abs(pc.d1.z), 1.0, 1e-12);  // straight direction: the axis
      EXPECT_NEAR(pc.d2.z, 0.0, 1e-12);
      EXPECT_NEAR(norm(pc.d2), 1.0, 1e-12);
    }
  }
}

TEST(Curvature, SphereSignFollowsTheNormalAndPoleIsDefined) {
  const double r = 3.0;
  const NurbsSurface s = test::sphere_octant(r);
  for (const double u : {0.1, 0.5, 0.9, 1.0}) {
    for (const double v : {0.0, 0.5, 1.0}) {
      const PrincipalCurvature pc = principal_curvature(s, u, v);
      // Su x Sv points inwards (towards the centre): the sphere bends towards it, k = +1/R.
      EXPECT_NEAR(pc.k1, 1.0 / r, 1e-7) << u << " " << v;
      EXPECT_NEAR(pc.k2, 1.0 / r, 1e-7) << u << " " << v;
      EXPECT_GT(pc.gaussian(), 0);
      EXPECT_NEAR(pc.mean(), 1.0 / r, 1e-7);
    }
  }
}

TEST(Curvature, TorusInnerSideHasNegativeGaussianCurvature) {
  const double rc = 5.0, rt = 1.5;
  const NurbsSurface s = test::torus_inner_quarter(rc, rt);
  for (const double u : {0.1, 0.5, 0.9}) {
    for (const double v : {0.2, 0.6}) {
      const Vec3d p = evaluate(s, u, v);
      const double rho = std::hypot(p.x, p.y);  // distance from the axis
      const double cos_phi = (rho - rc) / rt;   // tube angle, negative on the inner side
      const PrincipalCurvature pc = principal_curvature(s, u, v);
      const double k_tube = 1.0 / rt;
      const double k_ring = cos_phi / rho;
      EXPECT_NEAR(pc.gaussian(), k_tube * k_ring, 1e-12);
      EXPECT_LT(pc.gaussian(), 0);
      EXPECT_GT(pc.k1, 0);
      EXPECT_LT(pc.k2, 0);
      EXPECT_NEAR(std::max(std::abs(pc.k1), std::abs(pc.k2)), k_tube, 1e-12);
      EXPECT_NEAR(std::abs(dot(pc.d1, pc.d2)), 0.0, 1e-12);
    }
  }
}

Patch plain(const NurbsSurface& s) {
  Patch p;
  p.surface = s;
  return p;
}

TEST(PatchArea, FlatRectangleIsExact) {
  EXPECT_NEAR(patch_area(plain(test::flat_rectangle(3.0, 7.0))), 21.0, 1e-13);
}

TEST(PatchArea, QuarterCylinderTo1e10) {
  const double r = 2.5, h = 4.0;
  const double exact = kPi * r * h / 2;
  EXPECT_NEAR(patch_area(plain(test::quarter_cylinder(r, h))) / exact, 1.0, 1e-10);
}

TEST(PatchArea, SphereOctantWithPole) {
  const double r = 3.0;
  const double exact = 4 * kPi * r * r / 8;
  EXPECT_NEAR(patch_area(plain(test::sphere_octant(r))) / exact, 1.0, 1e-10);
}

TrimLoop square_loop(double a0, double b0, double a1, double b1, bool outer) {
  TrimLoop loop;
  loop.outer = outer;
  loop.curves_uv.push_back(make_polyline({{a0, b0, 0}, {a1, b0, 0}, {a1, b1, 0}}));
  loop.curves_uv.push_back(make_polyline({{a1, b1, 0}, {a0, b1, 0}, {a0, b0, 0}}));
  return loop;
}

TrimLoop circle_loop(double cu, double cv, double r) {
  TrimLoop loop;
  loop.outer = false;
  // Two half circles, clockwise as IGES writes holes (a reversed CCW arc set).
  loop.curves_uv.push_back(make_circular_arc({cu, cv, 0}, {cu + r, cv, 0}, {cu - r, cv, 0}));
  loop.curves_uv.push_back(make_circular_arc({cu, cv, 0}, {cu - r, cv, 0}, {cu + r, cv, 0}));
  return loop;
}

TEST(PatchArea, TrimmedSquareWithCircularHole) {
  const double side = 6.0, r = 0.3;
  const double exact = side * side * (1 - kPi * r * r);
  Patch p = plain(test::flat_rectangle(side, side));
  p.loops = {square_loop(0, 0, 1, 1, true), circle_loop(0.5, 0.5, r)};
  EXPECT_NEAR(patch_area(p) / exact, 1.0, 1e-6);
  // Without the outer loop the domain boundary is the outer loop.
  p.loops = {circle_loop(0.5, 0.5, r)};
  EXPECT_NEAR(patch_area(p) / exact, 1.0, 1e-6);
  // An off-centre hole that crosses span and cell boundaries of a curved patch.
  Patch curved = plain(test::random_bicubic(4));
  const double full = patch_area(curved);
  Patch inner = curved;
  inner.loops = {square_loop(0.31, 0.22, 0.69, 0.65, true)};
  NurbsSurface sub = curved.surface;
  sub.u0 = 0.31, sub.u1 = 0.69, sub.v0 = 0.22, sub.v1 = 0.65;
  const double sub_area = patch_area(plain(sub));
  EXPECT_NEAR(patch_area(inner) / sub_area, 1.0, 1e-10);
  Patch holed = curved;
  holed.loops = {square_loop(0.31, 0.22, 0.69, 0.65, false)};
  EXPECT_NEAR(patch_area(holed) / (full - sub_area), 1.0, 1e-10);
}

// The estimate the tessellation sizes its edges from: within its tolerance of the exact area on a
// pole, a trimmed hole and a curved patch with a hole across its spans.
TEST(PatchArea, EstimateIsWithinItsTolerance) {
  const double r = 3.0;
  const Patch octant = plain(test::sphere_octant(r));
  EXPECT_NEAR(patch_area(octant, kAreaEstimateTol) / (4 * kPi * r * r / 8), 1.0, kAreaEstimateTol);
  Patch plate = plain(test::flat_rectangle(6.0, 6.0));
  plate.loops = {square_loop(0, 0, 1, 1, true), circle_loop(0.5, 0.5, 0.3)};
  EXPECT_NEAR(patch_area(plate, kAreaEstimateTol) / patch_area(plate), 1.0, kAreaEstimateTol);
  Patch holed = plain(test::random_bicubic(4));
  holed.loops = {square_loop(0.31, 0.22, 0.69, 0.65, false)};
  EXPECT_NEAR(patch_area(holed, kAreaEstimateTol) / patch_area(holed), 1.0, kAreaEstimateTol);
  EXPECT_THROW(patch_area(holed, 0.0), InternalError);
  EXPECT_THROW(patch_area(holed, 1.0), InternalError);
}

TEST(Patch, SampleLoopsChainsCurvesWithoutDuplicateJoints) {
  Patch p = plain(test::flat_rectangle(1, 1));
  p.loops = {square_loop(0.1, 0.1, 0.9, 0.9, true), circle_loop(0.5, 0.5, 0.2)};
  const auto polys = sample_loops_uv(p, 1e-4);
  ASSERT_EQ(polys.size(), 2u);
  ASSERT_EQ(polys[0].size(), 4u);  // the square's corners, joints and closure dropped
  EXPECT_EQ(polys[0][0], (Vec2d{0.1, 0.1}));
  EXPECT_EQ(polys[0][2], (Vec2d{0.9, 0.9}));
  for (const Vec2d& q : polys[1]) EXPECT_NEAR(norm(q - Vec2d{0.5, 0.5}), 0.2, 1e-12);
  for (std::size_t i = 0; i < polys[1].size(); ++i) {
    EXPECT_GT(norm(polys[1][i] - polys[1][(i + 1) % polys[1].size()]), 1e-6);
  }
  EXPECT_TRUE(sample_loops_uv(plain(test::bilinear()), 1e-3).empty());
}

TEST(Patch, WrappingNames) {
  EXPECT_EQ(std::string(to_string(Wrapping::kPlain)), "plain");
  EXPECT_EQ(std::string(to_string(Wrapping::kTrimmed)), "trimmed");
  EXPECT_EQ(std::string(to_string(Wrapping::kFace)), "face");
}

}  // namespace
}  // namespace hm
