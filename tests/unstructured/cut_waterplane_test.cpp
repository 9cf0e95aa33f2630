// The waterplane cut of the fine patch triangulation: what stays is the wetted part, the new
// border lies on the plane and on the NURBS, the cut leaves no sliver, and the wetted area and
// volume of a generated Wigley hull match its closed forms.
#include "unstructured/cut_waterplane.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <vector>

#include "core/error.h"
#include "nurbs/generate_hull.h"
#include "quality/hydrostatics.h"
#include "mesh/adjacency.h"
#include "tessellate/tessellate.h"
#include "unstructured/merge.h"

namespace hm {
namespace {

struct Cut {
  GeneratedHull hull;
  Tessellation tess;
  MergedSurface merged;
  WaterplaneCut cut;
};

Cut cut_wigley(double waterline_z, int patches = 4, double snap = 0.3) {
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  spec.patches = patches;
  Cut c{generate_hull(spec), {}, {}, {}};
  TessellateOptions o;
  o.edge_length = 1.0;  // L / 100
  c.tess = tessellate(c.hull.patches, o, silent_progress());
  c.merged = merge_patches(c.hull.patches, c.tess.mesh, {}, silent_progress());
  WaterplaneCutOptions co;
  co.waterline_z = waterline_z;
  co.snap_fraction = snap;
  c.cut = cut_at_waterplane(c.hull.patches, c.merged.mesh, co);
  return c;
}

// Triangles with a corner on the plane z = z0 whose area over squared longest side is under 1e-3
// (an equilateral triangle has 0.43).
std::size_t slivers_at_cut(const SurfaceMesh& m, double z0) {
  std::size_t count = 0;
  for (const Face& f : m.faces) {
    if (m.positions[f[0]].z != z0 && m.positions[f[1]].z != z0 && m.positions[f[2]].z != z0) {
      continue;
    }
    double longest = 0;
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, squared_norm(m.positions[f[(k + 1) % 3]] - m.positions[f[k]]));
    }
    count += face_area(m.positions, f) < 1e-3 * longest;
  }
  return count;
}

TEST(CutWaterplane, KeepsTheWettedPartWithItsBorderOnThePlaneAndTheNurbs) {
  const double z0 = 4.1;  // between grid rows of the Wigley (T = 6.25)
  const Cut c = cut_wigley(z0);
  const SurfaceMesh& m = c.cut.mesh;
  ASSERT_GT(m.faces.size(), 100u);
  EXPECT_GT(c.cut.report.edges_cut + c.cut.report.vertices_snapped, 50u);
  EXPECT_EQ(c.cut.report.unconverged, 0u);
  ASSERT_EQ(m.face_patch.size(), m.faces.size());
  ASSERT_EQ(c.cut.face_new2old.size(), m.faces.size());
  std::size_t on_plane = 0;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    const Vec3d& p = m.positions[v];
    ASSERT_LE(p.z, z0);
    if (p.z != z0) continue;
    ++on_plane;
    // On the patch's surface at its (u, v), to round-off (L = 100 m).
    const Vec3d s = evaluate(c.hull.patches[m.vertex_patch[v]].surface, m.vertex_uv[v].x,
                             m.vertex_uv[v].y);
    EXPECT_NEAR(norm(s - p), 0, 1e-7) << "vertex " << v;
  }
  EXPECT_GE(on_plane, c.cut.report.edges_cut);
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    EXPECT_EQ(m.face_patch[f], c.merged.mesh.face_patch[c.cut.face_new2old[f]]);
  }
  // Still one manifold, consistently wound surface with one outline (waterline, centre plane).
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  EXPECT_EQ(adj.boundary_loops.size(), 1u);
}

TEST(CutWaterplane, SnappingLeavesNoSliverWhereTheLoopWouldMakeOne) {
  // A waterplane 0.1 mm above a row of grid vertices: cutting the row's triangles as they are
  // makes a sliver at every vertex of the row.
  const Cut probe = cut_wigley(4.1);
  double row_z = 0, best = 1e300;
  for (const Vec3d& p : probe.merged.mesh.positions) {
    if (std::abs(p.z - 4.1) < best) {
      best = std::abs(p.z - 4.1);
      row_z = p.z;
    }
  }
  const double z0 = row_z + 1e-4;
  const Cut snapped = cut_wigley(z0);
  const Cut raw = cut_wigley(z0, 4, 0.0);
  EXPECT_GT(snapped.cut.report.vertices_snapped, 20u);
  EXPECT_EQ(raw.cut.report.vertices_snapped, 0u);
  const std::size_t raw_slivers = slivers_at_cut(raw.cut.mesh, z0);
  const std::size_t slivers = slivers_at_cut(snapped.cut.mesh, z0);
  EXPECT_GT(raw_slivers, 20u);
  // Vertices on patch borders do not move (that would bend the border off the other patch), so
  // a few slivers may remain there: the 3 borders between 4 patches cross the row once each, and
  // at most 4 triangles of such a vertex's fan cross the plane.
  EXPECT_LE(slivers, 12u) << "of " << raw_slivers << " without snapping";
}

TEST(CutWaterplane, WigleyWettedAreaAndVolumeMatchTheClosedForm) {
  // At the design draft the kept part is the Wigley hull's wetted surface (half hull). The
  // triangles are within the chord tolerance (1e-4 L = 1 cm) of the surface, which bounds the
  // area error near 1e-3 and the volume error near that times wetted area over volume (3e-3).
  const Cut c = cut_wigley(6.25);
  double area = 0;
  for (const Face& f : c.cut.mesh.faces) area += face_area(c.cut.mesh.positions, f);
  EXPECT_NEAR(2 * area / c.hull.facts.wetted_area, 1, 1e-3);
  FloatingPosition position;
  position.waterline_z = 6.25;
  position.half_hull = true;
  const Hydrostatics h = hydrostatics_mesh(c.cut.mesh, position);
  EXPECT_NEAR(h.volume / c.hull.facts.displacement_volume, 1, 3e-3);
}

TEST(CutWaterplane, SameArraysWithOneAndTwoThreads) {
  Cut one, two;
  {
    tbb::global_control g(tbb::global_control::max_allowed_parallelism, 1);
    one = cut_wigley(3.3, 12);
  }
  {
    tbb::global_control g(tbb::global_control::max_allowed_parallelism, 2);
    two = cut_wigley(3.3, 12);
  }
  EXPECT_EQ(one.cut.mesh.positions, two.cut.mesh.positions);
  EXPECT_EQ(one.cut.mesh.faces, two.cut.mesh.faces);
  EXPECT_EQ(one.cut.mesh.vertex_uv, two.cut.mesh.vertex_uv);
}

TEST(CutWaterplane, NeedsVertexParameters) {
  Cut c = cut_wigley(4.1);
  SurfaceMesh bare = c.merged.mesh;
  bare.vertex_uv.clear();
  EXPECT_THROW(cut_at_waterplane(c.hull.patches, bare, {}), GeometryError);
}

}  // namespace
}  // namespace hm
