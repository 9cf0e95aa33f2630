// Merging patch triangulations: generated hulls with injected defects (gaps, duplicated points,
// wrong orientation flags, a pairwise overlap) and the real hulls in ../shared/data/hulls.
#include "unstructured/merge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "iges/read_iges.h"
#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "support/hull_spec.h"
#include "support/test_support.h"
#include "tessellate/tessellate.h"
#include "unstructured/features.h"
#include "unstructured/merge_steps.h"
#include "unstructured/merge_support.h"

namespace hm {
namespace {

using test::expect_clean_half_hull;
using test::generated;
using test::merge_of;
using test::Merged;
using test::total_area;

TEST(Merge, CleanMultiPatchHullsBecomeOneSurface) {
  for (HullKind kind : {HullKind::kWigley, HullKind::kRoundBilge, HullKind::kChine}) {
    const Merged m = merge_of(generated(kind, 24).patches);
    expect_clean_half_hull(m, to_string(kind));
    // Merging moves vertices along shared borders only: the area stays that of the patches.
    EXPECT_NEAR(total_area(m.merged.mesh) / total_area(m.tess.mesh), 1.0, 1e-3);
    EXPECT_TRUE(m.merged.report.patches_flipped.empty());
  }
}

// 300 round-bilge patches at 40,000 triangles: near the keel, a border vertex one short edge
// from a patch corner was split into the next patch's border edge at that corner while its own
// neighbour was already welded there, giving an edge a third face (found by compare-peers).
TEST(Merge, ManySmallPatchesMeetAtTheCentrePlaneWithoutAThirdFace) {
  const std::vector<Patch> patches = generated(HullKind::kRoundBilge, 300).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 40000));
  expect_clean_half_hull(m, "round-bilge, 300 patches");
}

// Two patches whose borders come within tolerance of each other across the tip of a third,
// narrower there than the tolerance, welded straight across it, and the tip lay on their seam
// with a third face on one edge (kcs.iges at 40,000 triangles: patch 53's tip between patches
// 10 and 21 on the flat side; the generated 300-patch chine hull likewise). The snap was tried
// again with a smaller tolerance there; since 2026-12-06 a vertex on the tip's border is not
// welded to one across the tip in the first place, and neither merge needs the retry (the
// retry's own test is Merge.FoldedHoleIsSnappedAgainAndCloses below, which still does).
TEST(Merge, ThirdPatchTipBetweenTwoCloseBordersGetsNoThirdFace) {
  const std::vector<Patch> patches = generated(HullKind::kChine, 300).patches;
  const Merged chine = merge_of(patches, edge_length_for_triangles(patches, 40000));
  expect_clean_half_hull(chine, "chine, 300 patches");
  HM_REQUIRE_SHARED_HULL(path, "kcs.iges");
  const ImportResult hull = read_iges_file(path.string());
  expect_clean_half_hull(merge_of(hull.patches, edge_length_for_triangles(hull.patches, 40000)),
                         "kcs.iges");
}

// Unit squares in the plane y = 0: for patch p, columns x0 .. x0 + nx and rows 0 .. nz, their
// corners shared by position with what is already in w.
void add_grid(merge::Work& w, PatchId p, double x0, int nx, int nz, double top_lift = 0) {
  SurfaceMesh& m = w.mesh;
  auto vertex = [&](double x, double z) {
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      if (std::abs(m.positions[v].x - x) < 1e-9 && std::abs(m.positions[v].z - z) < 1e-6) {
        return Index(v);
      }
    }
    m.positions.push_back({x, 0.0, z});
    m.vertex_patch.push_back(p);
    m.vertex_uv.push_back({});
    w.vert_old.push_back(Index(w.vert_old.size()));
    return Index(m.positions.size() - 1);
  };
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      const double za = k, zb = k + 1 == nz ? nz + top_lift : k + 1;
      const Index a = vertex(x0 + i, za), b = vertex(x0 + i + 1, za);
      const Index c = vertex(x0 + i + 1, zb), d = vertex(x0 + i, zb);
      m.faces.push_back({a, b, c, kInvalid});
      m.faces.push_back({a, c, d, kInvalid});
      m.face_patch.insert(m.face_patch.end(), {p, p});
      w.face_old.insert(w.face_old.end(), {Index(w.face_old.size()), Index(w.face_old.size() + 1)});
    }
  }
}

std::vector<OpenGap> open_gaps_of(const merge::Work& w) {
  const EdgeAdjacency adj = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  return merge::find_open_gaps(w, adj, MergeOptions{});
}

// A low side (patch 0, 4 m long, 1 m high, its top a rounding error above 1 m) meets a raised
// side (patch 1, 3 m high) at x = 4 m; the raised side's aft border runs up from where the low
// top ends. The low top runs on past that corner: no gap (ship_449_patches.iges reported one,
// 1.75 m "wide", between patches 305 and 345 at x = -48.5 m). The same sides 0.6 m apart, rows
// level, do face each other across a gap, though every foot there lies at an edge's end (until
// 2026-12-04 no such foot counted, and this gap went unreported).
TEST(MergeSteps, BorderRunningOnPastACornerIsNoGapButAlignedBordersApartAre) {
  merge::Work step;
  add_grid(step, 0, 0.0, 4, 1, 1e-12);
  add_grid(step, 1, 4.0, 2, 3);
  EXPECT_TRUE(open_gaps_of(step).empty());

  merge::Work apart;
  add_grid(apart, 0, 0.0, 3, 2);
  add_grid(apart, 1, 3.6, 3, 2);
  const std::vector<OpenGap> gaps = open_gaps_of(apart);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_EQ(gaps[0].patch_a, 0u);
  EXPECT_EQ(gaps[0].patch_b, 1u);
  EXPECT_NEAR(gaps[0].width, 0.6, 1e-12);
  EXPECT_EQ(gaps[0].vertices, 2u);  // the middle row, both sides (the corners are corners)
}

