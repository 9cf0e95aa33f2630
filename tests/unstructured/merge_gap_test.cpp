// Gaps the snap leaves open: measured and snapped again with a wider tolerance, zipped shut where
// they stay thin loops, and closed from their end where they open onto the hull's outline.
#include <gtest/gtest.h>

#include <vector>

#include "query/find_self_intersections.h"
#include "unstructured/features.h"
#include "unstructured/merge_support.h"

namespace hm::test {
namespace {

// Length of the merged surface's boundary, m.
double boundary_length(const Merged& m) {
  double sum = 0;
  for (Index e : m.adj.boundary_edges) {
    const MeshEdge& edge = m.adj.edges[e];
    sum += norm(m.merged.mesh.positions[edge.v1] - m.merged.mesh.positions[edge.v0]);
  }
  return sum;
}

// A generated hull of the default size with gaps of up to `gap` m between its patches.
HullSpec with_gaps(HullKind kind, int patches, bool full, double gap) {
  HullSpec spec;
  spec.kind = kind;
  spec.patches = patches;
  spec.full_hull = full;
  spec.defects.gap = gap;
  return spec;
}

// Chine 100 with every defect at 128,000 triangles: the chine's two borders stand 0.07-0.1 m
// apart from the transom to the stem, a slit that opens onto the outline at both ends, so the
// outline was the only loop and ran 174 m along it. The measured widths were looked up by
// vertex number after the snap had renumbered the vertices, so most went to other vertices, and
// the wider snap counted loops only (one more slit loop is no fewer loops). Now the chine closes:
// the volume is the clean hull's.
TEST(MergeGaps, ASlitOpeningOntoTheOutlineIsSnappedAtItsMeasuredWidth) {
  HullDefects d;
  d.gap = 0.1;
  d.overlap = 0.05;
  d.duplicate_points = true;
  d.flip_every = 3;
  const std::vector<Patch> broken = generated(HullKind::kChine, 100, d).patches;
  const std::vector<Patch> clean = generated(HullKind::kChine, 100).patches;
  const Merged m = merge_of(broken, edge_length_for_triangles(broken, 128000));
  const Merged ref = merge_of(clean, edge_length_for_triangles(clean, 128000));
  expect_clean_half_hull(m, "chine, 100 patches, every defect, 128,000 triangles");
  EXPECT_GT(m.merged.report.gap_vertices_widened, 0u);
  EXPECT_NEAR(m.merged.report.enclosed_volume / ref.merged.report.enclosed_volume, 1.0, 5e-3);
  EXPECT_NEAR(boundary_length(m) / boundary_length(ref), 1.0, 5e-3);
}

// Full round-bilge 24 with 0.1 m gaps and 5% overlaps: the halves stand 0.1 m apart at the stem,
// a slit 2.6 m high bent like a C (its fan from the centroid measured 0.43 m wide, so it was not
// zipped; the zipper's own faces measure 0.1 m), and at the transom the gap opens onto the deck
// edge, a notch 0.1 m wide and 0.2 m deep. Both close; the boundary is the deck edge alone. (The
// zipper closed both until 2026-12-06; since then the snap welds the halves across them, each
// half moving onto the centre plane.)
TEST(MergeGaps, BentSlitAndNotchAtTheDeckOfAFullHullClose) {
  HullDefects d;
  d.gap = 0.1;
  d.overlap = 0.05;
  HullSpec spec;
  spec.kind = HullKind::kRoundBilge;
  spec.patches = 24;
  spec.full_hull = true;
  spec.defects = d;
  const Merged m = merge_of(generate_hull(spec).patches);
  spec.defects = {};
  const Merged ref = merge_of(generate_hull(spec).patches);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  EXPECT_NEAR(boundary_length(m) / boundary_length(ref), 1.0, 5e-3);  // 227 m before, 219 m
}

// A clean full Wigley of 300 patches at 128,000 triangles: at the bow the deck edge turns back
// sharply between two patches, and a face across that corner would agree with the sides it
// joins within 90 degrees; it would be a lid on the deck, not a gap, and it stays open.
TEST(MergeGaps, TheSharpBowOfACleanFullHullIsNoNotch) {
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  spec.patches = 300;
  spec.full_hull = true;
  const std::vector<Patch> patches = generate_hull(spec).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 128000));
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  EXPECT_EQ(m.merged.report.gaps_bridged, 0u);
}

