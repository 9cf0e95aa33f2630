// Evaluation, derivatives, normals, validation and the batched kernel of NURBS surfaces.
#include "nurbs/nurbs_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "core/error.h"
#include "kernels/evaluate_nurbs.h"
#include "nurbs/basis.h"
#include "nurbs/evaluate_grid.h"
#include "nurbs_test_shapes.h"
#include "support/test_support.h"

namespace hm {
namespace {

using test::kHalfSqrt2;

void expect_near(const Vec3d& a, const Vec3d& b, double tol, const std::string& what = "") {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

TEST(NurbsSurface, BilinearPointsAndDerivativesAreExact) {
  const NurbsSurface s = test::bilinear();
  for (const double u : {0.0, 0.25, 0.5, 0.8, 1.0}) {
    for (const double v : {0.0, 0.1, 0.6, 1.0}) {
      const SurfaceDerivs d = evaluate_derivs(s, u, v, 2);
      expect_near(d.p, {2 * u, 3 * v, u * v}, 1e-15);
      expect_near(d.su, {2, 0, v}, 1e-14);
      expect_near(d.sv, {0, 3, u}, 1e-14);
      expect_near(d.suu, {0, 0, 0}, 1e-14);
      expect_near(d.suv, {0, 0, 1}, 1e-14);
      expect_near(d.svv, {0, 0, 0}, 1e-14);
      expect_near(evaluate(s, u, v), d.p, 0);
    }
  }
}

// Quadratic Bernstein polynomials and their first two derivatives.
double bern(int i, double t) {
  const double b[3] = {(1 - t) * (1 - t), 2 * t * (1 - t), t * t};
  return b[i];
}
double bern1(int i, double t) {
  const double b[3] = {-2 * (1 - t), 2 - 4 * t, 2 * t};
  return b[i];
}
double bern2(int i, double) {
  const double b[3] = {2, -4, 2};
  return b[i];
}

TEST(NurbsSurface, BiquadraticBezierMatchesBernsteinPolynomials) {
  const double c[3][3] = {{0.3, -1.2, 0.7}, {2.0, 0.5, -0.4}, {1.1, 0.9, -2.2}};  // c[j][i]
  std::vector<Vec3d> pts;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) pts.push_back({double(i), double(j), c[j][i]});
  }
  const NurbsSurface s =
      test::make_surface(2, 2, 3, 3, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1}, pts);
  for (const double u : {0.0, 0.3, 0.5, 0.9, 1.0}) {
    for (const double v : {0.0, 0.2, 0.75, 1.0}) {
      double z = 0, zu = 0, zv = 0, zuu = 0, zuv = 0, zvv = 0;
      for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
          z += c[j][i] * bern(i, u) * bern(j, v);
          zu += c[j][i] * bern1(i, u) * bern(j, v);
          zv += c[j][i] * bern(i, u) * bern1(j, v);
          zuu += c[j][i] * bern2(i, u) * bern(j, v);
          zuv += c[j][i] * bern1(i, u) * bern1(j, v);
          zvv += c[j][i] * bern(i, u) * bern2(j, v);
        }
      }
      const SurfaceDerivs d = evaluate_derivs(s, u, v, 2);
      expect_near(d.p, {2 * u, 2 * v, z}, 1e-14);
      expect_near(d.su, {2, 0, zu}, 1e-13);
      expect_near(d.sv, {0, 2, zv}, 1e-13);
      expect_near(d.suu, {0, 0, zuu}, 1e-12);
      expect_near(d.suv, {0, 0, zuv}, 1e-12);
      expect_near(d.svv, {0, 0, zvv}, 1e-12);
    }
  }
}

