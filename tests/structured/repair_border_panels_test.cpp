// The border-panel repairs on a flat plate: a strip of thin panels along a block border (the
// station after a cut station planned 0.1 m past it, against 1 m elsewhere) is removed, and the
// plate stays covered, manifold and flat with no panel failing a rule. With every node fixed no
// repair helps (a split only makes thinner triangles), and the mesh is left as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mesh/adjacency.h"
#include "nurbs/patch.h"
#include "query/hull_query.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

constexpr double kLength = 7, kWidth = 6;

// The plate z = 0, x in [0, 7], y in [0, 6], as a bilinear patch, and a fine grid of it.
struct Plate {
  std::vector<Patch> patches;
  SurfaceMesh fine;
};

Plate plate() {
  Plate p;
  NurbsSurface s;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.points = {{0, 0, 0}, {kLength, 0, 0}, {0, kWidth, 0}, {kLength, kWidth, 0}};
  s.weights = {1, 1, 1, 1};
  Patch patch;
  patch.surface = s;
  p.patches.push_back(patch);
  const int n = 28;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double u = double(i) / n, v = double(j) / n;
      p.fine.positions.push_back({u * kLength, v * kWidth, 0});
      p.fine.vertex_uv.push_back({u, v});
      p.fine.vertex_patch.push_back(0);
    }
  }
  auto id = [&](int i, int j) { return static_cast<Index>(i + (n + 1) * j); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      p.fine.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), kInvalid});
      p.fine.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1), kInvalid});
      p.fine.face_patch.insert(p.fine.face_patch.end(), 2, 0);
    }
  }
  return p;
}

// Quads on stations x = xs (rows of nodes at y = 0, 1, ..., 6); faces left of x = 4 are block 0,
// the others block 1. Row nodes are free (slot row set, not fixed) but on the cut station x = 4.
struct Panels {
  SurfaceMesh mesh;
  std::vector<NodeSlot> slots;
};

Panels panels(const std::vector<double>& xs, bool all_fixed) {
  Panels out;
  const int ny = 6;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    for (int j = 0; j <= ny; ++j) {
      out.mesh.positions.push_back({xs[i], double(j), 0});
      out.mesh.vertex_patch.push_back(0);
      out.mesh.vertex_uv.push_back({xs[i] / kLength, j / kWidth});
      NodeSlot slot;
      slot.row = static_cast<Index>(i);
      slot.s = j;
      slot.fixed = all_fixed || xs[i] == 4;
      out.slots.push_back(slot);
    }
  }
  auto id = [&](std::size_t i, int j) { return static_cast<Index>(i * (ny + 1) + j); };
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    for (int j = 0; j < ny; ++j) {
      out.mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      out.mesh.face_block.push_back(xs[i] < 4 ? 0 : 1);
    }
  }
  return out;
}

// Panels failing a rule: quad side ratio over 4, or an area ratio over 2 with a neighbour.
std::size_t failing(const SurfaceMesh& m) {
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  std::size_t fails = 0;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const Face& h = m.faces[f];
    const int n = corner_count(h);
    double lo = 1e300, hi = 0;
    for (int c = 0; c < n; ++c) {
      const double l = norm(m.positions[h[(c + 1) % n]] - m.positions[h[c]]);
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
    bool fail = n == 4 && hi > 4 * lo;
    const double a = face_area(m.positions, h);
    for (int c = 0; c < n; ++c) {
      const Index g = adj.opposite_face[4 * f + c];
      if (g == kInvalid) continue;
      const double b = face_area(m.positions, m.faces[g]);
      fail = fail || std::max(a, b) > 2 * std::min(a, b);
    }
    fails += fail;
  }
  return fails;
}

