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
// (or the path's end) are dropped.
TEST(Resample, NodesOfAPathThatDoublesBackAreNotCrowded) {
  const std::vector<Vec3d> path = {{0, 0, -0.75},     {0, 0, 0},      {0, 0.1875, 0},
                                   {0.019, 0.194, 0}, {0, 0.1875, 0}, {0.24, 0.27, 0},
                                   {0.64, 0.39, 0}};
  const std::vector<Vec3d> nodes = resample(path, unit_metric());
  ASSERT_FALSE(nodes.empty());
  Vec3d last = path.front();
  for (const Vec3d& p : nodes) {
    EXPECT_GE(norm(p - last), 0.25) << p.x << " " << p.y << " " << p.z;
    last = p;
  }
  EXPECT_GE(norm(path.back() - last), 0.25);
  // The corner where the path leaves the centre plane stays a node.
  EXPECT_NEAR(norm(nodes.front() - Vec3d{0, 0, 0}), 0.0, 1e-12);
}

}  // namespace
}  // namespace hm::structured