TEST(NurbsSurface, QuarterCylinderIsExactAndNormalsAreRadial) {
  const double r = 2.5, h = 4.0;
  const NurbsSurface s = test::quarter_cylinder(r, h);
  EXPECT_TRUE(s.rational());
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 4; ++j) {
      const double u = i / 20.0, v = j / 4.0;
      const Vec3d p = evaluate(s, u, v);
      EXPECT_NEAR(std::hypot(p.x, p.y), r, 1e-14 * r);
      EXPECT_NEAR(p.z, v * h, 1e-14);
      const Vec3d n = normal(s, u, v);
      expect_near(n, Vec3d{p.x / r, p.y / r, 0}, 1e-14);
    }
  }
}

TEST(NurbsSurface, DerivativesMatchCentralDifferencesOnRationalBicubic) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    const NurbsSurface s = test::random_bicubic(seed);
    std::mt19937 rng(seed + 100);
    std::uniform_real_distribution<double> t(0.02, 0.98);
    for (int k = 0; k < 20; ++k) {
      const double u = t(rng), v = t(rng);
      const double h = 1e-5;
      const SurfaceDerivs d = evaluate_derivs(s, u, v, 2);
      const SurfaceDerivs du_p = evaluate_derivs(s, u + h, v, 1);
      const SurfaceDerivs du_m = evaluate_derivs(s, u - h, v, 1);
      const SurfaceDerivs dv_p = evaluate_derivs(s, u, v + h, 1);
      const SurfaceDerivs dv_m = evaluate_derivs(s, u, v - h, 1);
      const double scale = 1.0 + norm(d.su) + norm(d.sv);
      expect_near(d.su, (du_p.p - du_m.p) / (2 * h), 1e-6 * scale, "su");
      expect_near(d.sv, (dv_p.p - dv_m.p) / (2 * h), 1e-6 * scale, "sv");
      const double scale2 = 1.0 + norm(d.suu) + norm(d.suv) + norm(d.svv);
      expect_near(d.suu, (du_p.su - du_m.su) / (2 * h), 1e-5 * scale2, "suu");
      expect_near(d.suv, (dv_p.su - dv_m.su) / (2 * h), 1e-5 * scale2, "suv");
      expect_near(d.suv, (du_p.sv - du_m.sv) / (2 * h), 1e-5 * scale2, "svu");
      expect_near(d.svv, (dv_p.sv - dv_m.sv) / (2 * h), 1e-5 * scale2, "svv");
    }
  }
}

TEST(NurbsSurface, SpanBoundariesAndDomainEndsMatchCoxDeBoor) {
  const NurbsSurface s = test::random_bicubic(7);
  std::vector<double> us = span_breaks_u(s);
  std::vector<double> vs = span_breaks_v(s);
  ASSERT_EQ(us, (std::vector<double>{0, 0.3, 0.6, 1}));
  ASSERT_EQ(vs, (std::vector<double>{0, 0.45, 1}));
  us.insert(us.end(), {0.1, 0.77, std::nextafter(1.0, 0.0)});
  vs.insert(vs.end(), {0.2, std::nextafter(0.45, 0.0)});
  for (const double u : us) {
    for (const double v : vs) {
      const Vec3d p = evaluate(s, u, v);
      ASSERT_TRUE(is_finite(p));
      expect_near(p, test::reference_point(s, u, v), 1e-13);
    }
  }
  // The corners of a clamped surface are its corner control points.
  expect_near(evaluate(s, 1.0, 1.0), s.point(s.count_u - 1, s.count_v - 1), 1e-14);
  expect_near(evaluate(s, 0.0, 1.0), s.point(0, s.count_v - 1), 1e-14);
  expect_near(evaluate(s, 1.0, 0.0), s.point(s.count_u - 1, 0), 1e-14);
  // Outside the domain the parameter is clamped, never read out of range.
  expect_near(evaluate(s, 1.5, -3.0), evaluate(s, 1.0, 0.0), 0);
}