// A slit: from x = 0 to 4, patch 0's top border at y = 1 (vertices at x = 0 .. 4) and patch 1's
// bottom border 2 cm above it (vertices at x = 0.5 .. 3.5, half a step along); beyond, the two
// patches share their border. The closed loop between them has 9 vertices and a perimeter of
// 8 m, far beyond a pinhole, but it is 2 cm wide where the gap tolerance is half a 1 m edge: a
// gap the snap left (the generated 1,000-patch chine hull at 400,000 triangles had one at its
// transom, 0.30 m round). It closes, unfolded; the outline stays open.
TEST(MergeSteps, SlitBetweenTwoBordersIsClosed) {
  merge::Work w;
  SurfaceMesh& m = w.mesh;
  auto vertex = [&](double x, double y, PatchId p) {
    m.positions.push_back({x, y, 0});
    m.vertex_patch.push_back(p);
    m.vertex_uv.push_back({});
    w.vert_old.push_back(Index(w.vert_old.size()));
    return Index(m.positions.size() - 1);
  };
  auto face = [&](Index a, Index b, Index c, PatchId p) {
    m.faces.push_back({a, b, c, kInvalid});
    m.face_patch.push_back(p);
    w.face_old.push_back(Index(w.face_old.size()));
  };
  // Rows from x = -1 to 5: y = 0 and y = 1 (patch 0), y = 2 (patch 1); patch 1's lower border c
  // runs along b but for the slit, 2 cm above it from x = 0 to 4 (so the slit is inside).
  std::vector<Index> a, b, c, d;
  for (int i = -1; i <= 5; ++i) a.push_back(vertex(i, 0, 0));
  for (int i = -1; i <= 5; ++i) b.push_back(vertex(i, 1, 0));
  c = {b[0], b[1]};
  for (int i = 0; i < 4; ++i) c.push_back(vertex(i + 0.5, 1.02, 1));
  c.insert(c.end(), {b[5], b[6]});
  for (int i = -1; i <= 5; ++i) d.push_back(vertex(i, 2, 1));
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    face(a[i], a[i + 1], b[i + 1], 0);
    face(a[i], b[i + 1], b[i], 0);
  }
  // Zip c to d by x, counter-clockwise seen from +z like patch 0.
  for (std::size_t i = 0, j = 0; i + 1 < c.size() || j + 1 < d.size();) {
    const bool step_c = j + 1 == d.size() ||
                        (i + 1 < c.size() && m.positions[c[i + 1]].x <= m.positions[d[j + 1]].x);
    if (step_c) {
      face(c[i], c[i + 1], d[j], 1);
      ++i;
    } else {
      face(c[i], d[j + 1], d[j], 1);
      ++j;
    }
  }
  const EdgeAdjacency before = build_edge_adjacency(m.faces, m.vertex_count());
  ASSERT_TRUE(before.nonmanifold_edges.empty());
  ASSERT_TRUE(before.inconsistent_edges.empty());
  ASSERT_EQ(before.boundary_loops.size(), 2u);
  const double area = total_area(m);

  // With a gap tolerance of 5 mm the slit is wider than a gap, and stays.
  merge::Work kept = w;
  MergeOptions narrow;
  narrow.gap_tolerance = 0.005;
  EXPECT_EQ(merge::fill_small_holes(kept, before, narrow).filled, 0u);
  EXPECT_EQ(kept.mesh.faces.size(), m.faces.size());

  EXPECT_EQ(merge::fill_small_holes(w, before, MergeOptions{}).filled, 1u);
  const EdgeAdjacency after = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(after.nonmanifold_edges.empty());
  EXPECT_TRUE(after.inconsistent_edges.empty());
  EXPECT_EQ(after.boundary_loops.size(), 1u);
  EXPECT_NEAR(total_area(m), area + 2 * 0.5 * 0.02 / 2 + 3 * 0.02, 1e-9);       // the slit's own
  for (const Face& f : m.faces) EXPECT_GT(face_normal(m.positions, f).z, 0.0);  // none folded
}

// A hole of four vertices whose shorter diagonal is already an edge of the mesh (a fin stands on
// it here; on the generated 1,000-patch round-bilge hull at 40,000 triangles it was a fold of
// the snap at the transom). Closing the hole along that diagonal gave the edge a third face;
// the other diagonal closes it cleanly.
// A 3 x 3 grid of unit squares in z = 0 over patches 0 and 1 with its middle square open, corner
// (2, 2) pulled in to (1.8, 1.8) so that the diagonal (1, 1)-(2, 2) is the shorter one, and a fin
// (patch 2) standing on each diagonal named in `fins`: 0 for (1, 1)-(2, 2), 1 for (2, 1)-(1, 2).
merge::Work grid_with_hole(std::initializer_list<int> fins) {
  merge::Work w;
  SurfaceMesh& m = w.mesh;
  auto at = [](int i, int j) { return Index(4 * j + i); };
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) m.positions.push_back({double(i), double(j), 0.0});
  }
  m.positions[at(2, 2)] = {1.8, 1.8, 0.0};
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      if (i == 1 && j == 1) continue;  // the hole
      const PatchId p = i < 2 ? 0 : 1;
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), kInvalid});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1), kInvalid});
      m.face_patch.insert(m.face_patch.end(), {p, p});
    }
  }
  for (int fin : fins) {
    const Index top = Index(m.positions.size());
    m.positions.push_back({1.4, 1.4, fin == 0 ? 1.0 : -1.0});
    m.faces.push_back(fin == 0 ? Face{at(1, 1), at(2, 2), top, kInvalid}
                               : Face{at(2, 1), at(1, 2), top, kInvalid});
    m.face_patch.push_back(2);
  }
  m.vertex_patch.assign(m.positions.size(), 0);
  test::number_as_input(w);
  return w;
}

