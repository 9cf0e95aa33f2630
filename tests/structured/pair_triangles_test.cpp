// Triangle pairs into quads: the two triangles of a split cell in a grid of unit quads become one
// quad again; a pair across a knuckle, across a block border, or whose quad would be reflex, have
// a straight corner, or be folded stays; nothing moves.
#include <gtest/gtest.h>

#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// A 3 x 3 grid of unit quads in z = 0 (corner (i, j) is vertex i + 4 j), block 0, its middle
// cell split along the diagonal 5-10 into triangles 5-6-10 and 5-10-9.
SurfaceMesh grid_with_split_middle() {
  SurfaceMesh m;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) m.positions.push_back({double(i), double(j), 0});
  for (Index j = 0; j < 3; ++j) {
    for (Index i = 0; i < 3; ++i) {
      const Index a = i + 4 * j;
      if (i == 1 && j == 1) {
        m.faces.push_back({a, a + 1, a + 5, kInvalid});
        m.faces.push_back({a, a + 5, a + 4, kInvalid});
      } else {
        m.faces.push_back({a, a + 1, a + 5, a + 4});
      }
    }
  }
  m.face_block.assign(m.faces.size(), 0);
  return m;
}

std::size_t quads(const SurfaceMesh& m) {
  std::size_t n = 0;
  for (const Face& f : m.faces) n += !is_triangle(f);
  return n;
}

TEST(PairTriangles, ASplitCellInAGridIsOneQuadAgain) {
  SurfaceMesh m = grid_with_split_middle();
  const std::vector<Vec3d> before = m.positions;
  EXPECT_EQ(pair_triangles({}, ZipOptions{}, m), 1u);
  EXPECT_EQ(m.positions, before);
  ASSERT_EQ(m.face_count(), 9u);
  EXPECT_EQ(quads(m), 9u);
  EXPECT_EQ(m.face_block.size(), 9u);
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  // The new quad keeps the triangles' orientation (+z) and covers the cell.
  double area = 0;
  for (const Face& f : m.faces) {
    const Vec3d n =
        cross(m.positions[f[2]] - m.positions[f[0]], m.positions[f[3]] - m.positions[f[1]]);
    EXPECT_GT(n.z, 0);
    area += 0.5 * n.z;
  }
  EXPECT_NEAR(area, 9.0, 1e-12);
}

TEST(PairTriangles, KnucklesBlocksReflexAndFoldedPairsStay) {
  {
    SurfaceMesh m = grid_with_split_middle();
    const std::vector<std::array<Index, 2>> knuckle{{10, 5}};
    EXPECT_EQ(pair_triangles(knuckle, ZipOptions{}, m), 0u);
    EXPECT_EQ(m.face_count(), 10u);
  }
  {
    SurfaceMesh m = grid_with_split_middle();
    m.face_block[5] = 1;  // the second triangle
    EXPECT_EQ(pair_triangles({}, ZipOptions{}, m), 0u);
    EXPECT_EQ(m.face_count(), 10u);
  }
  {
    // Corner 10 pulled in towards 5: both triangles still face +z, but the quad 5-6-10-9 is
    // reflex at 10 (its opposite sides are 1 and 0.72, within the zip's test).
    SurfaceMesh m = grid_with_split_middle();
    m.positions[10] = {1.4, 1.4, 0};
    EXPECT_EQ(pair_triangles({}, ZipOptions{}, m), 0u);
    EXPECT_EQ(m.face_count(), 10u);
  }
  {
    // Two triangles of a fan from one node over a row (0, 1, 2 on a line): their quad would have
    // a straight corner at 1, a triangle in all but name.
    SurfaceMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1, 1, 0}};
    m.faces = {{0, 1, 3, kInvalid}, {1, 2, 3, kInvalid}};
    m.face_block = {0, 0};
    EXPECT_EQ(pair_triangles({}, ZipOptions{}, m), 0u);
    EXPECT_EQ(m.face_count(), 2u);
    m.positions[1].y = -0.3;  // the corner at 1 turns: now a quad
    EXPECT_EQ(pair_triangles({}, ZipOptions{}, m), 1u);
    EXPECT_EQ(m.face_count(), 1u);
  }
  {
    // Corner 9 lifted out of the plane: the pair folds along 5-10 and the quad would be warped.
    SurfaceMesh m = grid_with_split_middle();
    m.positions[9].z = 0.5;
    EXPECT_EQ(pair_triangles({}, ZipOptions{}, m), 0u);
    EXPECT_EQ(m.face_count(), 10u);
  }
}

// A pair lifted at its outer corners (warp 0.07): its own split runs low along u-v, the quad's
// other split high along x-w. A small upright panel at the middle, tied to the mesh by a bridge
// panel from w, stands between the two: made a quad, the pair would pass through it on one of its
// splits, so it stays; lowered under both, it pairs.
TEST(PairTriangles, APairWhoseOtherSplitWouldPassThroughAPanelStays) {
  auto mesh = [](double lift) {
    const double h = 0.2;
    SurfaceMesh m;
    m.positions = {{0, 0, 0},
                   {1, 0, h},
                   {1, 1, 0},
                   {0, 1, h},
                   {0.45, 0.5, 0.1 + lift},
                   {0.55, 0.5, 0.1 + lift},
                   {0.5, 0.5, 0.3 + lift},
                   {-0.5, 1.5, h}};
    m.faces = {{0, 2, 3, kInvalid},   // u v w
               {2, 0, 1, kInvalid},   // v u x
               {4, 5, 6, kInvalid},   // upright, at the middle
               {3, 4, 7, kInvalid}};  // bridge from w
    m.face_block.assign(4, 0);
    return m;
  };
  SurfaceMesh standing = mesh(0);
  EXPECT_EQ(pair_triangles({}, ZipOptions{}, standing), 0u);
  EXPECT_EQ(standing.face_count(), 4u);
  SurfaceMesh lowered = mesh(-0.45);
  EXPECT_EQ(pair_triangles({}, ZipOptions{}, lowered), 1u);
  EXPECT_EQ(lowered.face_count(), 3u);
}

}  // namespace
}  // namespace hm::structured
