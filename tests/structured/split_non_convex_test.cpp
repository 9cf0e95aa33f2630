// Non-convex quads into triangles: a quad with a reflex corner, and one with three corners on a
// line (the end cap at a fine forefoot, property seed 1063), become two triangles along the
// diagonal through that corner; a convex quad stays; nothing moves and the block carries over.
#include <gtest/gtest.h>

#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

SurfaceMesh one_quad(std::vector<Vec3d> corners) {
  SurfaceMesh m;
  m.positions = std::move(corners);
  m.faces = {{0, 1, 2, 3}};
  m.face_block = {7};
  return m;
}

double signed_area_z(const SurfaceMesh& m, const Face& t) {
  return 0.5 *
         cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]).z;
}

TEST(SplitNonConvex, ReflexCornerIsSplitThroughIt) {
  // Corner 2 is pushed in past the diagonal 1-3: reflex there.
  SurfaceMesh m = one_quad({{0, 0, 0}, {2, 0, 0}, {0.6, 0.6, 0}, {0, 2, 0}});
  const std::vector<Vec3d> before = m.positions;
  EXPECT_EQ(split_non_convex(m), 1u);
  ASSERT_EQ(m.face_count(), 2u);
  EXPECT_EQ(m.positions, before);
  EXPECT_EQ(m.face_block, (std::vector<Index>{7, 7}));
  double area = 0;
  for (const Face& t : m.faces) {
    EXPECT_TRUE(is_triangle(t));
    // The diagonal runs from the reflex corner (2) to the one across (0).
    EXPECT_TRUE((t[0] == 0 || t[1] == 0 || t[2] == 0) && (t[0] == 2 || t[1] == 2 || t[2] == 2));
    EXPECT_GT(signed_area_z(m, t), 0.0);  // both keep the quad's orientation
    area += signed_area_z(m, t);
  }
  EXPECT_NEAR(area, 0.5 * 2 * 0.6 + 0.5 * 2 * 0.6, 1e-12);
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
}

TEST(SplitNonConvex, ThreeCornersOnALineAreSplitAndAConvexQuadStays) {
  // Seed 1063's end-cap quad at the forefoot (m): corners 0, 2 and 3 on the stem in y = 0, corner
  // 3 a hair inside the line from 0 to 2, and corner 1 5 cm off the centre plane.
  SurfaceMesh cap = one_quad(
      {{149.419, 0, -3.41}, {149.419, 0.052, -3.038}, {151.871, 0, -2.64}, {150.543, 0, -3.038}});
  EXPECT_EQ(split_non_convex(cap), 1u);
  ASSERT_EQ(cap.face_count(), 2u);
  // Split through the flat corner 3: the diagonal 1-3.
  for (const Face& t : cap.faces) {
    EXPECT_TRUE((t[0] == 1 || t[1] == 1 || t[2] == 1) && (t[0] == 3 || t[1] == 3 || t[2] == 3));
  }
  SurfaceMesh square = one_quad({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  EXPECT_EQ(split_non_convex(square), 0u);
  ASSERT_EQ(square.face_count(), 1u);
  EXPECT_EQ(square.faces[0][3], 3u);
}

}  // namespace
}  // namespace hm::structured