// A hole of four vertices whose shorter diagonal is already an edge of the mesh (a fin stands on
// it here; on the generated 1,000-patch round-bilge hull at 40,000 triangles it was a fold of
// the snap at the transom). Closing the hole along that diagonal gave the edge a third face;
// the other diagonal closes it cleanly.
TEST(MergeSteps, SmallHoleIsNotClosedAlongAnExistingEdge) {
  merge::Work w = grid_with_hole({0});
  const SurfaceMesh& m = w.mesh;
  const EdgeAdjacency before = build_edge_adjacency(m.faces, m.vertex_count());
  ASSERT_TRUE(before.nonmanifold_edges.empty());
  std::vector<std::array<Index, 2>> left_open;
  EXPECT_EQ(merge::fill_small_holes(w, before, MergeOptions{}, &left_open).filled, 1u);
  EXPECT_TRUE(left_open.empty());
  const EdgeAdjacency after = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(after.nonmanifold_edges.empty());
  EXPECT_TRUE(after.inconsistent_edges.empty());
  EXPECT_EQ(after.boundary_loops.size(), before.boundary_loops.size() - 1);
  EXPECT_EQ(m.face_count(), 19u);  // 16 round the hole, the fin, and the two new faces
}

// With both diagonals edges already, the hole stays open, and its four edges are named as left
// open: the merge snaps again with a smaller tolerance there.
TEST(MergeSteps, HoleWithBothDiagonalsTakenIsNamedAsLeftOpen) {
  merge::Work w = grid_with_hole({0, 1});
  const std::size_t faces = w.mesh.face_count();
  const EdgeAdjacency before = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  std::vector<std::array<Index, 2>> left_open;
  EXPECT_EQ(merge::fill_small_holes(w, before, MergeOptions{}, &left_open).filled, 0u);
  EXPECT_EQ(w.mesh.face_count(), faces);
  ASSERT_EQ(left_open.size(), 4u);
  std::set<Index> corners;
  for (const auto& [a, b] : left_open) corners.insert({a, b});
  EXPECT_EQ(corners, (std::set<Index>{5, 6, 9, 10}));
}

// A 3 x 3 grid of unit cells (patch 0 below y = 1, patch 1 above) whose middle upper cell is
// fanned from a vertex b at (1.5, b_y) instead of the cell's corner (1, 1)-(2, 1) edge: the faces
// along that edge leave a hole of three vertices, (1, 1), b and (2, 1).
merge::Work grid_with_three_vertex_hole(double b_y) {
  merge::Work w;
  SurfaceMesh& m = w.mesh;
  auto at = [](int i, int j) { return Index(4 * j + i); };
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) m.positions.push_back({double(i), double(j), 0.0});
  }
  const Index b = Index(m.positions.size());
  m.positions.push_back({1.5, b_y, 0.0});
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      const PatchId p = j == 0 ? 0 : 1;
      if (i == 1 && j == 1) {
        m.faces.push_back({at(1, 1), b, at(1, 2), kInvalid});
        m.faces.push_back({b, at(2, 1), at(2, 2), kInvalid});
        m.faces.push_back({b, at(2, 2), at(1, 2), kInvalid});
        m.face_patch.insert(m.face_patch.end(), {p, p, p});
        continue;
      }
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), kInvalid});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1), kInvalid});
      m.face_patch.insert(m.face_patch.end(), {p, p});
    }
  }
  m.vertex_patch.assign(m.positions.size(), 0);
  test::number_as_input(w);
  return w;
}

double smallest_face_area(const SurfaceMesh& m) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Face& f : m.faces) smallest = std::min(smallest, face_area(m.positions, f));
  return smallest;
}

// A vertex left on the border edge across it (a T-junction the snap did not split; the generated
// 300-patch round-bilge hull's transom at 10,000 and 20,000 triangles) makes a hole of three
// vertices with no area. A triangle there had no area either (`--validate` refused it); the face
// across the edge is split at the vertex instead, as a T-junction is.
TEST(MergeSteps, FlatThreeVertexHoleSplitsTheFaceAcross) {
  merge::Work w = grid_with_three_vertex_hole(1.0);
  const SurfaceMesh& m = w.mesh;
  const std::size_t faces = m.face_count();
  const EdgeAdjacency before = build_edge_adjacency(m.faces, m.vertex_count());
  ASSERT_EQ(before.boundary_loops.size(), 2u);
  std::vector<std::array<Index, 2>> left_open;
  EXPECT_EQ(merge::fill_small_holes(w, before, MergeOptions{}, &left_open).filled, 1u);
  EXPECT_TRUE(left_open.empty());
  EXPECT_EQ(m.face_count(), faces + 1);
  EXPECT_GT(smallest_face_area(m), 0.2);  // halves of a unit cell's triangle: 0.25
  const EdgeAdjacency after = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(after.nonmanifold_edges.empty());
  EXPECT_TRUE(after.inconsistent_edges.empty());
  EXPECT_EQ(after.boundary_loops.size(), 1u);
  // Both halves keep the split face's patch (the lower one) and its input triangle.
  EXPECT_EQ(m.face_patch.back(), 0u);
  EXPECT_EQ(w.face_old.size(), m.face_count());
  EXPECT_EQ(m.face_patch[w.face_old.back()], 0u);
}

// A hole of three vertices with area (b well off the edge) still gets its triangle.
TEST(MergeSteps, ThreeVertexHoleWithAreaGetsATriangle) {
  merge::Work w = grid_with_three_vertex_hole(1.2);
  const SurfaceMesh& m = w.mesh;
  const std::size_t faces = m.face_count();
  const EdgeAdjacency before = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_EQ(merge::fill_small_holes(w, before, MergeOptions{}, nullptr).filled, 1u);
  EXPECT_EQ(m.face_count(), faces + 1);
  const Face& added = m.faces.back();
  EXPECT_NEAR(face_area(m.positions, added), 0.1, 1e-12);  // base 1, height 0.2
  EXPECT_GT(dot(face_normal(m.positions, added), Vec3d{0, 0, 1}), 0.99);
  EXPECT_EQ(build_edge_adjacency(m.faces, m.vertex_count()).boundary_loops.size(), 1u);
}