std::size_t zero_area_faces(const SurfaceMesh& m) {
  std::size_t n = 0;
  for (const Face& f : m.faces) {
    double longest = 0;
    for (int c = 0; c < 3; ++c)
      longest = std::max(longest, squared_norm(m.positions[f[(c + 1) % 3]] - m.positions[f[c]]));
    n += face_area(m.positions, f) <= 1e-10 * longest;
  }
  return n;
}

// Full chine hulls with a gap between the halves of 2e-4 L and more, at 10,000 triangles (the
// structured mesher's fine mesh at 1,200 panels): the keels' gap ends on the transom's straight
// bottom edge, and what closed it there had its corners on that line. With 3 patches and 0.02 m
// the last hole was ten vertices on the edge, fanned (2 faces of no area); with 2 patches and
// 0.05 m the zipper laid 19 flat faces along it; with 0.03 m two keel vertices stayed apart on
// one spot. `--validate` refused every one. Now the hole is closed by splitting the faces along
// it at its vertices (split_flat_hole), and the merge's last step splits away or welds what
// flat faces are left (split_flat_faces).
TEST(MergeGaps, GapsClosingOnAStraightTransomEdgeLeaveNoFaceOfNoArea) {
  struct Case {
    int patches;
    double gap;
  };
  for (const Case c : {Case{3, 0.02}, Case{2, 0.05}, Case{2, 0.03}}) {
    SCOPED_TRACE(std::to_string(c.patches) + " patches, gap " + std::to_string(c.gap));
    HullSpec spec;
    spec.kind = HullKind::kChine;
    spec.patches = c.patches;
    spec.full_hull = true;
    spec.defects.gap = c.gap;
    const std::vector<Patch> patches = generate_hull(spec).patches;
    const Merged m = merge_of(patches, edge_length_for_triangles(patches, 10'000));
    EXPECT_EQ(zero_area_faces(m.merged.mesh), 0u);
    EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
    EXPECT_TRUE(m.adj.inconsistent_edges.empty());
    EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  }
}

// A full round-bilge hull of 2 patches with 0.1 m gaps (1e-3 L) at 40,000 triangles: the zipper
// and the flat-face splits left a slit of 28 vertices on one line, 9.5 cm long, where the two
// halves' transom edges meet at the centre plane (too many vertices for the hole pass, and it
// was not flat when that ran). The merge's last step closes such holes.
TEST(MergeGaps, ASlitOnOneLineLeftByTheLastStepsIsClosed) {
  const std::vector<Patch> patches =
      generate_hull(with_gaps(HullKind::kRoundBilge, 2, true, 0.1)).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 40'000));
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);  // the deck edge
  EXPECT_EQ(zero_area_faces(m.merged.mesh), 0u);
}

// Wigley hulls of 2 patches with 0.1 m gaps (1e-3 L) at 40,000 triangles. The full hull's halves
// stand 0.074-0.1 m apart at each sharp stem, a slit from z = 2.8 m up to the deck: the strip
// that closes it stands square to both sides, and the notch's agreement test took it for a lid
// (20 m of boundary there called transom edge). The half hull's gap between its two patches
// opens onto the deck, a slit whose edges (0.23 m) are longer than it is wide (8 m of hole, a gap
// reported open). A slit, whose width does not grow from its apex, now closes up to its mouth;
// the boundary is the outline alone, as long as the clean hull's.
TEST(MergeGaps, SlitsOpeningOntoTheDeckCloseUpToTheirMouth) {
  for (const bool full : {true, false}) {
    SCOPED_TRACE(full ? "full" : "half");
    HullSpec spec = with_gaps(HullKind::kWigley, 2, full, 0.1);
    const std::vector<Patch> broken = generate_hull(spec).patches;
    spec.defects = {};
    const std::vector<Patch> clean = generate_hull(spec).patches;
    const Merged m = merge_of(broken, edge_length_for_triangles(broken, 40'000));
    const Merged ref = merge_of(clean, edge_length_for_triangles(clean, 40'000));
    EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
    EXPECT_TRUE(m.adj.inconsistent_edges.empty());
    EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
    EXPECT_TRUE(m.merged.report.open_gaps.empty());
    EXPECT_NEAR(boundary_length(m) / boundary_length(ref), 1.0, 5e-3);
    EXPECT_NEAR(m.merged.report.enclosed_volume / ref.merged.report.enclosed_volume, 1.0, 5e-3);
  }
}

// A half Wigley of 24 patches with 0.1 m gaps at 400,000 triangles: at each station seam the snap
// welds the tips of the two patches' borders at the keel and leaves a V notch of 62-64 degrees
// in the centre-plane outline, past the 60 degrees a notch's apex was allowed (24 gaps reported
// open, 2 m of hole). An apex may now open to 90 degrees; no notch face may be flat (at the
// stem, where two borders run along one straight line, one had no area).
TEST(MergeGaps, VNotchesAtTheKeelClose) {
  const std::vector<Patch> patches =
      generate_hull(with_gaps(HullKind::kWigley, 24, false, 0.1)).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 400'000));
  expect_clean_half_hull(m, "wigley, 24 patches, 0.1 m gaps, 400,000 triangles");
  EXPECT_TRUE(m.merged.report.open_gaps.empty());
  EXPECT_EQ(zero_area_faces(m.merged.mesh), 0u);
}

// Full chine hulls of 2 and 3 patches, each side one patch with its transom inside, which comes
// down to one point at the keel. A 0.1 m gap in the centre plane opens that point into a short
// row across the transom's foot; the snap took the row's keel end (the bottom's corner) to the
// centre plane, back over the row, and the transom's faces on the row lay over the one beside it
// in its plane: 148 and 70 pairs of faces through each other at the default size. The row now
// joins the corner that passed over it, and the surface is the clean hull's there.
TEST(MergeGaps, ATransomFootOpenedByAGapIsOnePointAgain) {
  for (const int patches : {2, 3}) {
    SCOPED_TRACE(patches);
    const HullSpec spec = with_gaps(HullKind::kChine, patches, /*full=*/true, 0.1);
    const Merged m = merge_of(generate_hull(spec).patches);
    EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
    EXPECT_TRUE(m.adj.inconsistent_edges.empty());
    EXPECT_EQ(m.adj.boundary_loops.size(), 1u);  // the deck edge
    EXPECT_TRUE(m.merged.report.open_gaps.empty());
    const SelfIntersections x = find_self_intersections(m.merged.mesh, 1e-9 * spec.length);
    EXPECT_EQ(x.count, 0u) << "first near " << (x.first.empty() ? Vec3d{} : x.first[0].where).x;
  }
}

FeatureSet features_of(const Merged& m) {
  return find_features(m.merged.mesh, m.adj, m.patches, {});
}

// A generated hull with gaps of up to `gap` m, and the same hull without, each merged at
// `triangles` fine triangles (0: the default size).
struct GappedAndClean {
  Merged gapped, clean;
};
GappedAndClean gapped_and_clean(HullKind kind, int patches, bool full, double gap,
                                std::size_t triangles = 0) {
  const auto merged = [&](double g) {
    std::vector<Patch> p = generate_hull(with_gaps(kind, patches, full, g)).patches;
    const double edge = triangles > 0 ? edge_length_for_triangles(p, triangles) : 0.0;
    return merge_of(std::move(p), edge);
  };
  return {merged(gap), merged(0)};
}

// The half round-bilge hull of 2 patches (the transom and the rest) with 0.1 m gaps, at 40,000
// triangles: each patch stops up to 0.05 m short of the transom's edge, the side on the side, the
// transom on the transom. The gap was closed on the chamfer between the two borders, which split
// the edge's 90 degrees into two creases of about 45, and the knuckle ran from one to the other:
// 9 lines, 7.69 m, where the clean hull has 1 of 7.45 m. The side's border is finer than the gap
// is wide, which had kept the transom's vertices from joining it: each lay farther from the end
// of the side's edge across from it than 0.3 of that edge, and faced the edge's end. Now such a
// vertex joins the end its edge runs on to, and a pair of vertices at a knuckle closes at the
// corner of their two surfaces.
TEST(MergeGaps, AKnuckleAcrossAGapClosesAtItsCorner) {
  const auto [m, ref] = gapped_and_clean(HullKind::kRoundBilge, 2, /*full=*/false, 0.1, 40000);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  const FeatureSet f = features_of(m), f_ref = features_of(ref);
  ASSERT_EQ(f_ref.knuckles.size(), 1u);
  EXPECT_EQ(f.knuckles.size(), 1u);
  EXPECT_NEAR(f.knuckle_length(), f_ref.knuckle_length(), 1e-3 * f_ref.knuckle_length());
  // On the transom's edge (x = 0), not beside it, but at its two ends: there three borders meet
  // (the centre plane's or the deck's as well), and the two vertices take their mean, 0.025 m
  // aft of the transom.
  ASSERT_FALSE(f.knuckles.empty());
  const std::vector<Index>& line = f.knuckles[0].vertices;
  double off = 0;
  for (std::size_t k = 1; k + 1 < line.size(); ++k) {
    off = std::max(off, std::abs(m.merged.mesh.positions[line[k]].x));
  }
  EXPECT_LT(off, 1e-3) << "a knuckle vertex off the transom's plane";
}

// Full chine hulls of 2 and 3 patches with 0.1 m gaps, at the default size: the halves' bottom
// corners at the forefoot weld at the mean of the two, where both chines, the keel and the stem
// meet. The welded vertex kept the (u, v) of its own patch's corner, which lies 0.5 m aft and
// half a girth away on that patch, and the knuckle test trusted it: on that side the edge from
// the chine to the weld showed no jump on the NURBS (on the other side, whose faces use a
// vertex of another patch, the point was projected, and the jump was 10 degrees), so one chine
// turned up the stem and met it 0.9 m above the forefoot (9 lines where the clean hull has 8).
// A corner's (u, v) is now used only where it maps onto the corner.
TEST(MergeGaps, BothChinesMeetTheStemAtTheForefootAcrossAGap) {
  for (const int patches : {2, 3}) {
    SCOPED_TRACE(patches);
    const auto [m, ref] = gapped_and_clean(HullKind::kChine, patches, /*full=*/true, 0.1);
    const FeatureSet f = features_of(m), f_ref = features_of(ref);
    ASSERT_EQ(f_ref.knuckles.size(), 8u);
    EXPECT_EQ(f.knuckles.size(), f_ref.knuckles.size());
    EXPECT_NEAR(f.knuckle_length(), f_ref.knuckle_length(), 1e-2 * f_ref.knuckle_length());
  }
}

// The half round-bilge hull of 24 patches with 0.1 m gaps, at 40,000 triangles: where the snap
// closed the seams across the bilge (x = 8.33, 16.67, 25 and 33.3 m) it left slivers standing on
// their edges, 1 mm wide and 0.3 m long, at 96 degrees to their neighbours. The NURBS check
// took each side's normal signed like its face, and a sliver's normal lies square to the
// surface, so its sign was a coin toss: the check saw a 180-degree jump, and each seam had a
// knuckle line (5 lines, 8.74 m, where the clean hull has its transom's edge, 7.45 m). The sides
// now take their sign from how their patch faces the mesh.
TEST(MergeGaps, SliversStandingOnClosedSeamsMakeNoKnuckle) {
  const auto [m, ref] = gapped_and_clean(HullKind::kRoundBilge, 24, /*full=*/false, 0.1, 40000);
  const FeatureSet f = features_of(m), f_ref = features_of(ref);
  ASSERT_EQ(f_ref.knuckles.size(), 1u);
  EXPECT_EQ(f.knuckles.size(), 1u);
  EXPECT_NEAR(f.knuckle_length(), f_ref.knuckle_length(), 1e-3 * f_ref.knuckle_length());
}

// The clean full chine hull of 2 patches (its halves, each with its transom inside): the port
// transom's bottom edge stopped 0.43 m short of the keel (4.0 m, the starboard one 4.42 m). The
// bottom faces there have a keel corner of the other half, so their points are projected onto
// the patch, from their corners on the transom's edge: Newton stopped on that crease, and the
// face took the transom's normal. A face whose centroid lies on a crease now takes the side whose
// normal agrees with its own. The halves' lines are now alike.
TEST(MergeGaps, BothHalvesOfACleanFullChineHullHaveTheSameKnuckles) {
  const Merged m =
      merge_of(generate_hull(with_gaps(HullKind::kChine, 2, /*full=*/true, 0)).patches);
  const FeatureSet f = features_of(m);
  double port = 0, starboard = 0;
  for (const FeatureLine& line : f.knuckles) {
    double length = 0, y = 0;
    for (std::size_t k = 0; k + 1 < line.vertices.size(); ++k) {
      const Vec3d& a = m.merged.mesh.positions[line.vertices[k]];
      const Vec3d& b = m.merged.mesh.positions[line.vertices[k + 1]];
      length += norm(b - a);
      y += 0.5 * (a.y + b.y) * norm(b - a);
    }
    if (y < -1e-6 * length) port += length;
    if (y > 1e-6 * length) starboard += length;
  }
  EXPECT_EQ(f.knuckles.size(), 8u);
  EXPECT_GT(port, 100.0);
  EXPECT_NEAR(port, starboard, 1e-3 * starboard);
}

// The full Wigley of 2 patches (its halves) with 0.1 m gaps: each half stops 0.05 m from the
// centre plane, 0.25 m aft of the stem where the stem is fine. At the deck the halves' corners
// were left apart (their borders turn there into the deck edge, so no edge of the other lay
// across), a notch was filled flat, and the stem's knuckle stopped 0.72 m below the deck at
// both ends (113.6 m where the clean hull has 115.6). The two corners now weld as the two halves
// across the wedge of a fine stem.
TEST(MergeGaps, AFineStemsTopCornersWeldAcrossAGap) {
  const HullSpec spec = with_gaps(HullKind::kWigley, 2, /*full=*/true, 0.1);
  const Merged m = merge_of(generate_hull(spec).patches);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  ASSERT_EQ(m.adj.boundary_loops.size(), 1u);  // the deck edge
  const FeatureSet f = features_of(m);
  ASSERT_EQ(f.knuckles.size(), 1u);
  double top = -1e300;
  for (const Vec3d& p : m.merged.mesh.positions) top = std::max(top, p.z);
  const std::vector<Index>& line = f.knuckles[0].vertices;
  EXPECT_NEAR(m.merged.mesh.positions[line.front()].z, top, 1e-6);
  EXPECT_NEAR(m.merged.mesh.positions[line.back()].z, top, 1e-6);
}

}  // namespace
// The full round-bilge hull of 24 patches with 0.1 m gaps: where the stem curves into the keel
// (the forefoot, x = 100-102 m) its borders are refined to edges shorter than the gap, so the
// halves' vertices there, 0.08-0.09 m apart across the centre plane, lay beyond the tolerance
// (half an edge, 0.06 m); the hole filler closed the slit between them and the stem line broke
// into four pieces. At x = 36.4 m four patches meet on the keel with gaps both ways, and the
// shorter diagonal of the hole there ran across the keel: the keel was found forward of it only.
// 5 lines, 90.0 m, where the clean hull has 3 of 127.4 m. The halves now weld where each moves
// within its tolerance onto the centre plane.
TEST(MergeGaps, TheHalvesOfAFullHullWeldAcrossAGapWiderThanTheirEdges) {
  const Merged m = merge_of(generate_hull(with_gaps(HullKind::kRoundBilge, 24, true, 0.1)).patches);
  const Merged ref = merge_of(generate_hull(with_gaps(HullKind::kRoundBilge, 24, true, 0)).patches);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  const FeatureSet f = features_of(m), f_ref = features_of(ref);
  ASSERT_EQ(f_ref.knuckles.size(), 3u);  // the keel and stem, and the transom's two edges
  EXPECT_EQ(f.knuckles.size(), 3u);
  // The gap takes up to 0.1 m off the stem's top and the transom's ends.
  EXPECT_NEAR(f.knuckle_length(), f_ref.knuckle_length(), 0.5);
}

// The full round-bilge hull of 100 patches with 0.1 m gaps: where a knuckle runs through a
// junction of patches with gaps both ways, the hole left there is a small cross of slits, with
// corners on the line and off it to either side. Closed shortest diagonal first, its faces ran
// across the keel and bent over it, and the keel broke there: 5 lines where the clean hull has
// 3. The hole's faces now lie in the planes of the faces beside them, and the keel runs through.
TEST(MergeGaps, AHoleOnAKnuckleIsClosedAlongIt) {
  const Merged m =
      merge_of(generate_hull(with_gaps(HullKind::kRoundBilge, 100, true, 0.1)).patches);
  const Merged ref =
      merge_of(generate_hull(with_gaps(HullKind::kRoundBilge, 100, true, 0)).patches);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  const FeatureSet f = features_of(m), f_ref = features_of(ref);
  ASSERT_EQ(f_ref.knuckles.size(), 3u);
  EXPECT_EQ(f.knuckles.size(), 3u);
  EXPECT_NEAR(f.knuckle_length(), f_ref.knuckle_length(), 0.5);
}

// The full Wigley of 24 patches with every defect, at 40,000 triangles: where the stem and the
// stern post run into the flat keel (x = 8 and 92 m) the gaps leave slits across the knuckle,
// which the hole filler closed by ears, shortest diagonal first, across it; each end of the keel
// became a knot of three short lines (8 lines where the clean hull has 1). The ears are now
// taken among those whose faces lie in the planes of the faces beside them.
TEST(MergeGaps, SlitsAcrossAKnuckleCloseAlongIt) {
  HullSpec spec = with_gaps(HullKind::kWigley, 24, true, 0.1);
  spec.defects.overlap = 0.05;
  spec.defects.duplicate_points = true;
  spec.defects.flip_every = 3;
  const std::vector<Patch> patches = generate_hull(spec).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 40000));
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  const FeatureSet f = features_of(m);
  EXPECT_EQ(f.knuckles.size(), 1u);  // the stem, the keel and the stern post
}

// The clean full Wigley of 100 patches is 0.17 m thick near its forefoot (x = 4 m), where a seam
// between two patches crosses each side. Each side's seam vertices welded to the other side's
// across that thickness (their inward directions opposite, as of two borders that continue each
// other), and the forefoot was pinched onto the centre plane: 9 knuckle lines of 118.3 m, where
// the stem, the keel and the stern post make one line of 115.6 m. At 300 patches the stem is
// 0.19 m thick at its seams, under 0.3 of their border edges of 0.9 m: 9 lines, then 5 while the
// rule measured the thickness against the edges alone. A weld no longer runs through the hull's
// thickness, along both vertices' surface normals.
TEST(MergeGaps, NoWeldRunsThroughAThinHull) {
  for (const int patches : {100, 300}) {
    SCOPED_TRACE(std::to_string(patches) + " patches");
    const Merged m =
        merge_of(generate_hull(with_gaps(HullKind::kWigley, patches, true, 0)).patches);
    EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
    EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
    const FeatureSet f = features_of(m);
    EXPECT_EQ(f.knuckles.size(), 1u);
    EXPECT_NEAR(f.knuckle_length(), 115.6, 0.6);
    // Every vertex in the centre plane is on the profile (the knuckle line).
    std::vector<std::uint8_t> on_line(m.merged.mesh.vertex_count(), 0);
    for (const auto& line : f.knuckles) {
      for (Index v : line.vertices) on_line[v] = 1;
    }
    std::size_t pinched = 0;
    for (std::size_t v = 0; v < on_line.size(); ++v) {
      pinched += std::abs(m.merged.mesh.positions[v].y) < 1e-9 && !on_line[v];
    }
    EXPECT_EQ(pinched, 0u);
  }
}

// The clean half round-bilge hull of 300 patches, at the default size: at three patch corners of
// its bow (x = 86-90 m) the snap left a hole of three vertices along a seam, its middle vertex
// 1.4e-3 of the long side off the line (flat holes are split up to 1e-3). Its triangle stood
// across the hull, 90-100 degrees off the faces beside it, and three false knuckle lines of
// 0.4-0.7 m ran along those slivers: 4 lines of 9.1 m where the transom's edge is 1 of 7.45 m.
// Such a hole is now split as flat up to 1e-2.
TEST(MergeGaps, ATriangleStandingAcrossTheHullIsNoFill) {
  const Merged m = merge_of(generate_hull(with_gaps(HullKind::kRoundBilge, 300, false, 0)).patches);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  const FeatureSet f = features_of(m);
  EXPECT_EQ(f.knuckles.size(), 1u);
  EXPECT_NEAR(f.knuckle_length(), 7.445, 0.01);
}

// The clean full round-bilge hull of 300 patches has a transom strip 0.1-0.14 m tall along the
// transom's foot. A vertex of the transom patch above it, on the strip's upper border, welded to
// the bottom's corner 0.11 m below it, across the strip: each lay on the border of a different
// patch, so the strip was no third patch between them. The strip's faces then passed through the
// transom's (4 pairs), and the transom's edge became a knot of short lines on each side: 17
// lines where the hull has 3. A vertex on another patch's border no longer welds to one off
// that border, across that patch.
TEST(MergeGaps, AVertexOnAStripsBorderIsNotWeldedAcrossTheStrip) {
  const Merged m = merge_of(generate_hull(with_gaps(HullKind::kRoundBilge, 300, true, 0)).patches);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  EXPECT_EQ(find_self_intersections(m.merged.mesh, 1e-9 * 100).count, 0u);
  const FeatureSet f = features_of(m);
  EXPECT_EQ(f.knuckles.size(), 3u);
  EXPECT_NEAR(f.knuckle_length(), 127.4, 0.1);
}

// The full chine hull of 2 patches (its halves) with 0.1 m gaps, at 40,000 triangles: where the
// chines, the keel and the stem meet at the bow (one point of each half's border in the clean
// hull), the gap opens that point into a row of border edges of 5 mm, 0.05 m in all, whose
// vertices have tolerances of a few millimetres. Only the row's end at the keel welded to the
// other half's; the slit between the two rows was closed by faces square to the hull, a knot of
// short knuckle lines: 17 lines where the clean hull has 8. The row now joins its welded end.
TEST(MergeGaps, AShortRowAGapOpensAtTheBowJoinsItsWeld) {
  const std::vector<Patch> broken =
      generate_hull(with_gaps(HullKind::kChine, 2, true, 0.1)).patches;
  const std::vector<Patch> clean = generate_hull(with_gaps(HullKind::kChine, 2, true, 0)).patches;
  const Merged m = merge_of(broken, edge_length_for_triangles(broken, 40000));
  const Merged ref = merge_of(clean, edge_length_for_triangles(clean, 40000));
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  const FeatureSet f = features_of(m), f_ref = features_of(ref);
  ASSERT_EQ(f_ref.knuckles.size(), 8u);
  EXPECT_EQ(f.knuckles.size(), 8u);
  EXPECT_NEAR(f.knuckle_length(), f_ref.knuckle_length(), 1.0);
}

// The full Wigley of 6 patches with 0.1 m gaps, at 40,000 triangles: near the keel the stern post
// is a fin, its halves back to back less than 5 degrees apart and, with the gap, 0.016-0.023 m
// apart across the centre plane, over border edges of 0.24 m. Neither the wedge rule (which needs
// 5 degrees) nor the touching rule (5% of an edge) paired them, and the slit's fill made a second
// line of 0.24 m beside the stern post. They now weld as mirror images across the plane.
TEST(MergeGaps, AFinsHalvesAGapApartWeldAcrossTheCentrePlane) {
  const std::vector<Patch> patches =
      generate_hull(with_gaps(HullKind::kWigley, 6, true, 0.1)).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 40000));
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);  // the deck edge
  const FeatureSet f = features_of(m);
  EXPECT_EQ(f.knuckles.size(), 1u);
  // A clean Wigley's two deck edges near the stem leave the plane back to back too, 0.39 m apart
  // through the hull: they stay apart, and the line still ends at the stem's and stern's tops.
  const Merged clean = merge_of(generate_hull(with_gaps(HullKind::kWigley, 2, true, 0)).patches);
  const FeatureSet fc = features_of(clean);
  ASSERT_EQ(fc.knuckles.size(), 1u);
  const std::vector<Index>& line = fc.knuckles[0].vertices;
  const Vec3d a = clean.merged.mesh.positions[line.front()];
  const Vec3d z = clean.merged.mesh.positions[line.back()];
  EXPECT_LT(std::min(a.x, z.x), 0.01);
  EXPECT_GT(std::max(a.x, z.x), 99.99);
}

}  // namespace hm::test
