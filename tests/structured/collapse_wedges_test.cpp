// The wedge collapse on a flat grid of unit quads: a node pulled down to 5 cm above the one below
// it makes the two quads that share their short side wedges (side ratio 20). The short side
// collapses: both become triangles, nothing moves, the grid stays manifold and no quad breaks
// the side rule. A strip of thin quads (both short sides short: not wedges) is left to the other
// repairs, and a wedge whose short side joins two fixed nodes stays as it is.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <vector>

#include "mesh/adjacency.h"
#include "structured/editable_faces.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

struct Grid {
  SurfaceMesh mesh;
  std::vector<NodeSlot> slots;
};

// Nodes at x = xs[i], y = 0 .. ny in the plane z = 0; quads between them, block 0; every node a
// free row node (the ones on the grid's border are on the boundary, which node_freedom finds).
Grid grid(const std::vector<double>& xs, int ny, bool fixed) {
  Grid g;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    for (int j = 0; j <= ny; ++j) {
      g.mesh.positions.push_back({xs[i], double(j), 0});
      NodeSlot slot;
      slot.row = static_cast<Index>(i);
      slot.s = j;
      slot.fixed = fixed;
      g.slots.push_back(slot);
    }
  }
  auto id = [&](std::size_t i, int j) { return static_cast<Index>(i * (ny + 1) + j); };
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    for (int j = 0; j < ny; ++j) {
      g.mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      g.mesh.face_block.push_back(0);
    }
  }
  return g;
}

std::size_t quads_breaking_side_rule(const SurfaceMesh& m) {
  std::size_t n = 0;
  for (const Face& f : m.faces) n += !is_triangle(f) && side_ratio(m.positions, f) > 4;
  return n;
}

std::size_t triangles(const SurfaceMesh& m) {
  std::size_t n = 0;
  for (const Face& f : m.faces) n += is_triangle(f);
  return n;
}

