// The constrained Delaunay triangulation on its own (no NURBS involved).
#include "tessellate/cdt.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

namespace hm {
namespace {

double area2(const std::vector<Vec2d>& p, const Tri& t) {
  return cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]);
}

// Square [0, 1]^2 with a regular grid inside and a circular hole of n segments.
struct Holed {
  std::vector<Vec2d> pts;
  std::vector<Segment> segs;
};

Holed holed_square(int grid, int n, double r) {
  Holed h;
  const int side = 4 * grid;
  for (int i = 0; i < side; ++i) {
    const double f = double(i % grid) / grid;
    const int s = i / grid;
    const Vec2d p = s == 0   ? Vec2d{f, 0}
                    : s == 1 ? Vec2d{1, f}
                    : s == 2 ? Vec2d{1 - f, 1}
                             : Vec2d{0, 1 - f};
    h.pts.push_back(p);
    h.segs.push_back({Index(i), Index((i + 1) % side)});
  }
  const Index base = Index(h.pts.size());
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    h.pts.push_back({0.5 + r * std::cos(a), 0.5 + r * std::sin(a)});
    h.segs.push_back({Index(base + i), Index(base + (i + 1) % n)});
  }
  for (int j = 1; j < grid; ++j) {
    for (int i = 1; i < grid; ++i) {
      const Vec2d q{double(i) / grid, double(j) / grid};
      if (std::hypot(q.x - 0.5, q.y - 0.5) > r + 0.5 / grid) h.pts.push_back(q);
    }
  }
  return h;
}

TEST(Cdt, SquareWithHoleCoversExactlyTheRegion) {
  const Holed h = holed_square(10, 24, 0.3);
  const std::vector<Tri> tris = triangulate_region(h.pts, h.segs);
  double area = 0;
  for (const Tri& t : tris) {
    const double a = area2(h.pts, t);
    ASSERT_GT(a, 0) << "triangles must be counter-clockwise and non-degenerate";
    area += 0.5 * a;
  }
  // The hole is the 24-gon inscribed in the circle.
  const double hole = 0.5 * 24 * 0.3 * 0.3 * std::sin(2 * std::numbers::pi / 24);
  EXPECT_NEAR(area, 1.0 - hole, 1e-12);
  // Every segment is an edge used by exactly one kept triangle (it bounds the region).
  std::map<std::uint64_t, int> uses;
  for (const Tri& t : tris)
    for (int i = 0; i < 3; ++i) ++uses[edge_key(t[i], t[(i + 1) % 3])];
  for (const Segment& s : h.segs) EXPECT_EQ(uses[edge_key(s[0], s[1])], 1);
  for (const auto& [k, n] : uses) EXPECT_LE(n, 2);
}

TEST(Cdt, LongSegmentsAcrossAGridAreRecovered) {
  // A thin diamond whose long sides cut through many grid points' Delaunay edges.
  std::vector<Vec2d> pts{{0, 0.5}, {0.5, 0.45}, {1, 0.5}, {0.5, 0.55}};
  std::vector<Segment> segs{{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  for (int j = 0; j <= 10; ++j)
    for (int i = 0; i <= 10; ++i) pts.push_back({i / 10.0 + 0.013, j / 10.0 + 0.007});
  const std::vector<Tri> tris = triangulate_region(pts, segs);
  double area = 0;
  for (const Tri& t : tris) area += 0.5 * area2(pts, t);
  EXPECT_NEAR(area, 0.05, 1e-12);
}

TEST(Cdt, PointOnASegmentSplitsIt) {
  std::vector<Vec2d> pts{{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0}};
  std::vector<Segment> segs{{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  const std::vector<Tri> tris = triangulate_region(pts, segs);
  double area = 0;
  for (const Tri& t : tris) area += 0.5 * area2(pts, t);
  EXPECT_NEAR(area, 1.0, 1e-12);
  EXPECT_EQ(tris.size(), 3u);
}

}  // namespace
}  // namespace hm