// A slit of five vertices whose two runs cross: patch 0's run A-B-C-D (below, z = 0) and patch
// 1's run D-E-A (above), E above B-C, so that D-E and E-A cross it. The two halves' borders meet
// so along a tight forefoot curve, each sampled at its own points (the property test's seed 1063
// at 40,000 triangles). No ear of it is left once the one at E is clipped; a fan closes it.
TEST(MergeSteps, SlitWhoseRunsCrossIsClosedByAFan) {
  merge::Work w;
  SurfaceMesh& m = w.mesh;
  m.positions = {{0, 0, 0},  {1, 0.2, 0}, {2, 0.2, 0}, {3, 0, 0},  {1.5, 0.25, 0},  // A..E
                 {0, -1, 0}, {1, -1, 0},  {2, -1, 0},  {3, -1, 0},                  // below
                 {0, 1, 0},  {1.5, 1, 0}, {3, 1, 0}};                               // above
  const Index run[4] = {0, 1, 2, 3}, below[4] = {5, 6, 7, 8};
  for (int i = 0; i < 3; ++i) {
    m.faces.push_back({below[i], below[i + 1], run[i + 1], kInvalid});
    m.faces.push_back({below[i], run[i + 1], run[i], kInvalid});
    m.face_patch.insert(m.face_patch.end(), {0, 0});
  }
  m.faces.insert(
      m.faces.end(),
      {{0, 4, 10, kInvalid}, {0, 10, 9, kInvalid}, {4, 3, 11, kInvalid}, {4, 11, 10, kInvalid}});
  m.face_patch.insert(m.face_patch.end(), {1, 1, 1, 1});
  m.vertex_patch = {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 1};
  test::number_as_input(w);
  const std::size_t faces = m.face_count();
  const EdgeAdjacency before = build_edge_adjacency(m.faces, m.vertex_count());
  std::vector<std::array<Index, 2>> left_open;
  EXPECT_EQ(merge::fill_small_holes(w, before, MergeOptions{}, &left_open).filled, 1u);
  EXPECT_TRUE(left_open.empty());
  EXPECT_EQ(m.face_count(), faces + 3);  // five vertices, three faces
  const EdgeAdjacency after = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(after.nonmanifold_edges.empty());
  EXPECT_TRUE(after.inconsistent_edges.empty());
  EXPECT_EQ(after.boundary_loops.size(), 1u);  // the outline
}

// The generated 1,000-patch round-bilge hull at 40,000 triangles: two transom patches (995 and
// 997) snapped so that a vertex of one lay inside a face of the other, which left a hole of four
// vertices whose both diagonals were edges (0.61 m round, reported as a hole). The merge snaps
// again with a smaller tolerance near such a hole, and the hull closes.
TEST(Merge, FoldedHoleIsSnappedAgainAndCloses) {
  const std::vector<Patch> patches = generated(HullKind::kRoundBilge, 1000).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 40000));
  expect_clean_half_hull(m, "round-bilge, 1000 patches");
  EXPECT_GE(m.merged.report.snap_retries, 1u);
}

// A unit square of two triangles (patch 0) whose first triangle patch 1 gives again, wound alike:
// a face given twice keeps one copy, even at a corner of the outline, where two of its edges
// have no other face (dropping both would cut the corner off).
TEST(MergeSteps, FaceGivenTwiceAtACornerKeepsOneCopy) {
  merge::Work w;
  SurfaceMesh& m = w.mesh;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 2, kInvalid}, {0, 2, 3, kInvalid}, {1, 2, 0, kInvalid}};
  m.face_patch = {0, 0, 1};
  m.vertex_patch.assign(4, 0);
  m.vertex_uv.assign(4, {});
  w.face_old = {0, 1, 2};
  w.vert_old = {0, 1, 2, 3};
  EXPECT_EQ(merge::drop_degenerate(w, 1.0), 1u);
  ASSERT_EQ(m.face_count(), 2u);
  EXPECT_NEAR(total_area(m), 1.0, 1e-12);
  EXPECT_EQ(m.vertex_count(), 4u);
}

// A full Wigley hull's two halves meet in the centre plane along keel and stem, and each half's
// corner triangle there lies in that plane: the two are one face given twice, back to back, and
// both go. With one half's patch flipped (not yet turned when the faces are cleaned up) the two
// copies were wound alike, one stayed, and its diagonal had three faces. Both go now, as when
// neither is flipped: the same surface comes out, turned.
TEST(Merge, CentrePlaneCornerOfAFlippedHalfLeavesNoThirdFace) {
  // The property test's seed 1009 with overlaps on (2026-12-04).
  HullSpec spec =
      test::hull_spec(HullKind::kWigley, 121.203, 21.6683, 7.37033, 11.2088, 4, /*full=*/true);
  const Merged plain = merge_of(generate_hull(spec).patches);
  spec.defects.flip_every = 3;
  spec.defects.seed = 1009;
  std::vector<Patch> patches = generate_hull(spec).patches;
  // As `hullmesh generate` writes them: a bare type 128 has no flag to say it is reversed.
  for (Patch& p : patches) p.reversed = false;
  const Merged flipped = merge_of(std::move(patches));
  EXPECT_FALSE(flipped.merged.report.patches_flipped.empty());
  EXPECT_TRUE(flipped.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(flipped.adj.inconsistent_edges.empty());
  EXPECT_EQ(flipped.adj.boundary_loops.size(), 1u);  // the deck edge
  EXPECT_EQ(flipped.merged.mesh.face_count(), plain.merged.mesh.face_count());
  EXPECT_NEAR(flipped.merged.report.enclosed_volume, plain.merged.report.enclosed_volume,
              1e-9 * plain.merged.report.enclosed_volume);
}

// A flat bilinear patch in the plane x = 0 with corners (y, z): a0, a1 along the lower side and
// b0, b1 along the upper one.
Patch plate(Vec2d a0, Vec2d a1, Vec2d b0, Vec2d b1) {
  Patch p;
  NurbsSurface& s = p.surface;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.points = {{0, a0.x, a0.y}, {0, a1.x, a1.y}, {0, b0.x, b0.y}, {0, b1.x, b1.y}};
  s.weights = {1, 1, 1, 1};
  p.wrapping = Wrapping::kGenerated;
  return p;
}

// A transom cut into rows, the lowest ones strips narrower than the gap tolerance (half the 1 m
// border edge). Snapping moved a strip's sides across it, onto the same neighbour or the patch
// beyond, and folded the strips into edges with three and four faces.
TEST(Merge, StripsNarrowerThanTheToleranceKeepTheirWidth) {
  const std::vector<Patch> patches = {
      plate({0, 0.3}, {4, 0.35}, {0, 3}, {4, 3}),         // the transom above
      plate({0, 0.21}, {4, 0.25}, {0, 0.3}, {4, 0.35}),   // a strip 9 to 10 cm tall
      plate({0, 0.17}, {4, 0.20}, {0, 0.21}, {4, 0.25}),  // and one of 4 to 5 cm
      plate({0, 0}, {4, 0}, {0, 0.17}, {4, 0.20})};
  const Merged m = merge_of(patches, 1.0);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  EXPECT_NEAR(total_area(m.merged.mesh), 4 * 3, 1e-9 * 12);  // no face folds over another
}

// The generated chine hull of 1,000 patches: its transom rows and the strips at the chine are
// narrower than the gap tolerance. Vertices of the patches on either side of such a strip are
// close to each other, with the strip between them. A close pair like that is welded only
// when no third patch lies between the two vertices, or edges get three and four faces (9
// here before that rule, with the own-width limit alone).
TEST(Merge, NoWeldAcrossAThirdPatch) {
  const std::vector<Patch> patches = generated(HullKind::kChine, 1000).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 128000));
  expect_clean_half_hull(m, "chine, 1000 patches");
}

