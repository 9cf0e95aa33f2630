// Cuts of the merged fine surface: at the waterplane what stays is the wetted part, the new border
// lies on the plane and on the NURBS, the cut leaves no sliver, and the wetted area and volume of
// a generated Wigley hull match its closed forms; at the centre plane a full hull keeps one half.
#include "unstructured/cut_at_plane.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "quality/hydrostatics.h"
#include "support/hull_spec.h"
#include "support/test_support.h"
#include "tessellate/tessellate.h"
#include "unstructured/merge.h"

namespace hm {
namespace {

struct Cut {
  GeneratedHull hull;
  Tessellation tess;
  MergedSurface merged;
  PlaneCut cut;
};

// A generated hull tessellated at L / 100, merged, and cut.
Cut cut_hull(const HullSpec& spec, const PlaneCutOptions& options) {
  Cut c{generate_hull(spec), {}, {}, {}};
  TessellateOptions o;
  o.edge_length = 1.0;  // L / 100
  c.tess = tessellate(c.hull.patches, o, silent_progress());
  c.merged = merge_patches(c.hull.patches, c.tess.mesh, {}, silent_progress());
  c.cut = cut_at_plane(c.hull.patches, c.merged.mesh, options);
  return c;
}

Cut cut_wigley(double waterline_z, int patches = 4, double snap = 0.3) {
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  spec.patches = patches;
  PlaneCutOptions co;
  co.value = waterline_z;
  co.snap_fraction = snap;
  return cut_hull(spec, co);
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

TEST(CutAtPlane, KeepsTheWettedPartWithItsBorderOnThePlaneAndTheNurbs) {
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
    const Vec3d s =
        evaluate(c.hull.patches[m.vertex_patch[v]].surface, m.vertex_uv[v].x, m.vertex_uv[v].y);
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

TEST(CutAtPlane, SnappingLeavesNoSliverWhereTheLoopWouldMakeOne) {
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

// Faces whose area is at most 1e-6 of their longest side squared.
std::size_t faces_without_area(const SurfaceMesh& m) {
  std::size_t count = 0;
  for (const Face& f : m.faces) {
    double longest = 0;
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, squared_norm(m.positions[f[(k + 1) % 3]] - m.positions[f[k]]));
    }
    count += face_area(m.positions, f) <= 1e-6 * longest;
  }
  return count;
}

// Tessellates the patches at about `triangles`, merges them and cuts at `draft` above their
// lowest point. Every vertex on the plane must lie on its patch (to 1 um) or count as not
// refined (in a gap the merge bridged; at most max_unrefined), and no face may be left without
// area.
void expect_sound_waterline_cut(const std::vector<Patch>& patches, std::size_t triangles,
                                double draft, std::size_t max_unrefined) {
  TessellateOptions o;
  o.edge_length = edge_length_for_triangles(patches, triangles);
  const Tessellation tess = tessellate(patches, o, silent_progress());
  const MergedSurface merged = merge_patches(patches, tess.mesh, {}, silent_progress());
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3d& p : merged.mesh.positions) lowest = std::min(lowest, p.z);
  PlaneCutOptions co;
  co.value = lowest + draft;
  const PlaneCut cut = cut_at_plane(patches, merged.mesh, co);
  const SurfaceMesh& m = cut.mesh;
  EXPECT_LE(cut.report.unconverged, max_unrefined);
  std::size_t on_plane = 0, on_patch = 0;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    if (m.positions[v].z != co.value) continue;
    ++on_plane;
    const Vec3d s =
        evaluate(patches[m.vertex_patch[v]].surface, m.vertex_uv[v].x, m.vertex_uv[v].y);
    on_patch += norm(s - m.positions[v]) < 1e-6;
  }
  EXPECT_GT(on_plane, 50u);
  EXPECT_EQ(on_patch + cut.report.unconverged, on_plane);
  EXPECT_EQ(faces_without_area(m), 0u);
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_EQ(adj.boundary_loops.size(), 1u);
}

// The generated 300-patch round-bilge hull at 10,000 triangles, cut at its draft. A face of
// one patch whose corners both lie on borders, named by their other patches, had its crossing
// refined on a neighbour whose section ends before it: it came out on that neighbour's border,
// 0.12 m along the waterline, on the crossing of the face's other edge, and the face had no
// area.
TEST(CutAtPlane, CrossingsOfFacesBetweenBordersStayOnTheirEdges) {
  HullSpec spec;
  spec.kind = HullKind::kRoundBilge;
  spec.patches = 300;
  expect_sound_waterline_cut(generate_hull(spec).patches, 10000, spec.draft, 0);
}

// A chine hull with gaps and overlaps (the property test's seed 1006), cut below its draft: where
// a patch border runs nearly in the waterplane, the merge bridges a 17 mm gap over 0.4 m of
// waterline, and the border vertices it moved keep their patch's border (u, v). Their edges'
// crossings were refined onto the border, up to 0.3 m away, three of them onto one point. A
// crossing that far from its edge is now sought on the corners' patches, and in a bridged gap
// stays on the bridge (counted as not refined).
TEST(CutAtPlane, CrossingsInABridgedGapStayOnTheirEdges) {
  HullSpec spec = test::hull_spec(HullKind::kChine, 168.811, 14.3579, 4.3493, 6.04267, 6);
  spec.defects.gap = 0.0168811;
  spec.defects.overlap = 0.05;
  spec.defects.seed = 1006;
  expect_sound_waterline_cut(generate_hull(spec).patches, 40000, 2.793356, 10);
}

TEST(CutAtPlane, WigleyWettedAreaAndVolumeMatchTheClosedForm) {
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

TEST(CutAtPlane, KeepBothSplitsTheSurfaceAlongTheWaterlineAndDropsNothing) {
  // The hull meshed above its waterline too: every face lies wholly on one side of the plane,
  // the area is the whole surface's, the wet faces are exactly those of the ordinary cut, and
  // the waterline is a line of interior edges (the outline stays one loop).
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  spec.patches = 4;
  PlaneCutOptions co;
  co.value = 4.1;
  co.keep_both = true;
  co.snap_fraction = 0;  // no vertex moves, so the split faces are the crossed ones
  const Cut both = cut_hull(spec, co);
  co.keep_both = false;
  const Cut wet = cut_hull(spec, co);
  const SurfaceMesh& m = both.cut.mesh;
  double area = 0, merged_area = 0, wet_area = 0, below_area = 0;
  for (const Face& f : m.faces) {
    bool above = false, below = false;
    for (int k = 0; k < corner_count(f); ++k) {
      above |= m.positions[f[k]].z > co.value;
      below |= m.positions[f[k]].z < co.value;
    }
    EXPECT_FALSE(above && below);
    area += face_area(m.positions, f);
    if (!above) below_area += face_area(m.positions, f);
  }
  for (const Face& f : both.merged.mesh.faces)
    merged_area += face_area(both.merged.mesh.positions, f);
  for (const Face& f : wet.cut.mesh.faces) wet_area += face_area(wet.cut.mesh.positions, f);
  // The new vertices lie on the NURBS, not on the chords they split: the area moves by the chord
  // error's order (1e-4 L edges), not more.
  EXPECT_NEAR(area / merged_area, 1, 1e-5);
  EXPECT_NEAR(below_area / wet_area, 1, 1e-12);
  EXPECT_GT(both.cut.report.faces_split, 20u);
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  EXPECT_EQ(adj.boundary_loops.size(), 1u);
  std::size_t waterline_edges = 0;
  for (const MeshEdge& e : adj.edges) {
    if (m.positions[e.v0].z == co.value && m.positions[e.v1].z == co.value) {
      EXPECT_EQ(e.uses, 2u);
      ++waterline_edges;
    }
  }
  EXPECT_GT(waterline_edges, 50u);
}

TEST(CutAtPlane, SameArraysWithOneTwoAndEightThreads) {
  const Cut one = hm::test::with_threads(1, [] { return cut_wigley(3.3, 12); });
  for (int threads : {2, 8}) {
    const Cut two = hm::test::with_threads(threads, [] { return cut_wigley(3.3, 12); });
    EXPECT_EQ(one.cut.mesh.positions, two.cut.mesh.positions) << threads;
    EXPECT_EQ(one.cut.mesh.faces, two.cut.mesh.faces) << threads;
    EXPECT_EQ(one.cut.mesh.vertex_uv, two.cut.mesh.vertex_uv) << threads;
  }
}

// A full Wigley hull's halves meet at y = 0 (keel, stem and stern lie in the centre plane), so the
// centre-plane cut keeps the port half exactly, with the centre plane as its open side.
TEST(CutAtPlane, CentrePlaneKeepsThePortHalfOfAFullHull) {
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  spec.patches = 8;
  spec.full_hull = true;
  PlaneCutOptions co;
  co.axis = 1;
  co.value = 0;
  co.keep_below = false;
  const Cut c = cut_hull(spec, co);
  const SurfaceMesh& merged = c.merged.mesh;
  const EdgeAdjacency before = build_edge_adjacency(merged.faces, merged.vertex_count());
  ASSERT_TRUE(before.nonmanifold_edges.empty());
  ASSERT_TRUE(before.inconsistent_edges.empty());
  const SurfaceMesh& m = c.cut.mesh;
  double area = 0, full = 0;
  for (const Face& f : m.faces) area += face_area(m.positions, f);
  for (const Face& f : merged.faces) full += face_area(merged.positions, f);
  EXPECT_NEAR(area / full, 0.5, 1e-3);
  for (const Vec3d& p : m.positions) ASSERT_GE(p.y, 0.0);
  // The open side now includes the centre plane, exactly at y = 0 (the rest is the deck edge).
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  std::size_t on_centre = 0;
  for (const auto& e : adj.edges) {
    if (e.uses != 1) continue;
    on_centre += m.positions[e.v0].y == 0 && m.positions[e.v1].y == 0;
  }
  EXPECT_GT(on_centre, 20u);
}

// The same machinery on another axis, through the middle of a round-bilge hull's patches (a
// buttock at y = 2 m, keeping the part inboard of it): splits happen, the new border lies on the
// plane exactly and on the NURBS, and the surface stays manifold.
// A full round-bilge hull with gaps (the property test's seed 1000 with gaps allowed on full
// hulls): its keel vertices lie at y = 1e-19, not 0, on lines none of whose edges cross y = 0,
// so the snap left them there. Every edge from one of them across the plane got a new vertex
// where the vertex already was: 661 faces with no area after the centre-plane cut. A vertex
// within the refinement tolerance of the plane is now on it.
TEST(CutAtPlane, VerticesARoundOffFromThePlaneAreOnIt) {
  HullSpec spec =
      test::hull_spec(HullKind::kRoundBilge, 62.833, 5.29959, 1.45248, 1.9981, 2, /*full=*/true);
  spec.defects.gap = 0.0062833;
  spec.defects.duplicate_points = true;
  spec.defects.seed = 1000;
  const GeneratedHull hull = generate_hull(spec);
  TessellateOptions o;
  o.edge_length = edge_length_for_triangles(hull.patches, 10000);
  const Tessellation tess = tessellate(hull.patches, o, silent_progress());
  const MergedSurface merged = merge_patches(hull.patches, tess.mesh, {}, silent_progress());
  std::size_t hair_off = 0;
  for (const Vec3d& p : merged.mesh.positions) hair_off += p.y != 0 && std::abs(p.y) < 1e-12;
  EXPECT_GT(hair_off, 0u);  // what the case is about
  PlaneCutOptions co;
  co.axis = 1;
  co.value = 0;
  co.keep_below = false;
  const PlaneCut cut = cut_at_plane(hull.patches, merged.mesh, co);
  const SurfaceMesh& m = cut.mesh;
  EXPECT_EQ(faces_without_area(m), 0u);
  std::size_t still_off = 0;
  for (const Vec3d& p : m.positions) still_off += p.y != 0 && p.y < 1e-12;
  EXPECT_EQ(still_off, 0u);
}

// A generated full hull with defects, as `hullmesh generate` writes it (a bare type 128 has no
// flag to say it is reversed), tessellated to about `triangles`, merged, and cut at y = 0
// keeping the port half.
struct FullHullCut {
  MergedSurface merged;
  PlaneCut cut;
};
FullHullCut centre_cut_of_merged(const HullSpec& spec, std::size_t triangles) {
  std::vector<Patch> patches = generate_hull(spec).patches;
  for (Patch& p : patches) p.reversed = false;
  TessellateOptions o;
  o.edge_length = edge_length_for_triangles(patches, triangles);
  const Tessellation tess = tessellate(patches, o, silent_progress());
  FullHullCut out;
  out.merged = merge_patches(patches, tess.mesh, {}, silent_progress());
  PlaneCutOptions co;
  co.axis = 1;
  co.value = 0;
  co.keep_below = false;
  out.cut = cut_at_plane(patches, out.merged.mesh, co);
  return out;
}

// The property test's old seed 1019: a full round-bilge hull with overlaps and flipped patches,
// whose keel the weld left 0.2 mm off the centre plane, on the dropped side. Each face at the
// keel had two edges crossing the plane within a thousandth of their length of one keel vertex,
// and both crossings, refined onto the patch's border in the plane, met at one point: a face
// with no area. The keel, a line running in the plane, is put on it first.
TEST(CutAtPlane, ALineRunningInThePlaneAHairOffItIsOnIt) {
  HullSpec spec =
      test::hull_spec(HullKind::kRoundBilge, 62.1315, 5.19313, 1.36921, 1.72714, 12, /*full=*/true);
  spec.defects.overlap = 0.05;
  spec.defects.flip_every = 2;
  spec.defects.seed = 1019;
  const FullHullCut c = centre_cut_of_merged(spec, 10000);
  std::size_t keel_off = 0;  // what the case is about
  for (const Vec3d& p : c.merged.mesh.positions) keel_off += p.y < -1e-5 && p.y > -1e-3;
  EXPECT_GT(keel_off, 0u);
  EXPECT_EQ(faces_without_area(c.cut.mesh), 0u);
}

// The property test's seed 1107 (of 160): a full round-bilge hull, 81.9 m, with overlaps and every
// third patch flipped. Under the centre-plane cut two edges of a face at its keel crossed the
// plane and were both refined to one point, where their patch's border meets the plane: the kept
// triangle between them had no area (2 of them, at x = 22.9 and 46.3 m). Crossings refined to
// one point are now one vertex, and the face between them goes.
TEST(CutAtPlane, CrossingsRefinedToOnePointAreOneVertex) {
  for (std::size_t triangles : {10000u, 20000u, 40000u}) {
    SCOPED_TRACE(triangles);
    HullSpec spec = test::hull_spec(HullKind::kRoundBilge, 81.9198, 7.61257, 2.52026, 3.16897, 16,
                                    /*full=*/true);
    spec.defects.overlap = 0.05;
    spec.defects.flip_every = 3;
    spec.defects.seed = 1107;
    const FullHullCut c = centre_cut_of_merged(spec, triangles);
    EXPECT_EQ(faces_without_area(c.cut.mesh), 0u);
    const EdgeAdjacency adj = build_edge_adjacency(c.cut.mesh.faces, c.cut.mesh.vertex_count());
    EXPECT_TRUE(adj.nonmanifold_edges.empty());
  }
}

TEST(CutAtPlane, AButtockCutSplitsAlongTheYAxisAsTheWaterplaneDoesAlongZ) {
  HullSpec spec;
  spec.kind = HullKind::kRoundBilge;
  spec.patches = 24;
  PlaneCutOptions co;
  co.axis = 1;
  co.value = 2.0;
  const Cut c = cut_hull(spec, co);
  const PlaneCut& cut = c.cut;
  const GeneratedHull& hull = c.hull;
  const SurfaceMesh& m = cut.mesh;
  EXPECT_GT(cut.report.faces_split, 50u);
  EXPECT_EQ(cut.report.unconverged, 0u);
  std::size_t on_plane = 0;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    ASSERT_LE(m.positions[v].y, 2.0);
    if (m.positions[v].y != 2.0) continue;
    ++on_plane;
    const Vec3d s =
        evaluate(hull.patches[m.vertex_patch[v]].surface, m.vertex_uv[v].x, m.vertex_uv[v].y);
    EXPECT_NEAR(norm(s - m.positions[v]), 0, 1e-7) << "vertex " << v;
  }
  EXPECT_GT(on_plane, 50u);
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
}

TEST(CutAtPlane, NeedsVertexParameters) {
  Cut c = cut_wigley(4.1);
  SurfaceMesh bare = c.merged.mesh;
  bare.vertex_uv.clear();
  EXPECT_THROW(cut_at_plane(c.hull.patches, bare, {}), GeometryError);
  PlaneCutOptions bad;
  bad.axis = 3;
  EXPECT_THROW(cut_at_plane(c.hull.patches, c.merged.mesh, bad), GeometryError);
}

}  // namespace
}  // namespace hm