TEST(NurbsSurface, NonUnitDomainScalesDerivatives) {
  NurbsSurface s = test::bilinear();
  s.knots_u = {2, 2, 5, 5};  // u = 2 + 3 t
  s.u0 = 2;
  s.u1 = 5;
  validate_surface(s);
  const SurfaceDerivs d = evaluate_derivs(s, 3.5, 0.5, 1);
  expect_near(d.p, {1.0, 1.5, 0.25}, 1e-15);
  expect_near(d.su, Vec3d{2, 0, 0.5} / 3.0, 1e-15);
}

TEST(NurbsSurface, CollapsedEdgeHasFiniteUnitNormals) {
  const double r = 3.0;
  const NurbsSurface s = test::sphere_octant(r);
  // The edge u = 1 is the pole: Sv (around the axis) vanishes there.
  const SurfaceDerivs pole = evaluate_derivs(s, 1.0, 0.3, 1);
  EXPECT_LT(norm(pole.sv), 1e-12);
  for (int j = 0; j <= 10; ++j) {
    const double v = j / 10.0;
    const Vec3d n = normal(s, 1.0, v);
    ASSERT_TRUE(is_finite(n));
    EXPECT_NEAR(norm(n), 1.0, 1e-12);
    // The octant's Su x Sv points inwards; at the pole that is -z.
    expect_near(n, {0, 0, -1}, 1e-4);
    // And the normal agrees with the radial direction everywhere else.
    const Vec3d p = evaluate(s, 0.5, v);
    expect_near(normal(s, 0.5, v), -p / r, 1e-12);
  }
  // A fully collapsed patch (a point) gives the zero vector, not NaN.
  NurbsSurface dot_patch = s;
  for (Vec3d& p : dot_patch.points) p = {1, 2, 3};
  const Vec3d n0 = normal(dot_patch, 0.5, 0.5);
  EXPECT_TRUE(is_finite(n0));
  EXPECT_EQ(norm(n0), 0.0);
}

TEST(NurbsSurface, DuplicatedControlRowHasFiniteNormals) {
  // The first two control columns coincide: Su vanishes along the whole edge u = 0, which is
  // still a regular curve (not collapsed).
  NurbsSurface s = test::random_bicubic(8, 0.3, false);
  for (int j = 0; j < s.count_v; ++j) s.points[1 + s.count_u * j] = s.point(0, j);
  for (const double v : {0.0, 0.3, 0.5, 1.0}) {
    EXPECT_LT(norm(evaluate_derivs(s, 0.0, v, 1).su), 1e-12);
    const Vec3d n = normal(s, 0.0, v);
    ASSERT_TRUE(is_finite(n));
    EXPECT_NEAR(norm(n), 1.0, 1e-12);
    EXPECT_GT(dot(n, normal(s, 1e-3, v)), 0.99);
  }
}

TEST(NurbsSurface, KnuckleFromRepeatedInteriorKnotEvaluates) {
  // Degree 2 in u with a double interior knot at 0.5: C0 crease along the middle control column.
  std::vector<Vec3d> pts;
  const double xs[5] = {0, 1, 2, 3, 4};
  const double zs[5] = {0, 0.5, 1.5, 0.5, 0};
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 5; ++i) pts.push_back({xs[i], 2.0 * j, zs[i]});
  }
  const NurbsSurface s =
      test::make_surface(2, 1, 5, 2, test::clamped_knots(2, {0.5, 0.5}, 0, 1), {0, 0, 1, 1}, pts);
  validate_surface(s);
  for (const double v : {0.0, 0.4, 1.0}) {
    const Vec3d at = evaluate(s, 0.5, v);
    expect_near(at, {2, 2 * v, 1.5}, 1e-14);
    expect_near(evaluate(s, std::nextafter(0.5, 0.0), v), at, 1e-12);
    expect_near(at, test::reference_point(s, 0.5, v), 1e-14);
    // Normals on both sides are finite and differ (a real crease).
    const Vec3d left = normal(s, 0.5 - 1e-9, v);
    const Vec3d right = normal(s, 0.5, v);
    EXPECT_NEAR(norm(left), 1.0, 1e-12);
    EXPECT_NEAR(norm(right), 1.0, 1e-12);
    EXPECT_LT(dot(left, right), 0.99);
  }
}

