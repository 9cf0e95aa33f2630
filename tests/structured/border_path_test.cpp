// Resampling a path along the surface's boundary at the panel size (border_path.h).
#include "structured/border_path.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace hm::structured {
namespace {

Metric unit_metric() {
  Metric m;
  m.size = {1.0, 1.0, 1.0};
  return m;
}

// A straight path 4 panels long: three nodes a panel apart between its ends.
TEST(Resample, StraightPathGetsANodeEveryPanel) {
  const std::vector<Vec3d> nodes = resample({{0, 0, 0}, {1.5, 0, 0}, {4, 0, 0}}, unit_metric());
  ASSERT_EQ(nodes.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(nodes[i].x, double(i + 1), 1e-12);
}

// A corner turning by more than 40 degrees is kept as a node.
TEST(Resample, CornersAreKept) {
  const std::vector<Vec3d> nodes = resample({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}}, unit_metric());
  ASSERT_EQ(nodes.size(), 3u);
  EXPECT_NEAR(nodes[1].x, 2.0, 1e-12);
  EXPECT_NEAR(nodes[1].y, 0.0, 1e-12);
}

// npl_round_bilge.iges at its stern: the boundary runs up the centre plane, turns along the
// waterline, steps out 0.3 mm and doubles back onto the point it left (its 3 mm keel bar beside
// a 1.5 mm step). Each turn was a corner, so three nodes within 0.3 mm of each other, and the
// cap zipped onto them had panels with no area. Nodes a quarter panel or nearer the one before
// (or the path's end) are dropped, but for a corner a chord would cut a tenth of a panel or
// more off: the turn from the centre plane onto the waterline stays, once.
TEST(Resample, NodesOfAPathThatDoublesBackAreNotCrowded) {
  const std::vector<Vec3d> path = {{0, 0, -0.75},     {0, 0, 0},      {0, 0.1875, 0},
                                   {0.019, 0.194, 0}, {0, 0.1875, 0}, {0.24, 0.27, 0},
                                   {0.64, 0.39, 0}};
  const std::vector<Vec3d> nodes = resample(path, unit_metric());
  ASSERT_EQ(nodes.size(), 2u);
  // The corner where the path leaves the centre plane, and the one where it turns along the
  // waterline after the step; the step's own corners are gone.
  EXPECT_NEAR(norm(nodes[0] - Vec3d{0, 0, 0}), 0.0, 1e-12);
  EXPECT_NEAR(norm(nodes[1] - Vec3d{0, 0.1875, 0}), 0.0, 1e-12);
  EXPECT_GE(norm(path.back() - nodes.back()), 0.25);
}

// The property test's seed 1102 at its transom: the boundary beyond the first station runs up
// the centre plane a fifth of a panel from the transom's lowest point to the waterline and
// turns out along it. The corner was dropped as too near the node before, and the panel edge
// that replaced it cut across the immersed transom, leaving a free edge below the waterline.
// A corner whose chord would pass a tenth of a panel or more from it stays.
TEST(Resample, ACornerTheChordWouldCutAcrossStays) {
  const std::vector<Vec3d> path = {{0, 0, -0.2}, {0, 0, 0}, {0, 0.9, 0}};
  const std::vector<Vec3d> nodes = resample(path, unit_metric());
  ASSERT_EQ(nodes.size(), 1u);
  EXPECT_NEAR(norm(nodes[0] - Vec3d{0, 0, 0}), 0.0, 1e-12);
  // A corner a twentieth of a panel up goes: the chord passes within a tenth of it.
  const std::vector<Vec3d> shallow = {{0, 0, -0.05}, {0, 0, 0}, {0, 0.9, 0}};
  EXPECT_TRUE(resample(shallow, unit_metric()).empty());
}

// Seeds 1091 and 1134 at the bow: the stem meets the waterline a seventh of a panel from the
// last station's upper end, where the path ends. That corner, the last node, was dropped as too
// near the end, and the panel edge from the stem node to the row's end left the surface beyond
// uncovered. The last corner stays down to a twentieth of a panel from the end.
TEST(Resample, TheLastCornerNearTheEndStays) {
  const std::vector<Vec3d> path = {{0, 0, 0}, {0.5, 0, 0.7}, {0.36, 0.05, 0.7}};
  const std::vector<Vec3d> nodes = resample(path, unit_metric());
  ASSERT_EQ(nodes.size(), 1u);
  EXPECT_NEAR(norm(nodes[0] - Vec3d{0.5, 0, 0.7}), 0.0, 1e-12);
}

// A disc of n triangles round its centre, its rim an ellipse in z = 0 with a wobbly radius: one
// boundary loop of n vertices.
SurfaceMesh wobbly_disc(int n) {
  SurfaceMesh m;
  m.positions.push_back({0, 0, 0});
  for (int i = 0; i < n; ++i) {
    const double t = 2 * 3.14159265358979 * i / n;
    const double r = 1 + 0.2 * std::sin(5 * t);
    m.positions.push_back({3 * r * std::cos(t), r * std::sin(t), 0});
  }
  for (int i = 0; i < n; ++i) {
    m.faces.push_back({0, Index(1 + i), Index(1 + (i + 1) % n), kInvalid});
  }
  return m;
}

// The way round as the loop_path of each direction, measured whole (the rule before the walk
// stopped early): the shorter way that stays in the slab.
std::vector<Vec3d> reference_path(const SurfaceMesh& s, const EdgeAdjacency& adj, const Vec3d& a,
                                  const Vec3d& b, const Metric& metric, double tol, double x_lo,
                                  double x_hi) {
  const LoopSpot sa = nearest_boundary_edge(s, adj, a);
  const LoopSpot sb = nearest_boundary_edge(s, adj, b);
  if (sa.loop != sb.loop || sa.distance > tol || sb.distance > tol) return {};
  std::vector<Vec3d> best;
  double best_len = std::numeric_limits<double>::infinity();
  for (const bool forward : {true, false}) {
    std::vector<Vec3d> pts{a};
    bool inside = true;
    for (Index v : loop_path(adj.boundary_loops[sa.loop].vertices, sa.edge, sb.edge, forward)) {
      inside = inside && s.positions[v].x >= x_lo && s.positions[v].x <= x_hi;
      pts.push_back(s.positions[v]);
    }
    if (!inside) continue;
    pts.push_back(b);
    double len = 0;
    for (std::size_t i = 1; i < pts.size(); ++i) len += metric.length(pts[i - 1], pts[i]);
    if (len < best_len) {
      best_len = len;
      best = std::move(pts);
    }
  }
  return best;
}

// The walk stops a way round once it leaves the slab or outgrows the way already found; the
// path must come out as the whole walk of both ways gives it, point for point, with and without
// a slab, and with the short way cut off by the slab.
TEST(ShortestBorderPath, StoppingEarlyGivesTheWholeWalksPath) {
  const SurfaceMesh disc = wobbly_disc(300);
  const EdgeAdjacency adj = build_edge_adjacency(disc.faces, disc.vertex_count());
  ASSERT_EQ(adj.boundary_loops.size(), 1u);
  const Metric metric = unit_metric();
  const auto rim = [&](double t) {
    const double r = 1 + 0.2 * std::sin(5 * t);
    return Vec3d{3 * r * std::cos(t), r * std::sin(t), 0};
  };
  int compared = 0, short_ways = 0, empty = 0;
  for (int k = 0; k < 60; ++k) {
    // Near pairs, and (every third) pairs nearly opposite, whose two ways are about as long.
    const double t0 = 0.37 * k;
    const double t1 =
        k % 3 == 0 ? t0 + 3.14159265358979 + 0.02 * (k % 7 - 3) : t0 + 0.05 + 0.11 * (k % 23);
    const Vec3d a = rim(t0), b = rim(t1);
    for (const auto& [lo, hi] : {std::pair{-1e300, 1e300}, std::pair{-1.0, 3.5},
                                 std::pair{std::min(a.x, b.x) - 0.2, std::max(a.x, b.x) + 0.2}}) {
      const std::vector<Vec3d> got = shortest_border_path(disc, adj, a, b, metric, 0.05, lo, hi);
      const std::vector<Vec3d> want = reference_path(disc, adj, a, b, metric, 0.05, lo, hi);
      ASSERT_EQ(got.size(), want.size()) << "pair " << k;
      for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], want[i]);
      ++compared;
      short_ways += !got.empty() && got.size() < 150;
      empty += got.empty();
    }
  }
  EXPECT_EQ(compared, 180);
  EXPECT_GT(short_ways, 40);  // most pairs are nearer one way round
  EXPECT_GT(empty, 0);        // and some slabs leave neither way
}

}  // namespace
}  // namespace hm::structured
