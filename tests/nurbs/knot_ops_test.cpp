// Exact knot operations: insertion, splitting, extraction and reversal leave the surface as it was.
#include "nurbs/knot_ops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.h"

namespace hm {
namespace {

// A rational bicubic x biquadratic surface with uneven knots, a wavy net and varied weights.
NurbsSurface wavy_surface() {
  NurbsSurface s;
  s.degree_u = 3;
  s.degree_v = 2;
  s.count_u = 7;
  s.count_v = 5;
  s.knots_u = {0, 0, 0, 0, 0.2, 0.45, 0.7, 1, 1, 1, 1};
  s.knots_v = {0, 0, 0, 0.3, 0.6, 1, 1, 1};
  for (int j = 0; j < s.count_v; ++j) {
    for (int i = 0; i < s.count_u; ++i) {
      s.points.push_back({1.5 * i + 0.3 * std::sin(j), 2.0 * j + 0.2 * std::cos(i),
                          std::sin(0.9 * i) * std::cos(0.7 * j)});
      s.weights.push_back(1.0 + 0.3 * std::sin(1.3 * i + 0.4 * j) * std::sin(1.3 * i + 0.4 * j));
    }
  }
  return s;
}

// Max distance between a and b over random points of b's domain.
double max_difference(const NurbsSurface& a, const NurbsSurface& b, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0;
  for (int k = 0; k < 400; ++k) {
    const double u = b.u0 + unit(rng) * (b.u1 - b.u0), v = b.v0 + unit(rng) * (b.v1 - b.v0);
    worst = std::max(worst, norm(evaluate(a, u, v) - evaluate(b, u, v)));
  }
  return worst;
}

TEST(KnotOps, InsertionInUAndVLeavesTheSurfaceUnchanged) {
  const NurbsSurface s = wavy_surface();
  for (double t : {0.1, 0.2, 0.5, 0.93}) {
    for (int times = 1; times <= 3; ++times) {
      const NurbsSurface r = insert_knot_u(s, t, times);
      EXPECT_EQ(r.count_u, s.count_u + times);
      EXPECT_EQ(knot_multiplicity(r.knots_u, t), knot_multiplicity(s.knots_u, t) + times);
      EXPECT_NO_THROW(validate_surface(r));
      EXPECT_LT(max_difference(s, r, 11), 1e-12) << t << " x" << times;
    }
    const NurbsSurface r = insert_knot_v(s, t, 2);
    EXPECT_EQ(r.count_v, s.count_v + 2);
    EXPECT_EQ(r.count_u, s.count_u);
    EXPECT_LT(max_difference(s, r, 12), 1e-12) << t;
  }
}

TEST(KnotOps, FullMultiplicityRepeatsAColumn) {
  const NurbsSurface s = wavy_surface();
  const NurbsSurface r = insert_knot_u(s, 0.55, s.degree_u + 1);
  EXPECT_LT(max_difference(s, r, 13), 1e-12);
  int repeated = 0;
  for (int i = 0; i + 1 < r.count_u; ++i) {
    bool same = true;
    for (int j = 0; j < r.count_v; ++j) {
      same = same && r.point(i, j) == r.point(i + 1, j) && r.weight(i, j) == r.weight(i + 1, j);
    }
    repeated += same ? 1 : 0;
  }
  EXPECT_EQ(repeated, 1);
}

TEST(KnotOps, SplitPiecesMatchAndShareBordersBitForBit) {
  const NurbsSurface s = wavy_surface();
  const std::vector<double> bu = {0.0, 0.2, 0.33, 0.8, 1.0};
  const std::vector<NurbsSurface> cols = split_u(s, bu);
  ASSERT_EQ(cols.size(), 4u);
  for (std::size_t k = 0; k < cols.size(); ++k) {
    EXPECT_EQ(cols[k].u0, bu[k]);
    EXPECT_EQ(cols[k].u1, bu[k + 1]);
    EXPECT_NO_THROW(validate_surface(cols[k]));
    EXPECT_LT(max_difference(s, cols[k], 20 + k), 1e-12);
    if (k == 0) continue;
    for (int j = 0; j < s.count_v; ++j) {
      const Vec3d a = cols[k - 1].point(cols[k - 1].count_u - 1, j);
      const Vec3d b = cols[k].point(0, j);
      EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
    }
  }
  const std::vector<NurbsSurface> rows = split_v(cols[2], {0.0, 0.1, 0.6, 1.0});
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_LT(max_difference(s, rows[k], 30 + k), 1e-12);
  }
}

TEST(KnotOps, SubSurfaceMatchesTheOriginalOnItsDomain) {
  const NurbsSurface s = wavy_surface();
  const NurbsSurface r = extract_subsurface(s, 0.13, 0.61, 0.25, 0.9);
  EXPECT_EQ(r.u0, 0.13);
  EXPECT_EQ(r.u1, 0.61);
  EXPECT_EQ(r.v0, 0.25);
  EXPECT_EQ(r.v1, 0.9);
  EXPECT_EQ(r.knots_u.front(), 0.13);
  EXPECT_EQ(r.knots_v.back(), 0.9);
  EXPECT_LT(max_difference(s, r, 40), 1e-12);
  // Corners interpolate: a clamped sub-surface's corner control points are on the surface.
  EXPECT_LT(norm(r.point(0, 0) - evaluate(s, 0.13, 0.25)), 1e-12);
  EXPECT_LT(norm(r.point(r.count_u - 1, r.count_v - 1) - evaluate(s, 0.61, 0.9)), 1e-12);
  // A sub-surface of a sub-surface.
  const NurbsSurface q = extract_subsurface(r, 0.2, 0.3, 0.5, 0.55);
  EXPECT_LT(max_difference(s, q, 41), 1e-12);
}

// A sub-surface cut a rounding error before an interior knot (property seed 4877's overlapping
// patch) starts with a knot span about 1e-16 wide. Its derivatives at the start are those of the
// surface there, not that span's noise: the kernel evaluates on the span beside it.
TEST(KnotOps, ASpanOfRoundingWidthAtTheStartDoesNotSpoilTheDerivatives) {
  const NurbsSurface s = wavy_surface();
  for (const double knot : {0.2, 0.45, 0.7}) {
    const double ua = std::nextafter(std::nextafter(knot, 0.0), 0.0);
    const NurbsSurface r = extract_subsurface(s, ua, 0.95, 0.1, 0.8);
    ASSERT_GT(r.knots_u[r.degree_u + 1], r.knots_u[r.degree_u]);
    ASSERT_LT(r.knots_u[r.degree_u + 1] - r.knots_u[r.degree_u], 1e-15);
    for (const double v : {0.1, 0.37, 0.8}) {
      const SurfaceDerivs want = evaluate_derivs(s, ua, v, 2);
      const SurfaceDerivs got = evaluate_derivs(r, ua, v, 2);
      EXPECT_LT(norm(got.p - want.p), 1e-12) << knot << " " << v;
      EXPECT_LT(norm(got.su - want.su), 1e-9 * norm(want.su)) << knot << " " << v;
      EXPECT_LT(norm(got.sv - want.sv), 1e-9 * norm(want.sv)) << knot << " " << v;
      EXPECT_LT(norm(got.suu - want.suu), 1e-7 * norm(want.suu)) << knot << " " << v;
      EXPECT_LT(norm(normal(r, ua, v) - normal(s, ua, v)), 1e-9) << knot << " " << v;
    }
  }
}

TEST(KnotOps, ReversalKeepsTheGeometryAndFlipsTheNormal) {
  const NurbsSurface s = extract_subsurface(wavy_surface(), 0.1, 0.9, 0.2, 0.8);
  const NurbsSurface ru = reverse_u(s);
  const NurbsSurface rv = reverse_v(s);
  EXPECT_EQ(ru.u0, s.u0);
  EXPECT_EQ(ru.u1, s.u1);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double u = s.u0 + unit(rng) * (s.u1 - s.u0), v = s.v0 + unit(rng) * (s.v1 - s.v0);
    EXPECT_LT(norm(evaluate(s, u, v) - evaluate(ru, s.u0 + (s.u1 - u), v)), 1e-12);
    EXPECT_LT(norm(evaluate(s, u, v) - evaluate(rv, u, s.v0 + (s.v1 - v))), 1e-12);
    EXPECT_LT(dot(normal(s, u, v), normal(ru, s.u0 + (s.u1 - u), v)), -0.999999);
  }
  const NurbsSurface back = reverse_u(ru);
  EXPECT_EQ(back.points, s.points);
  const NurbsSurface t = transpose_uv(s);
  EXPECT_LT(norm(evaluate(s, 0.3, 0.7) - evaluate(t, 0.7, 0.3)), 1e-15);
}

TEST(KnotOps, RejectsImpossibleRequests) {
  const NurbsSurface s = wavy_surface();
  EXPECT_THROW(insert_knot_u(s, 0.0, 1), GeometryError);
  EXPECT_THROW(insert_knot_u(s, 1.5, 1), GeometryError);
  EXPECT_THROW(insert_knot_u(s, 0.2, 4), GeometryError);  // 0.2 is there once; 5 > degree + 1
  EXPECT_THROW(split_u(s, {0.5, 0.5}), GeometryError);
  EXPECT_THROW(split_u(s, {0.5}), GeometryError);
  EXPECT_THROW(extract_subsurface(s, -0.1, 0.5, 0, 1), GeometryError);
  NurbsSurface bad = s;
  bad.weights.pop_back();
  EXPECT_THROW(insert_knot_u(bad, 0.5, 1), GeometryError);
}

}  // namespace
}  // namespace hm