TEST(NurbsSurface, ValidateAcceptsGoodSurfaces) {
  EXPECT_NO_THROW(validate_surface(test::bilinear()));
  EXPECT_NO_THROW(validate_surface(test::quarter_cylinder(1, 1)));
  EXPECT_NO_THROW(validate_surface(test::random_bicubic(3)));
  EXPECT_NO_THROW(validate_surface(test::sphere_octant(2)));
}

// Runs validate_surface on a broken copy and returns the message (empty when nothing threw).
template <class F>
std::string rejection(F&& breaker) {
  NurbsSurface s = test::random_bicubic(3);
  breaker(s);
  try {
    validate_surface(s);
  } catch (const GeometryError& e) {
    return e.what();
  }
  return "";
}

TEST(NurbsSurface, ValidateRejectsMalformedSurfacesWithClearMessages) {
  EXPECT_NE(rejection([](NurbsSurface& s) {
              std::swap(s.knots_u[4], s.knots_u[5]);
            }).find("knots decrease"),
            std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) { s.weights[4] = 0; }).find("weight 4 is 0"),
            std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) { s.weights[2] = -1; }).find("weight 2 is -1"),
            std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) {
              s.weights[1] = std::numeric_limits<double>::quiet_NaN();
            }).find("weights must be positive"),
            std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) {
              s.degree_v = 5;  // 5 control rows, degree 5 needs 6
              s.knots_v.insert(s.knots_v.begin(), 2, 0.0);
            }).find("needs at least 6 control points"),
            std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) { s.knots_v.pop_back(); }).find("expected count"),
            std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) { s.points[7].y = INFINITY; }).find("not finite"),
            std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) { s.degree_u = 0; }).find("below 1"), std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) { s.u1 = 2.0; }).find("outside the knot range"),
            std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) { s.v0 = s.v1; }).find("empty"), std::string::npos);
  EXPECT_NE(rejection([](NurbsSurface& s) { s.points.pop_back(); }).find("control points"),
            std::string::npos);
  // The direction is named.
  EXPECT_NE(rejection([](NurbsSurface& s) { s.knots_v[0] = 0.9; }).find("v direction"),
            std::string::npos);
}

bool same_bits(const Vec3d& a, const Vec3d& b) { return std::memcmp(&a, &b, sizeof(Vec3d)) == 0; }