// A full Wigley hull as two halves: they meet at the stem, stern and keel at well under 60
// degrees (the fold test alone kept that seam open), and at each end-keel corner both halves
// have a triangle lying in the centre plane, which the welds lay back to back. The result is
// one closed hull open only along its deck edge.
TEST(Merge, FullHullHalvesCloseAlongSharpEndsAndKeel) {
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  spec.patches = 8;
  spec.full_hull = true;
  const Merged m = merge_of(generate_hull(spec).patches);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  ASSERT_EQ(m.adj.boundary_loops.size(), 1u);
  double top = -1e300;
  for (const Vec3d& p : m.merged.mesh.positions) top = std::max(top, p.z);
  for (Index v : m.adj.boundary_loops[0].vertices) {
    EXPECT_NEAR(m.merged.mesh.positions[v].z, top, 1e-6) << "an open edge below the deck";
  }
  EXPECT_GT(m.merged.report.enclosed_volume, 0.0);
}

// The two halves of a full round-bilge hull meet in the centre plane along its forefoot, where
// the halves lie well inside the snap's fold test of 60 degrees of each other, and each half's
// border there is sampled at its own points along the same curve. A vertex of one run lies on
// an edge of the other (3.8 mm off a 0.26 m chord): it must be split in, not refused as a fold
// (the property test's seed 1028 left a hole 2.1 m round there, 3 free edges below its
// waterline).
TEST(Merge, HalvesSampledApartAlongAFineForefootMeetVertexToVertex) {
  const HullSpec spec =
      test::hull_spec(HullKind::kRoundBilge, 91.8418, 13.4708, 3.64385, 5.50769, 7, /*full=*/true);
  const Merged m = merge_of(generate_hull(spec).patches);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  // Snapped, not filled: a fan across the slit would fold its faces.
  EXPECT_EQ(m.merged.report.holes_filled, 0u);
  ASSERT_EQ(m.adj.boundary_loops.size(), 1u);  // the deck edge
  double top = -1e300;
  for (const Vec3d& p : m.merged.mesh.positions) top = std::max(top, p.z);
  for (Index v : m.adj.boundary_loops[0].vertices) {
    EXPECT_NEAR(m.merged.mesh.positions[v].z, top, 1e-6) << "an open edge below the deck";
  }
}

// A full hull's halves a gap apart (the property test's 1e-4 L): where they meet at a fine stem
// or forefoot their borders are mirrored across the gap, well inside the fold test's 60 degrees
// of each other, and where the hull is a fin of no thickness (a round-bilge forefoot, a Wigley's
// keel ends) they lie back to back a hair apart. Until 2026-12-04 (evening) the seam stayed
// open there: 134 and 87 border vertices below the deck on these Wigley and round-bilge hulls.
TEST(Merge, FullHullHalvesWithGapsCloseBelowTheDeck) {
  for (HullKind kind : {HullKind::kWigley, HullKind::kRoundBilge, HullKind::kChine}) {
    HullSpec spec;
    spec.kind = kind;
    spec.patches = 8;
    spec.full_hull = true;
    spec.defects.gap = 1e-4 * spec.length;
    const Merged m = merge_of(generate_hull(spec).patches);
    SCOPED_TRACE(to_string(kind));
    EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
    EXPECT_TRUE(m.adj.inconsistent_edges.empty());
    double top = -1e300;
    for (const Vec3d& p : m.merged.mesh.positions) top = std::max(top, p.z);
    std::size_t below_deck = 0;
    for (const BoundaryLoop& loop : m.adj.boundary_loops) {
      for (Index v : loop.vertices) below_deck += m.merged.mesh.positions[v].z < top - 1e-6;
    }
    EXPECT_EQ(below_deck, 0u) << "open edges below the deck";
    EXPECT_GT(m.merged.report.enclosed_volume, 0.0);
  }
}