TEST(CollapseWedges, WedgePairBecomesTwoTrianglesAndNothingMoves) {
  Grid g = grid({0, 1, 2, 3, 4}, 4, false);
  const Index pulled = 2 * 5 + 2;  // node (2, 2)
  g.mesh.positions[pulled].y = 1.05;
  ASSERT_EQ(quads_breaking_side_rule(g.mesh), 2u);
  const std::vector<Vec3d> before = g.mesh.positions;
  const std::size_t faces = g.mesh.faces.size();

  EXPECT_EQ(collapse_wedges(g.slots, {}, 0.35, g.mesh), 1u);
  EXPECT_EQ(quads_breaking_side_rule(g.mesh), 0u);
  EXPECT_EQ(triangles(g.mesh), 2u);
  EXPECT_EQ(g.mesh.faces.size(), faces);
  EXPECT_EQ(g.mesh.positions, before);  // merged, not moved
  const EdgeAdjacency adj = build_edge_adjacency(g.mesh.faces, g.mesh.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  EXPECT_EQ(adj.boundary_loops.size(), 1u);
  // One of the short side's ends is gone from every face.
  std::size_t uses_pulled = 0, uses_below = 0;
  for (const Face& f : g.mesh.faces) {
    for (int c = 0; c < corner_count(f); ++c) {
      uses_pulled += f[c] == pulled;
      uses_below += f[c] == pulled - 1;
    }
  }
  EXPECT_TRUE(uses_pulled == 0 || uses_below == 0);
}

TEST(CollapseWedges, ThinQuadsAndFixedNodesAreLeft) {
  // A column 0.1 m wide: its quads break the side rule, but their short sides face each other.
  Grid thin = grid({0, 1, 2, 2.1, 3, 4}, 4, false);
  ASSERT_EQ(quads_breaking_side_rule(thin.mesh), 4u);
  EXPECT_EQ(collapse_wedges(thin.slots, {}, 0.35, thin.mesh), 0u);
  EXPECT_EQ(quads_breaking_side_rule(thin.mesh), 4u);

  Grid fixed = grid({0, 1, 2, 3, 4}, 4, true);
  fixed.mesh.positions[2 * 5 + 2].y = 1.05;
  const std::vector<Face> faces = fixed.mesh.faces;
  EXPECT_EQ(collapse_wedges(fixed.slots, {}, 0.35, fixed.mesh), 0u);
  EXPECT_EQ(fixed.mesh.faces, faces);
}

// The guard the wedge collapse puts on its merges: three corners on one line (a short side
// merged along a straight transom edge) are flat; a thin but true triangle is not.
TEST(CollapseWedges, ThreeCornersOnALineAreFlat) {
  std::vector<Vec3d> positions{{0, 0, 0}, {2, 1, 0}, {4, 2, 0}, {4, 2.1, 0}};
  std::vector<Face> faces{{0, 1, 2, kInvalid}, {0, 2, 3, kInvalid}};
  EditableFaces m(faces, positions);
  EXPECT_TRUE(m.flat({0}));
  EXPECT_FALSE(m.flat({1}));  // a corner of 1.1 degrees
  EXPECT_TRUE(m.flat({0, 1}));
}

// The other guard: a merge may not drag panels across others that share no corner with them. A
// fan from the waterline node w runs down a stem just left of the first column; the wedge at the
// column's top has its short side along the waterline, from w to w2 (on a knuckle, so w2 stays).
// Merging w into w2 would make the wedge a triangle and ease the fan's area ratios, but drag the
// fan 0.1 m right, over the column's quad below (DTMB 5415's stem at 0.3137 m, 800 panels,
// trimmed -0.16 degrees: 3 of its 4 pairs of panels through each other). The wedge stays a quad.
TEST(CollapseWedges, AMergeThatDragsAFanAcrossAPanelIsNotMade) {
  // 0 a0, 1 a1, 2 w (the first column); 3 b0, 4 b1, 5 w2 (the second); 6 t on the stem, 7 s the
  // stem's corner with the waterline.
  SurfaceMesh mesh;
  mesh.positions = {{0, 0.2, 0}, {0, 1, 0},   {0, 2, 0},       {1, 0.2, 0},
                    {1, 1, 0},   {0.1, 2, 0}, {-0.02, 0.3, 0}, {-0.6, 2, 0}};
  mesh.faces = {{0, 3, 4, 1}, {1, 4, 5, 2}, {1, 2, 6, kInvalid}, {6, 2, 7, kInvalid}};
  mesh.face_block.assign(mesh.faces.size(), 0);
  std::vector<NodeSlot> slots(mesh.positions.size());
  for (Index v = 0; v < 6; ++v) {
    slots[v].row = v / 3;
    slots[v].s = v % 3;
  }
  const std::vector<std::array<Index, 2>> knuckles{{4, 5}};
  ASSERT_EQ(quads_breaking_side_rule(mesh), 1u);
  {
    std::vector<Face> faces = mesh.faces;
    std::vector<Vec3d> positions = mesh.positions;
    EditableFaces m(faces, positions);
    const std::set<Index> core{1, 2, 3}, judged{0, 1, 2, 3};
    EXPECT_EQ(m.crossings(core, judged, 1e-9), 0u);
    const EditableFaces::Score before = m.score(core, judged);
    m.merge_node(2, 5);
    EXPECT_TRUE(m.score(core, judged).better_than(before));  // by the rules alone, a gain
    EXPECT_EQ(m.crossings(core, judged, 1e-9), 1u);          // the fan's second over the quad
    EXPECT_TRUE(node_freedom(slots, knuckles, mesh).may_merge(2, 5, slots));
  }
  EXPECT_EQ(collapse_wedges(slots, knuckles, 0.35, mesh), 0u);
  EXPECT_EQ(quads_breaking_side_rule(mesh), 1u);
}

}  // namespace
}  // namespace hm::structured
