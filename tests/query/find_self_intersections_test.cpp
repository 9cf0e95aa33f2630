// Self-intersections: crossings found, touches and shared corners not, coplanar overlaps found,
// and the same answer at any thread count.
#include "query/find_self_intersections.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/test_support.h"

namespace hm {
namespace {

Index add_vertex(SurfaceMesh& m, const Vec3d& p) {
  m.positions.push_back(p);
  return static_cast<Index>(m.positions.size() - 1);
}

void add_triangle(SurfaceMesh& m, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Index i = add_vertex(m, a), j = add_vertex(m, b), k = add_vertex(m, c);
  m.faces.push_back({i, j, k, kInvalid});
  m.face_patch.push_back(0);
}

// An n x n grid of quads over [-1, 1]^2, mapped by f(s, t) (s, t in [-1, 1]).
template <class F>
void add_grid(SurfaceMesh& m, int n, F f) {
  const Index base = static_cast<Index>(m.positions.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.push_back(f(-1 + 2.0 * i / n, -1 + 2.0 * j / n));
  auto v = [&](int i, int j) { return base + static_cast<Index>(i + (n + 1) * j); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
      m.face_patch.push_back(static_cast<PatchId>(base));
    }
  }
}

TEST(SelfIntersections, TwoTrianglesThroughEachOtherCrossOnce) {
  SurfaceMesh m;
  add_triangle(m, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  add_triangle(m, {0, -0.5, -1}, {0, 0.5, -1}, {0, 0, 1});
  const SelfIntersections s = find_self_intersections(m, 1e-9);
  ASSERT_EQ(s.count, 1u);
  ASSERT_EQ(s.first.size(), 1u);
  EXPECT_EQ(s.first[0].face_a, 0u);
  EXPECT_EQ(s.first[0].face_b, 1u);
  // The shared chord lies on x = 0, z = 0, for y in [-0.5, 0.5].
  EXPECT_NEAR(s.first[0].where.x, 0, 1e-12);
  EXPECT_NEAR(s.first[0].where.z, 0, 1e-12);
  EXPECT_LE(std::abs(s.first[0].where.y), 0.5);
}

TEST(SelfIntersections, TouchesAndSharedCornersAreNotCrossings) {
  SurfaceMesh m;
  // A triangle standing on another with one edge lying in its plane: a touch.
  add_triangle(m, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
  add_triangle(m, {0, -0.5, 0}, {0, 0.5, 0}, {0, 0, 1});
  // A corner resting on a face, below the first pair.
  add_triangle(m, {-1, -1, -3}, {1, -1, -3}, {0, 1, -3});
  add_triangle(m, {0, 0, -3}, {0.5, 0, -2}, {0, 0.5, -2});
  EXPECT_EQ(find_self_intersections(m, 1e-9).count, 0u);
  // Two faces that share a vertex are never tested, even folded through each other.
  SurfaceMesh fold;
  add_grid(fold, 1, [](double s, double t) { return Vec3d{s, t, 0}; });
  const Index o = 0;
  const Index a = add_vertex(fold, {0.5, 0.5, 1}), b = add_vertex(fold, {0.5, 0.5, -1});
  fold.faces.push_back({o, a, b, kInvalid});
  fold.face_patch.push_back(1);
  EXPECT_EQ(find_self_intersections(fold, 1e-9).count, 0u);
}

TEST(SelfIntersections, CoplanarOverlapIsACrossingAndCoplanarNeighboursAreNot) {
  SurfaceMesh m;
  add_triangle(m, {0, 0, 0}, {2, 0, 0}, {0, 2, 0});
  add_triangle(m, {0.5, 0.5, 0}, {3, 0.5, 0}, {0.5, 3, 0});
  EXPECT_EQ(find_self_intersections(m, 1e-9).count, 1u);
  SurfaceMesh n;  // edge to edge along x + y = 2 without shared vertices (a T-junction)
  add_triangle(n, {0, 0, 0}, {2, 0, 0}, {0, 2, 0});
  add_triangle(n, {3, 0, 0}, {1, 1, 0}, {3, -1, 0});
  EXPECT_EQ(find_self_intersections(n, 1e-9).count, 0u);
}

TEST(SelfIntersections, AClosedSurfaceHasNoneUntilAFaceIsPushedThroughIt) {
  // A cylinder of 24 x 8 quads with a cone over each end, all welded.
  SurfaceMesh m;
  const int n = 24, rows = 8;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      m.positions.push_back({std::cos(a), std::sin(a), -1 + 2.0 * j / rows});
    }
  const Index bottom = add_vertex(m, {0, 0, -1.5}), top = add_vertex(m, {0, 0, 1.5});
  auto v = [&](int i, int j) { return static_cast<Index>(i % n + n * j); };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < n; ++i)
      m.faces.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
  for (int i = 0; i < n; ++i) {
    m.faces.push_back({v(i + 1, 0), v(i, 0), bottom, kInvalid});
    m.faces.push_back({v(i, rows), v(i + 1, rows), top, kInvalid});
  }
  m.face_patch.assign(m.faces.size(), 0);
  EXPECT_EQ(find_self_intersections(m, 1e-9).count, 0u);
  // The top apex pushed down through the bottom cone: its fan crosses the bottom's.
  m.positions[top].z = -2;
  const SelfIntersections s = find_self_intersections(m, 1e-9);
  EXPECT_GT(s.count, 0u);
  for (const FaceCrossing& c : s.first) EXPECT_LT(c.where.z, -0.9);
}

TEST(SelfIntersections, TwoCrossingGridsAtOneTwoAndEightThreads) {
  SurfaceMesh m;
  add_grid(m, 40, [](double s, double t) { return Vec3d{s, t, 0.1 * s * t}; });
  add_grid(m, 40, [](double s, double t) { return Vec3d{0.013 + 0.2 * t, s, t}; });
  SelfIntersections first;
  for (int threads : test::kThreadCounts) {
    SelfIntersections s;
    test::with_threads(threads, [&] { s = find_self_intersections(m, 1e-9, 1000); });
    ASSERT_GE(s.count, 40u) << "the crossing runs the whole width of both grids";
    ASSERT_EQ(s.first.size(), s.count);
    for (const FaceCrossing& c : s.first) {
      EXPECT_LT(c.face_a, 1600u);
      EXPECT_GE(c.face_b, 1600u);
      EXPECT_NEAR(c.where.z, 0.1 * c.where.x * c.where.y, 1e-3) << "on the first grid";
    }
    if (threads == test::kThreadCounts[0]) {
      first = s;
      continue;
    }
    ASSERT_EQ(s.count, first.count) << threads << " threads";
    for (std::size_t k = 0; k < s.first.size(); ++k) {
      EXPECT_EQ(s.first[k].face_a, first.first[k].face_a);
      EXPECT_EQ(s.first[k].face_b, first.first[k].face_b);
      EXPECT_EQ(s.first[k].where.x, first.first[k].where.x);
      EXPECT_EQ(s.first[k].where.y, first.first[k].where.y);
      EXPECT_EQ(s.first[k].where.z, first.first[k].where.z);
    }
  }
}

}  // namespace
}  // namespace hm