// The fold test's exceptions for the two halves of a full hull hold in the centre plane only.
// Elsewhere one patch's border can lie along another's, both on the same side, 12 degrees
// apart, where the overlap cut left a remnant (the 100-patch chine hull with 0.1 m gaps and 5%
// overlaps at 40,000 triangles, at x = 86.6 m on the chine): stitched, it left two holes.
TEST(Merge, OverlapRemnantOffTheCentrePlaneIsNotStitchedAsAWedge) {
  const std::vector<Patch> plain = generated(HullKind::kChine, 100).patches;
  HullDefects d;
  d.gap = 0.1;
  d.overlap = 0.05;
  const Merged m = merge_of(generated(HullKind::kChine, 100, d).patches,
                            edge_length_for_triangles(plain, 40000));
  expect_clean_half_hull(m, "chine, 100 patches, gaps and overlaps");
}

// The generated 1,000-patch chine hull at its default size (about 4 triangles a patch) left 20
// gaps open along its keel in the centre plane, 33.7 m of hole, from 2026-12-02 until the
// crossing-slit fan of 2026-12-04 (evening): slits whose two runs cross, where the ears ran out.
TEST(Merge, ThousandPatchChineHullClosesAlongItsKeelAtTheDefaultSize) {
  expect_clean_half_hull(merge_of(generated(HullKind::kChine, 1000).patches),
                         "chine, 1000 patches");
}

TEST(Merge, ClosesGapsOfOneThousandthOfTheLength) {
  HullDefects d;
  d.gap = 0.1;  // 1e-3 L
  const Merged m = merge_of(generated(HullKind::kWigley, 24, d).patches);
  expect_clean_half_hull(m, "wigley, 0.1 m gaps");
  EXPECT_GT(m.merged.report.gaps_closed, 0u);
  EXPECT_GT(m.merged.report.widest_gap_closed, 0.04);
  EXPECT_LT(m.merged.report.widest_gap_closed, 0.2);
  EXPECT_TRUE(m.merged.report.open_gaps.empty());
}

