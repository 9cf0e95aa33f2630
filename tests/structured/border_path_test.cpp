// Resampling a path along the surface's boundary at the panel size (border_path.h).
#include "structured/border_path.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace hm::structured