TEST(RepairBorderPanels, ThinStripAlongACutStationIsRemoved) {
  const Plate p = plate();
  const HullQuery query(p.patches, p.fine);
  Panels m = panels({0, 1, 2, 3, 4, 4.1, 5, 6, 7}, false);
  const std::size_t before = failing(m.mesh);
  ASSERT_GT(before, 6u);  // the six thin panels and their neighbours
  const BorderRepairCounts c = repair_border_panels(query, m.slots, {}, m.mesh);
  // The thin panels, and the panels across the cut station from them (half their neighbours
  // are ten times their size).
  EXPECT_EQ(c.distorted, 12u);
  // The strip is removed: its row merges into the cut station, its two end nodes along the
  // plate's border too, and the panels beyond it reach the cut station. Nothing fails then.
  EXPECT_EQ(c.removed, 6u);
  EXPECT_EQ(failing(m.mesh), 0u);
  // Still the whole plate, flat, one border, every side used at most twice, no fold.
  double area = 0;
  for (const Face& f : m.mesh.faces) {
    const double a = face_area(m.mesh.positions, f);
    EXPECT_GT(a, 0);
    area += a;
  }
  EXPECT_NEAR(area, kLength * kWidth, 1e-9);
  for (const Vec3d& q : m.mesh.positions) EXPECT_NEAR(q.z, 0, 1e-12);
  const EdgeAdjacency adj = build_edge_adjacency(m.mesh.faces, m.mesh.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_EQ(adj.boundary_loops.size(), 1u);
  EXPECT_EQ(m.mesh.face_block.size(), m.mesh.faces.size());
  // The merged nodes, the seven of the row at x = 4.1, are used by no face any more.
  std::vector<int> used(m.mesh.vertex_count(), 0);
  for (const Face& f : m.mesh.faces)
    for (int k = 0; k < corner_count(f); ++k) used[f[k]] = 1;
  for (std::size_t v = 0; v < used.size(); ++v)
    EXPECT_EQ(used[v] == 0, m.mesh.positions[v].x == 4.1) << v;
}

TEST(RepairBorderPanels, NothingChangesWhereNoRepairHelps) {
  const Plate p = plate();
  const HullQuery query(p.patches, p.fine);
  // Every node fixed: no removal or extension; a split of a thin quad only makes two thin
  // triangles, each failing the area rule against its neighbours.
  Panels m = panels({0, 1, 2, 3, 4, 4.1, 5, 6, 7}, true);
  const SurfaceMesh was = m.mesh;
  const BorderRepairCounts c = repair_border_panels(query, m.slots, {}, m.mesh);
  EXPECT_EQ(c.distorted, 12u);
  EXPECT_EQ(c.removed + c.extended + c.split, 0u);
  EXPECT_EQ(m.mesh.faces, was.faces);
  EXPECT_EQ(m.mesh.positions, was.positions);
  // A regular grid has no distorted border panel at all.
  Panels r = panels({0, 1, 2, 3, 4, 5, 6, 7}, false);
  EXPECT_EQ(repair_border_panels(query, r.slots, {}, r.mesh).distorted, 0u);
}

// A thin strip along the plate's end x = 7, where bridge_starts laid the boundary between two
// rows' starts (an open transom's edge a little aft of the last station): no face lies across
// that side, but its nodes are a bridge's, and the strip is removed as along a cut station. The
// same strip along a plain boundary is no border panel's.
TEST(RepairBorderPanels, ThinStripAlongABridgeIsRemoved) {
  const Plate p = plate();
  const HullQuery query(p.patches, p.fine);
  for (const bool bridge : {false, true}) {
    Panels m = panels({0, 1, 2, 3, 4, 5, 6, 6.9, 7}, false);
    for (std::size_t v = 0; v < m.slots.size(); ++v) {
      if (m.mesh.positions[v].x != 7) continue;
      m.slots[v] = NodeSlot{};  // a boundary node, fixed
      m.slots[v].bridge = bridge;
    }
    const std::size_t before = failing(m.mesh);
    ASSERT_GE(before, 6u) << bridge;
    const BorderRepairCounts c = repair_border_panels(query, m.slots, {}, m.mesh);
    if (!bridge) {
      EXPECT_EQ(c.removed, 0u);
      EXPECT_EQ(failing(m.mesh), before);
      continue;
    }
    EXPECT_EQ(c.removed, 6u);
    EXPECT_EQ(failing(m.mesh), 0u);
    double area = 0;
    for (const Face& f : m.mesh.faces) area += face_area(m.mesh.positions, f);
    EXPECT_NEAR(area, kLength * kWidth, 1e-9);
    const EdgeAdjacency adj = build_edge_adjacency(m.mesh.faces, m.mesh.vertex_count());
    EXPECT_TRUE(adj.nonmanifold_edges.empty());
    EXPECT_EQ(adj.boundary_loops.size(), 1u);
  }
}

}  // namespace
}  // namespace hm::structured