// On a fine tessellation a gap of 1e-3 L is wider than the default tolerance (half the local
// border edge). Where a gap stays open, the snap runs again with each open border vertex's
// tolerance widened to 1.25 times the gap measured there. The chine hull with 0.1 m gaps at
// 128,000 triangles kept 21 loops without that, 8 with it (2026-12-04).
TEST(Merge, OpenGapsAreSnappedAgainToTheirMeasuredWidth) {
  HullDefects d;
  d.gap = 0.1;  // 1e-3 L
  const std::vector<Patch> patches = generated(HullKind::kChine, 24, d).patches;
  const double edge = edge_length_for_triangles(patches, 128000);
  MergeOptions fixed;
  fixed.widen_to_gaps = false;
  const Merged before = merge_of(patches, edge, fixed);
  const Merged after = merge_of(patches, edge);
  EXPECT_EQ(before.merged.report.gap_vertices_widened, 0u);
  EXPECT_GT(after.merged.report.gap_vertices_widened, 0u);
  EXPECT_LE(after.merged.report.widened_to, 2e-3 * 100 + 1e-9);  // at most 2e-3 L
  EXPECT_LT(after.adj.boundary_loops.size(), before.adj.boundary_loops.size() / 2);
  EXPECT_TRUE(after.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(after.adj.inconsistent_edges.empty());
  EXPECT_LT(after.merged.report.open_gaps.size(), before.merged.report.open_gaps.size());
}

// Where a gap is wider than the border edges on both sides, no vertex of one border comes near
// the other's, and the snap leaves it open at any tolerance: a thin loop along two patches. Such
// loops are zipped shut. The Wigley hull with 0.1 m gaps (1e-3 L) at 128,000 triangles kept 24
// loops (312 m of hole) before; one, its outline, after.
TEST(Merge, GapsWiderThanTheBorderEdgesAreZippedShut) {
  HullDefects d;
  d.gap = 0.1;  // 1e-3 L
  const std::vector<Patch> clean_patches = generated(HullKind::kWigley, 24).patches;
  const std::vector<Patch> patches = generated(HullKind::kWigley, 24, d).patches;
  const double edge = edge_length_for_triangles(patches, 128000);
  MergeOptions plain;
  plain.widen_to_gaps = false;
  plain.bridge_gaps = false;
  const Merged before = merge_of(patches, edge, plain);
  const Merged after = merge_of(patches, edge);
  const Merged clean = merge_of(clean_patches, edge);
  EXPECT_GE(before.adj.boundary_loops.size(), 20u);
  EXPECT_GT(after.merged.report.gaps_bridged, 0u);
  expect_clean_half_hull(after, "wigley, 24 patches, 0.1 m gaps, 128,000 triangles");
  // The bridges stand where the hull is: its volume is the clean hull's.
  EXPECT_NEAR(after.merged.report.enclosed_volume / clean.merged.report.enclosed_volume, 1.0, 2e-3);
}

// A clean hull has no open gap, and merges as it did without the widening: byte for byte.
TEST(Merge, CleanHullIsNotSnappedAgain) {
  const std::vector<Patch> patches = generated(HullKind::kRoundBilge, 300).patches;
  const double edge = edge_length_for_triangles(patches, 40000);
  MergeOptions fixed;
  fixed.widen_to_gaps = false;
  const Merged a = merge_of(patches, edge, fixed), b = merge_of(patches, edge);
  EXPECT_EQ(b.merged.report.gap_vertices_widened, 0u);
  EXPECT_EQ(a.merged.mesh.faces, b.merged.mesh.faces);
  EXPECT_EQ(a.merged.mesh.positions, b.merged.mesh.positions);
}

TEST(Merge, ReportsGapsWiderThanTheTolerance) {
  HullDefects d;
  d.gap = 0.1;
  Merged m;
  m.patches = generated(HullKind::kWigley, 4, d).patches;
  m.tess = tessellate(m.patches, {}, silent_progress());
  MergeOptions o;
  o.gap_tolerance = 0.02;  // narrower than the gaps
  m.merged = merge_patches(m.patches, m.tess.mesh, o, silent_progress());
  ASSERT_FALSE(m.merged.report.open_gaps.empty());
  // Straight across a side the gap is 0.1 m; the widest point of a stretch may lie where patch
  // corners meet and the borders no longer face each other, so only a lower bound is exact.
  for (const OpenGap& g : m.merged.report.open_gaps) {
    EXPECT_LT(g.patch_a, g.patch_b);
    EXPECT_GT(g.width, 0.08);
    EXPECT_GT(g.vertices, 0u);
  }
  // The gaps stay open: the outline is not the only boundary.
  EXPECT_GT(
      build_edge_adjacency(m.merged.mesh.faces, m.merged.mesh.vertex_count()).boundary_loops.size(),
      1u);
}

TEST(Merge, DuplicatedPointsChangeNothing) {
  HullDefects d;
  d.duplicate_points = true;
  const Merged m = merge_of(generated(HullKind::kRoundBilge, 24, d).patches);
  expect_clean_half_hull(m, "round bilge, duplicated points");
}

TEST(Merge, PatchesWithWrongOrientationFlagsAreTurned) {
  GeneratedHull h = generated(HullKind::kChine, 12);
  // A file that declares some patches with the wrong orientation: their normals point in.
  std::vector<PatchId> wrong = {1, 4, 7};
  for (PatchId p : wrong) h.patches[p].reversed = !h.patches[p].reversed;
  const Merged m = merge_of(h.patches);
  expect_clean_half_hull(m, "chine, three wrong flags");
  EXPECT_EQ(m.merged.report.patches_flipped, wrong);
  // Every face normal points out of the hull: away from the centre plane on the side.
  const Merged ref = merge_of(generated(HullKind::kChine, 12).patches);
  EXPECT_NEAR(m.merged.report.enclosed_volume, ref.merged.report.enclosed_volume,
              1e-9 * ref.merged.report.enclosed_volume);
}

TEST(Merge, PairwiseOverlapIsCutAway) {
  HullDefects d;
  d.overlap = 0.05;
  const Merged m = merge_of(generated(HullKind::kWigley, 2, d).patches);
  const Merged ref = merge_of(generated(HullKind::kWigley, 2).patches);
  expect_clean_half_hull(m, "wigley, 2 overlapping patches");
  EXPECT_GT(m.merged.report.overlap_area_removed, 0.0);
  // What remains covers the hull once.
  EXPECT_NEAR(total_area(m.merged.mesh) / total_area(ref.merged.mesh), 1.0, 2e-3);
  EXPECT_NEAR(total_area(m.tess.mesh) - m.merged.report.overlap_area_removed,
              total_area(m.merged.mesh), 2e-3 * total_area(m.merged.mesh));
}

// Overlaps of 2% and 5% of a patch on hulls of 4 to 48 patches. Across the seams they are
// mostly narrower than an edge (wigley, 12 patches at 2%: 0.33 m under 1 m edges), so only the
// border vertices lie on the patch below, and where four patches meet, the patch on top lies on
// three others at once. Before the cut along the edges these hulls kept a double layer at seams
// (wigley at 12 patches: 11 boundary loops) or at the four-patch corners (an edge with three
// faces: 11 of the 24 cases failed). Round-bilge at 48 patches and 5% failed (4 such edges,
// where a three-patch corner meets the bilge) until corners left on the border by the cut moved
// onto it.
TEST(Merge, OverlapsAreCutAtSeamsAndMultiPatchCorners) {
  for (HullKind kind : {HullKind::kWigley, HullKind::kRoundBilge, HullKind::kChine}) {
    for (int patches : {4, 12, 24, 48}) {
      const Merged ref = merge_of(generated(kind, patches).patches);
      for (double overlap : {0.02, 0.05}) {
        HullDefects d;
        d.overlap = overlap;
        const Merged m = merge_of(generated(kind, patches, d).patches);
        const std::string what = std::string(to_string(kind)) + ", " + std::to_string(patches) +
                                 " patches, overlap " + std::to_string(overlap);
        expect_clean_half_hull(m, what);
        EXPECT_GT(m.merged.report.overlap_area_removed, 0.0) << what;
        // The hull is covered once: its area is that of the hull without overlaps, to the
        // issue's 0.1% (measured: within 3.6e-5). The volume, closed over the outline, differs
        // by the two tessellations' chord errors (measured: within 0.75%).
        EXPECT_NEAR(total_area(m.merged.mesh) / total_area(ref.merged.mesh), 1.0, 1e-3) << what;
        EXPECT_NEAR(m.merged.report.enclosed_volume / ref.merged.report.enclosed_volume, 1.0, 1e-2)
            << what;
      }
    }
  }
}

// Gaps and overlaps together (gaps up to 0.1 m, 5% overlaps; wigley, round-bilge and chine of
// 24 patches at 40,000 triangles): each patch's border runs a little outside the border of the
// patch it overlaps. A covered border vertex then counted as on the lower border, and the cut
// kept a chord from it across the lower patch's corner, doubling that corner: wigley and
// round-bilge had edges with three faces (the merge failed) and chine a hole, until the lower
// corners were inserted into the edges the cut crosses. The hull is covered once: its area is
// that of the hull with neither defect, to 0.5% (the gaps are closed by stretching the faces
// beside them).
TEST(Merge, GapsAndOverlapsTogetherAreCutAndClosed) {
  for (HullKind kind : {HullKind::kWigley, HullKind::kRoundBilge, HullKind::kChine}) {
    const std::vector<Patch> plain = generated(kind, 24).patches;
    const double edge = edge_length_for_triangles(plain, 40000);
    const Merged ref = merge_of(plain, edge);
    HullDefects d;
    d.gap = 0.1;
    d.overlap = 0.05;
    const Merged m = merge_of(generated(kind, 24, d).patches, edge);
    const std::string what = std::string(to_string(kind)) + ", 24 patches, gaps and overlaps";
    expect_clean_half_hull(m, what);
    EXPECT_GT(m.merged.report.overlap_area_removed, 0.0) << what;
    EXPECT_NEAR(total_area(m.merged.mesh) / total_area(ref.merged.mesh), 1.0, 5e-3) << what;
  }
}

// Gaps of up to 0.1 m (1e-3 L) on a fine tessellation (128,000 triangles, border edges of a few
// centimetres) with the tolerance set to 0.15 m: the two sides of a gap are several edges apart.
// Welds were held to 0.6 of the local edge whatever the tolerance, and every gap stayed open (12
// loops on wigley, 35 on round-bilge); the sides now weld where they are each other's nearest.
TEST(Merge, SetToleranceClosesGapsSeveralEdgesWide) {
  for (HullKind kind : {HullKind::kWigley, HullKind::kRoundBilge}) {
    HullDefects d;
    d.gap = 0.1;
    const std::vector<Patch> patches = generated(kind, 24, d).patches;
    TessellateOptions to;
    to.edge_length = edge_length_for_triangles(patches, 128000);
    const Tessellation t = tessellate(patches, to, silent_progress());
    MergeOptions mo;
    mo.gap_tolerance = 0.15;
    const MergedSurface m = merge_patches(patches, t.mesh, mo, silent_progress());
    const EdgeAdjacency adj = build_edge_adjacency(m.mesh.faces, m.mesh.vertex_count());
    SCOPED_TRACE(to_string(kind));
    EXPECT_TRUE(adj.nonmanifold_edges.empty());
    EXPECT_TRUE(adj.inconsistent_edges.empty());
    EXPECT_EQ(adj.boundary_loops.size(), 1u);
    EXPECT_TRUE(m.report.open_gaps.empty());
    EXPECT_GT(m.report.vertices_welded, 1000u);
  }
}

TEST(Merge, SameBytesWithOneTwoAndEightThreads) {
  // Gaps (the snap), overlaps (the cut, whose checks run in parallel), and both.
  HullDefects gaps, overlaps, both;
  gaps.gap = both.gap = 0.05;
  overlaps.overlap = both.overlap = 0.05;
  for (const HullDefects& d : {gaps, overlaps, both}) {
    const std::vector<Patch> patches = generated(HullKind::kRoundBilge, 24, d).patches;
    const MergedSurface one = hm::test::with_threads(1, [&] { return merge_of(patches).merged; });
    for (int threads : {2, 8}) {
      const MergedSurface two =
          hm::test::with_threads(threads, [&] { return merge_of(patches).merged; });
      ASSERT_EQ(one.mesh.vertex_count(), two.mesh.vertex_count()) << threads;
      ASSERT_EQ(one.mesh.faces, two.mesh.faces) << threads;
      for (std::size_t v = 0; v < one.mesh.vertex_count(); ++v) {
        ASSERT_EQ(one.mesh.positions[v].x, two.mesh.positions[v].x) << threads;
        ASSERT_EQ(one.mesh.positions[v].y, two.mesh.positions[v].y) << threads;
        ASSERT_EQ(one.mesh.positions[v].z, two.mesh.positions[v].z) << threads;
      }
      EXPECT_EQ(one.vert_new2old, two.vert_new2old) << threads;
      EXPECT_EQ(one.face_new2old, two.face_new2old) << threads;
      EXPECT_EQ(one.report.overlap_triangles_removed, two.report.overlap_triangles_removed);
    }
  }
}

TEST(Merge, ChineKnucklesAreFoundAcrossPatchBorders) {
  const GeneratedHull h = generated(HullKind::kChine, 24);
  const Merged m = merge_of(h.patches);
  const FeatureSet f = find_features(m.merged.mesh, m.adj, m.patches, {});
  double truth = 0;
  for (const auto& line : h.facts.knuckles) {
    for (std::size_t i = 0; i + 1 < line.size(); ++i) truth += norm(line[i + 1] - line[i]);
  }
  EXPECT_NEAR(f.knuckle_length() / truth, 1.0, 0.01);
}

TEST(Merge, RejectsInconsistentInput) {
  const GeneratedHull h = generated(HullKind::kWigley, 2);
  Tessellation t = tessellate(h.patches, {}, silent_progress());
  t.mesh.face_patch[0] = 7;
  EXPECT_THROW(merge_patches(h.patches, t.mesh, {}, silent_progress()), GeometryError);
}

// The real hulls that merge into one surface with only their outline open.
class MergeSharedHull : public ::testing::TestWithParam<const char*> {};

TEST_P(MergeSharedHull, OneSurfaceWithOnlyItsOutlineOpen) {
  HM_REQUIRE_SHARED_HULL(path, GetParam());
  const ImportResult hull = read_iges_file(path.string());
  const Merged m = merge_of(hull.patches);
  expect_clean_half_hull(m, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Hulls, MergeSharedHull,
                         ::testing::Values("wigley.iges", "series60.iges", "dtmb5415.iges",
                                           "kcs.iges"));

// ship_449's keel plate (DE 8385) is a four-sided patch with two sides in line, folded over a
// hair at their corner. Its grid crowded (28,000 of 183,000 triangles) and crossed itself, and
// the merge left 7 edges with three faces at 128,000 triangles and 262 at 400,000.
TEST(MergeShip449, FoldedKeelPlateMergesAtFineSizes) {
  HM_REQUIRE_SHARED_HULL(path, "ship_449_patches.iges");
  const ImportResult hull = read_iges_file(path.string());
  for (const std::size_t triangles : {128000u, 400000u}) {
    SCOPED_TRACE(triangles);
    const Merged m = merge_of(hull.patches, edge_length_for_triangles(hull.patches, triangles));
    EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
    EXPECT_TRUE(m.adj.inconsistent_edges.empty());
    EXPECT_GT(m.merged.report.enclosed_volume, 0.0);
    std::size_t plate = 0;
    for (PatchId p : m.tess.mesh.face_patch) plate += hull.patches[p].de == 8385;
    EXPECT_LT(double(plate), 0.02 * double(m.tess.mesh.face_count()));  // 27 m^2 of 5,896
  }
}

}  // namespace
}  // namespace hm