void expect_batch_equals_single(const NurbsSurface& s, int nu, int nv) {
  const SurfaceSamples g = evaluate_grid(s, nu, nv, true);
  const SurfaceSamples p = evaluate_grid(s, nu, nv, false);
  const std::vector<double> us = uniform_params(s.u0, s.u1, nu);
  const std::vector<double> vs = uniform_params(s.v0, s.v1, nv);
  std::vector<Vec2d> uv;
  for (const double v : vs) {
    for (const double u : us) uv.push_back({u, v});
  }
  const SurfaceSamples l = evaluate_uv(s, uv, true);
  ASSERT_EQ(g.positions.size(), uv.size());
  int mismatches = 0;
  for (std::size_t k = 0; k < uv.size(); ++k) {
    const Vec3d pos = evaluate(s, uv[k].x, uv[k].y);
    const Vec3d n = normal(s, uv[k].x, uv[k].y);
    mismatches += !same_bits(g.positions[k], pos) + !same_bits(p.positions[k], pos) +
                  !same_bits(l.positions[k], pos) + !same_bits(g.normals[k], n) +
                  !same_bits(l.normals[k], n);
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(NurbsKernel, BatchedEqualsSinglePointBitForBit) {
  expect_batch_equals_single(test::random_bicubic(11), 37, 23);
  expect_batch_equals_single(test::sphere_octant(2.0), 17, 9);  // pole: fallback normals
  expect_batch_equals_single(test::quarter_cylinder(1.5, 2.0), 11, 5);
  expect_batch_equals_single(test::random_bicubic(12), 100, 100);  // parallel rows
}

// The grid kernel contracts each u parameter with a v span's rows of the net once, for every v
// parameter in that span; the sums and their order are combine's, so every value must be the
// single point's to the bit. v parameters out of order make it contract the rows again.
void expect_grid_derivs_equal_single(const NurbsSurface& s, std::vector<double> us,
                                     std::vector<double> vs) {
  const kernel::SurfaceArrays a = surface_arrays(s);
  for (int order = 0; order <= 2; ++order) {
    kernel::BasisTable bu, bv;
    kernel::basis_table(a.degree_u, a.count_u, a.knots_u, us, order, bu);
    kernel::basis_table(a.degree_v, a.count_v, a.knots_v, vs, order, bv);
    const std::size_t m = order == 0 ? 1 : (order == 1 ? 3 : 6);
    std::vector<Vec3d> grid(us.size() * vs.size() * m);
    kernel::surface_grid_derivs(a, bu, bv, order, grid);
    int mismatches = 0;
    for (std::size_t j = 0; j < vs.size(); ++j) {
      for (std::size_t i = 0; i < us.size(); ++i) {
        Vec3d d[6];
        kernel::surface_derivs(a, us[i], vs[j], order, d);
        for (std::size_t k = 0; k < m; ++k) {
          mismatches += !same_bits(grid[(i + us.size() * j) * m + k], d[k]);
        }
      }
    }
    EXPECT_EQ(mismatches, 0) << "order " << order;
  }
}

TEST(NurbsKernel, GridDerivativesEqualSinglePointBitForBit) {
  const NurbsSurface cubic = test::random_bicubic(21);
  expect_grid_derivs_equal_single(cubic, uniform_params(cubic.u0, cubic.u1, 13),
                                  uniform_params(cubic.v0, cubic.v1, 11));
  std::vector<double> shuffled = uniform_params(cubic.v0, cubic.v1, 9);
  std::swap(shuffled[1], shuffled[7]);
  std::swap(shuffled[2], shuffled[5]);
  expect_grid_derivs_equal_single(cubic, uniform_params(cubic.u0, cubic.u1, 7), shuffled);
  const NurbsSurface sphere = test::sphere_octant(2.0);  // rational, degree 2: run-time degrees
  expect_grid_derivs_equal_single(sphere, uniform_params(sphere.u0, sphere.u1, 6),
                                  uniform_params(sphere.v0, sphere.v1, 5));
}

TEST(NurbsKernel, GridIsIdenticalForOneAndManyThreads) {
  const NurbsSurface s = test::random_bicubic(13);
  const SurfaceSamples many =
      hm::test::with_threads(8, [&] { return evaluate_grid(s, 120, 90, true); });
  const SurfaceSamples one =
      hm::test::with_threads(1, [&] { return evaluate_grid(s, 120, 90, true); });
  ASSERT_EQ(one.positions.size(), many.positions.size());
  EXPECT_EQ(std::memcmp(one.positions.data(), many.positions.data(),
                        one.positions.size() * sizeof(Vec3d)),
            0);
  EXPECT_EQ(
      std::memcmp(one.normals.data(), many.normals.data(), one.normals.size() * sizeof(Vec3d)), 0);
}

TEST(NurbsKernel, GridIsLaidOutUFastest) {
  const NurbsSurface s = test::bilinear();
  const std::vector<double> us{0.0, 0.5, 1.0};
  const std::vector<double> vs{0.0, 1.0};
  const SurfaceSamples g = evaluate_grid(s, us, vs);
  ASSERT_EQ(g.positions.size(), 6u);
  EXPECT_TRUE(g.normals.empty());
  expect_near(g.positions[1], {1, 0, 0}, 0);
  expect_near(g.positions[3], {0, 3, 0}, 0);
  expect_near(g.positions[5], {2, 3, 1}, 0);
}

}  // namespace
}  // namespace hm
