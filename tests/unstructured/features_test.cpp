// Features of one-patch generated hulls: knuckles against the generator's true knuckle lines,
// nothing on smooth surfaces, boundary kinds of a half hull, hints, corners, thread-count
// independence. One patch needs no merger: its triangulation already shares vertices.
#include "unstructured/features.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "core/error.h"
#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "support/test_support.h"
#include "tessellate/tessellate.h"
#include "unstructured/classify_boundaries.h"

namespace hm {
namespace {

struct Hull {
  GeneratedHull generated;
  Tessellation tess;
  EdgeAdjacency adjacency;
};

// A one-patch port half hull, L = 100 m, tessellated on its initial grid of L / 40 only
// (max_refine_levels = 0), built once per kind. The grid is laid per knot span, so every
// knuckle (a knot of full multiplicity) is a row of grid vertices exactly on the NURBS. The
// adaptive refinement is left out so that the expected edges can be named exactly; with it, the
// knuckles stay on their knots too (tests/tessellate RefinedKnucklesStayOnTheirKnots), but the
// true-knuckle test below (5 mm or 15% of an edge) then also catches short transom-face edges
// near the centreline, where the knuckle curve and the transom converge.
const Hull& hull(HullKind kind, int refine_levels = 0) {
  static std::map<std::pair<HullKind, int>, Hull> cache;
  auto it = cache.find({kind, refine_levels});
  if (it != cache.end()) return it->second;
  Hull h;
  HullSpec spec;
  spec.kind = kind;
  spec.patches = 1;
  h.generated = generate_hull(spec);
  TessellateOptions o;
  o.edge_length = spec.length / 40;
  o.max_refine_levels = refine_levels;
  h.tess = tessellate(h.generated.patches, o, silent_progress());
  h.adjacency = build_edge_adjacency(h.tess.mesh.faces, h.tess.mesh.vertex_count());
  return cache.emplace(std::pair(kind, refine_levels), std::move(h)).first->second;
}

FeatureSet features(const Hull& h, const FeatureOptions& o = {}) {
  return find_features(h.tess.mesh, h.adjacency, h.generated.patches, o);
}

double distance_to_polyline(const Vec3d& q, const std::vector<Vec3d>& line) {
  double best = INFINITY;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const Vec3d ab = line[i + 1] - line[i];
    const double t = std::clamp(dot(q - line[i], ab) / squared_norm(ab), 0.0, 1.0);
    best = std::min(best, norm(q - (line[i] + t * ab)));
  }
  return best;
}

// Whether edge e runs along one of the true knuckle polylines: both ends within tol of the same
// polyline (grid vertices lie on the exact curve; tol covers the polyline's own chords, 101
// samples) and its midpoint within 15% of its length (the coarse mesh edge is a chord of the
// curve too: a transom edge across the round bilge sags by some 10%).
bool on_true_knuckle(const Hull& h, Index e, double tol = 5e-3) {
  const MeshEdge& me = h.adjacency.edges[e];
  const Vec3d& a = h.tess.mesh.positions[me.v0];
  const Vec3d& b = h.tess.mesh.positions[me.v1];
  for (const std::vector<Vec3d>& line : h.generated.facts.knuckles) {
    if (distance_to_polyline(a, line) <= tol && distance_to_polyline(b, line) <= tol &&
        distance_to_polyline(0.5 * (a + b), line) <= std::max(tol, 0.15 * norm(b - a))) {
      return true;
    }
  }
  return false;
}

double polyline_length(const std::vector<Vec3d>& line) {
  double sum = 0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) sum += norm(line[i + 1] - line[i]);
  return sum;
}

TEST(Features, ChineHullEveryTrueKnuckleEdgeIsFoundAndNothingElse) {
  const Hull& h = hull(HullKind::kChine);
  const FeatureSet f = features(h);
  ASSERT_EQ(f.edge_knuckle.size(), h.adjacency.edges.size());
  std::size_t truth = 0, found = 0;
  for (Index e = 0; e < h.adjacency.edges.size(); ++e) {
    if (h.adjacency.edges[e].uses != 2) continue;
    const bool on_truth = on_true_knuckle(h, e);
    truth += on_truth;
    found += f.edge_knuckle[e];
    EXPECT_EQ(f.edge_knuckle[e] != 0, on_truth) << "edge " << e;
  }
  EXPECT_GT(truth, 40u);  // chine and transom edge are long lines of edges
  EXPECT_EQ(found, truth);
  // Chine, and the transom knuckle above and below the chine: three lines meeting at the corner
  // where chine and transom cross. The chine runs all the way to the stem, although its jump
  // fades below the threshold there (the extension step follows it).
  EXPECT_EQ(f.knuckles.size(), 3u);
  double true_length = 0;
  for (const auto& line : h.generated.facts.knuckles) true_length += polyline_length(line);
  EXPECT_NEAR(f.knuckle_length(), true_length, 2e-3 * true_length);
  EXPECT_EQ(f.candidates_rejected_by_nurbs, 0u);
}

TEST(Features, OnePatchKnucklesInsideThePatchAreConfirmedOnTheNurbs) {
  // Chine and transom knuckles of a one-patch hull sit on knots of full multiplicity: only a
  // one-sided NURBS normal sees their jump, and the check must keep them all.
  const Hull& h = hull(HullKind::kChine);
  FeatureOptions unchecked;
  unchecked.confirm_on_nurbs = false;
  const FeatureSet mesh_only = features(h, unchecked);
  const FeatureSet checked = features(h);
  for (Index e = 0; e < h.adjacency.edges.size(); ++e) {
    // Edges the mesh alone misses are the chine's end near the stem, where its jump fades
    // below the threshold; the NURBS check follows the line on there.
    if (checked.edge_knuckle[e] && !mesh_only.edge_knuckle[e]) {
      EXPECT_TRUE(on_true_knuckle(h, e)) << "edge " << e;
    }
    if (mesh_only.edge_knuckle[e] && on_true_knuckle(h, e)) {
      EXPECT_TRUE(checked.edge_knuckle[e]) << "edge " << e;
    }
  }
}

TEST(Features, SmoothWigleyHasNoKnuckle) {
  const Hull& h = hull(HullKind::kWigley);
  ASSERT_TRUE(h.generated.facts.knuckles.empty());
  const FeatureSet f = features(h);
  EXPECT_TRUE(f.knuckles.empty());
  EXPECT_EQ(std::count(f.edge_knuckle.begin(), f.edge_knuckle.end(), 1), 0);
}

TEST(Features, RoundBilgeHullKnucklesOnlyAtItsTransom) {
  // Smooth everywhere (bilge, bulb, sonar dome, stem) but for its flat transom's edge.
  const Hull& h = hull(HullKind::kRoundBilge);
  const FeatureSet f = features(h);
  std::size_t found = 0;
  for (Index e = 0; e < h.adjacency.edges.size(); ++e) {
    if (h.adjacency.edges[e].uses != 2) continue;
    found += f.edge_knuckle[e];
    EXPECT_EQ(f.edge_knuckle[e] != 0, on_true_knuckle(h, e)) << "edge " << e;
  }
  EXPECT_GT(found, 5u);
  ASSERT_EQ(f.knuckles.size(), 1u);
  const double true_length = polyline_length(h.generated.facts.knuckles[0]);
  EXPECT_NEAR(f.knuckle_length(), true_length, 0.01 * true_length);  // chords of a curved edge
}

TEST(Features, NurbsCheckTurnsDownCoarseSmoothCandidates) {
  // A threshold below the coarse mesh's own facet angles on the bilge and bulb: the mesh says
  // knuckle, the smooth NURBS says no.
  const Hull& h = hull(HullKind::kRoundBilge);
  {
    const NurbsSurface& s = h.generated.patches[0].surface;
    for (double du : {-1e-4, -1e-6, 0.0, 1e-6, 1e-4}) {
      for (double dv : {-1e-4, 0.0, 1e-4}) {
        Vec3d n = normal(s, 0.9708 + du, 0.9 + dv);
        SurfaceDerivs d = evaluate_derivs(s, 0.9708 + du, 0.9 + dv, 1);
        printf("du %g dv %g n %.5f %.5f %.5f |su| %.4f |sv| %.4f\n", du, dv, n.x, n.y, n.z,
               norm(d.su), norm(d.sv));
      }
    }
    std::vector<double> ku = s.knots_u;
    for (double k : ku)
      if (k > 0.9) printf("%.6f ", k);
    printf("\n");
  }
  FeatureOptions o;
  o.knuckle_angle_deg = 4;
  const FeatureSet f = features(h, o);
  EXPECT_GT(f.candidates_rejected_by_nurbs, 0u);
  for (Index e = 0; e < h.adjacency.edges.size(); ++e) {
    if (f.edge_knuckle[e]) {
      EXPECT_TRUE(on_true_knuckle(h, e)) << "edge " << e;
    }
  }
}

TEST(Features, RefinedSmoothHullsStaySmooth) {
  // With the adaptive refinement on (chord tolerance 1e-4 L): the Wigley has no knuckle, and the
  // round-bilge hull has none away from its transom (x = 0).
  EXPECT_TRUE(features(hull(HullKind::kWigley, 6)).knuckles.empty());
  const Hull& h = hull(HullKind::kRoundBilge, 6);
  const FeatureSet f = features(h);
  EXPECT_FALSE(f.knuckles.empty());
  for (Index e = 0; e < h.adjacency.edges.size(); ++e) {
    if (!f.edge_knuckle[e]) continue;
    const MeshEdge& me = h.adjacency.edges[e];
    EXPECT_LT(h.tess.mesh.positions[me.v0].x, 0.1) << "edge " << e;
    EXPECT_LT(h.tess.mesh.positions[me.v1].x, 0.1) << "edge " << e;
  }
}

// Boundary kinds by edge count: a one-patch half hull is open on the centre plane (keel, stem,
// transom centreline) and at the deck (sheer and the top of the transom). Its transom is
// modelled, so no transom edge is open.
std::map<BoundaryKind, std::size_t> edges_by_kind(const FeatureSet& f) {
  std::map<BoundaryKind, std::size_t> n;
  for (const BoundaryRun& r : f.boundaries) n[r.kind] += r.vertices.size() - (r.closed ? 0 : 1);
  return n;
}

// m with only the faces whose centroid `keep` accepts (and their patches).
template <class Keep>
SurfaceMesh kept_faces(SurfaceMesh m, Keep&& keep) {
  std::vector<Face> faces;
  std::vector<PatchId> face_patch;
  for (std::size_t t = 0; t < m.faces.size(); ++t) {
    if (!keep(face_centroid(m.positions, m.faces[t]))) continue;
    faces.push_back(m.faces[t]);
    face_patch.push_back(m.face_patch[t]);
  }
  m.faces = std::move(faces);
  m.face_patch = std::move(face_patch);
  return m;
}

TEST(Features, HalfHullBoundariesAreCentrePlaneAndDeckEdge) {
  for (HullKind kind : {HullKind::kWigley, HullKind::kRoundBilge, HullKind::kChine}) {
    SCOPED_TRACE(to_string(kind));
    const Hull& h = hull(kind);
    const FeatureSet f = features(h);
    auto n = edges_by_kind(f);
    EXPECT_GT(n[BoundaryKind::kCentrePlane], 10u);
    EXPECT_GT(n[BoundaryKind::kDeckEdge], 10u);
    EXPECT_EQ(n[BoundaryKind::kHole], 0u);
    EXPECT_EQ(n[BoundaryKind::kTransomEdge], 0u);
    EXPECT_EQ(n[BoundaryKind::kWaterline], 0u);
    // One boundary loop: deck run and centre-plane run, with corners where they meet.
    EXPECT_EQ(f.boundaries.size(), 2u);
    for (const BoundaryRun& r : f.boundaries) {
      EXPECT_FALSE(r.closed);
      EXPECT_EQ(f.vertex_feature[r.vertices.front()], VertexFeature::kCorner);
      EXPECT_EQ(f.vertex_feature[r.vertices.back()], VertexFeature::kCorner);
      for (Index v : r.vertices) {
        const Vec3d& p = h.tess.mesh.positions[v];
        if (r.kind == BoundaryKind::kCentrePlane) {
          EXPECT_NEAR(p.y, 0.0, 1e-6);
        } else {
          EXPECT_NEAR(p.z, 8.0, 1e-6);  // the deck edge, D = 8 m
        }
      }
    }
  }
}

// The chine hull without its transom part: faces of the transom (x < 1e-9 everywhere on them)
// are dropped, and the hull ends in an open transom at x = 0.
TEST(Features, OpenTransomIsATransomEdge) {
  const Hull& h = hull(HullKind::kChine);
  const SurfaceMesh m = kept_faces(h.tess.mesh, [](const Vec3d& c) { return c.x >= 1e-9; });
  ASSERT_LT(m.faces.size(), h.tess.mesh.faces.size());
  const EdgeAdjacency adjacency = build_edge_adjacency(m.faces, m.vertex_count());
  const FeatureSet f = find_features(m, adjacency, h.generated.patches, {});
  auto n = edges_by_kind(f);
  EXPECT_GT(n[BoundaryKind::kTransomEdge], 4u);
  EXPECT_EQ(n[BoundaryKind::kHole], 0u);
  for (const BoundaryRun& r : f.boundaries) {
    if (r.kind != BoundaryKind::kTransomEdge) continue;
    for (Index v : r.vertices) EXPECT_NEAR(m.positions[v].x, 0.0, 1e-6);
  }
  // The transom knuckle went with the transom; the chine stays.
  EXPECT_EQ(f.knuckles.size(), 1u);
}

// A sheer that steps up: aft of a grid column near x = 20 m the side ends at a grid row near
// z = 4 m, forward of it it rises to the deck (D = 8 m), and the column between is open (a
// raised forecastle's end, as ship_449_patches.iges has at x = -48.5 m). The low rim is a deck
// edge right up to the step: nothing stands above it, although the side beside it (forward, in
// the same x slab) is twice as high.
TEST(Features, LowSheerBesideAStepUpIsDeckEdgeUpToTheStep) {
  const Hull& h = hull(HullKind::kWigley);
  SurfaceMesh m = h.tess.mesh;
  double xs = 0, zc = 0, bx = INFINITY, bz = INFINITY;
  for (const Vec3d& p : m.positions) {
    if (std::abs(p.x - 20.0) < bx) bx = std::abs(p.x - 20.0), xs = p.x;
    if (std::abs(p.z - 4.0) < bz) bz = std::abs(p.z - 4.0), zc = p.z;
  }
  m = kept_faces(m, [&](const Vec3d& c) { return !(c.x < xs && c.z > zc); });
  const EdgeAdjacency adjacency = build_edge_adjacency(m.faces, m.vertex_count());
  const FeatureSet f = find_features(m, adjacency, h.generated.patches, {});
  auto n = edges_by_kind(f);
  EXPECT_EQ(n[BoundaryKind::kHole], 0u);
  EXPECT_GT(n[BoundaryKind::kTransomEdge], 0u);  // the step's column
  std::size_t low_rim = 0;
  for (const BoundaryRun& r : f.boundaries) {
    for (std::size_t i = 0; i + 1 < r.vertices.size(); ++i) {
      const Vec3d& a = m.positions[r.vertices[i]];
      const Vec3d& b = m.positions[r.vertices[i + 1]];
      if (std::abs(a.z - zc) > 1e-9 || std::abs(b.z - zc) > 1e-9 || a.y < 1e-6 || b.y < 1e-6) {
        continue;
      }
      ++low_rim;
      EXPECT_EQ(r.kind, BoundaryKind::kDeckEdge) << "x " << a.x << " .. " << b.x;
    }
  }
  EXPECT_GT(low_rim, 4u);
}

// The last sliver of a fan at a patch tip, along a rising sheer: its third corner lies just
// below the edge, near its upper end, so its centroid stands above the edge's mid-height
// (kcs.iges at 128,000 triangles, x = -1.76 m: 1 cm of its deck edge was a hole). Below the
// edge's line, square to it, is what makes a deck edge.
TEST(Features, RisingSheerOverATipSliverIsDeckEdge) {
  SurfaceMesh m;
  m.positions = {{0, 1, 1}, {1, 1, 1.3}, {0.98, 1, 1.29}, {0, 1, 0}, {1, 1, 0}};  // off y = 0
  m.faces = {{0, 2, 1, kInvalid}, {0, 3, 2, kInvalid}, {2, 3, 4, kInvalid}, {2, 4, 1, kInvalid}};
  m.face_patch.assign(m.faces.size(), 0);
  const EdgeAdjacency adjacency = build_edge_adjacency(m.faces, m.vertex_count());
  const std::vector<BoundaryKind> kind =
      detail::classify_boundary_edges(m, adjacency, FeatureOptions{}, 1.3);
  std::size_t checked = 0;
  for (std::size_t e = 0; e < adjacency.edges.size(); ++e) {
    const MeshEdge& me = adjacency.edges[e];
    if (me.v0 == 0 && me.v1 == 1) {
      EXPECT_EQ(kind[e], BoundaryKind::kDeckEdge);  // the sheer, over the sliver
      ++checked;
    }
    if (me.v0 == 3 && me.v1 == 4) {
      EXPECT_EQ(kind[e], BoundaryKind::kHole);  // the lower rim, its faces above it
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2u);
}

TEST(Features, WaterlineCutBoundaryIsWaterline) {
  // Dropping every face above z = 3 m leaves a ragged rim; the rim vertices on z = 3 exactly
  // (a grid row there) make waterline edges when the option names that z.
  const Hull& h = hull(HullKind::kWigley);
  SurfaceMesh m = h.tess.mesh;
  // The Wigley's v grid rows are at fixed z; pick the grid z closest to 3 m.
  double cut = 0, best = INFINITY;
  for (const Vec3d& p : m.positions) {
    if (std::abs(p.z - 3.0) < best) best = std::abs(p.z - 3.0), cut = p.z;
  }
  m = kept_faces(m, [&](const Vec3d& c) { return c.z <= cut; });
  const EdgeAdjacency adjacency = build_edge_adjacency(m.faces, m.vertex_count());
  FeatureOptions o;
  o.waterline_z = cut;
  const FeatureSet f = find_features(m, adjacency, h.generated.patches, o);
  auto n = edges_by_kind(f);
  EXPECT_GT(n[BoundaryKind::kWaterline], 10u);
  EXPECT_EQ(n[BoundaryKind::kDeckEdge], 0u);
}

TEST(Features, WaterlineInsideTheSurfaceIsAKnuckleLine) {
  // A smooth Wigley with no knuckle: its grid row nearest z = 3 m lies inside the surface. Told
  // that the waterline runs there inside the surface, every interior edge on that row is a
  // knuckle (one line from end to end), even with a hint that suppresses everything near it;
  // without the flag there is none.
  const Hull& h = hull(HullKind::kWigley);
  const SurfaceMesh& m = h.tess.mesh;
  double row = 0, best = INFINITY;
  for (const Vec3d& p : m.positions) {
    if (std::abs(p.z - 3.0) < best) best = std::abs(p.z - 3.0), row = p.z;
  }
  const EdgeAdjacency adjacency = build_edge_adjacency(m.faces, m.vertex_count());
  std::size_t on_row = 0;
  for (const MeshEdge& e : adjacency.edges) {
    on_row += e.uses == 2 && std::abs(m.positions[e.v0].z - row) < 1e-8 &&
              std::abs(m.positions[e.v1].z - row) < 1e-8;
  }
  ASSERT_GT(on_row, 10u);
  FeatureOptions o;
  o.waterline_z = row;
  EXPECT_EQ(find_features(m, adjacency, h.generated.patches, o).knuckles.size(), 0u);
  o.waterline_inside = true;
  KnuckleHint everything;
  everything.plane_point = {0, 0, row};
  everything.plane_normal = {0, 0, 1};
  everything.distance = 10;
  o.suppress.push_back(everything);
  const FeatureSet f = find_features(m, adjacency, h.generated.patches, o);
  std::size_t knuckle_edges = 0;
  for (std::size_t e = 0; e < adjacency.edges.size(); ++e) {
    if (!f.edge_knuckle[e]) continue;
    ++knuckle_edges;
    // The grid row's z to rounding (the rule's tolerance is 1e-9 L).
    EXPECT_NEAR(m.positions[adjacency.edges[e].v0].z, row, 1e-8);
    EXPECT_NEAR(m.positions[adjacency.edges[e].v1].z, row, 1e-8);
  }
  EXPECT_EQ(knuckle_edges, on_row);
  EXPECT_EQ(f.knuckles.size(), 1u);
}

// A sliver whose three sides are all knuckle edges holds one line twice (ship_449_patches.iges
// had four, at patch seams near the bilge): its longest side goes, and one line runs through the
// sliver's third corner. Here a flat square with a sliver 2 mm wide along y = 0, and a hint that
// makes every edge near y = 0 a knuckle.
TEST(Features, ASliverWithThreeKnuckleSidesHoldsOneLine) {
  SurfaceMesh m;
  // a, b: the line's ends; s: the sliver's third corner; t, u: above and below.
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0.5, 0.002, 0}, {0.5, 1, 0}, {0.5, -1, 0}};
  const Index a = 0, b = 1, s = 2, t = 3, u = 4;
  m.faces = {{a, u, b, kInvalid}, {a, b, s, kInvalid}, {a, s, t, kInvalid}, {s, b, t, kInvalid}};
  m.face_patch.assign(m.faces.size(), 0);
  const EdgeAdjacency adjacency = build_edge_adjacency(m.faces, m.vertex_count());
  FeatureOptions o;
  o.confirm_on_nurbs = false;
  KnuckleHint along;
  along.kind = KnuckleHint::Kind::kPoints;
  along.points = {{0, 0, 0}, {1, 0, 0}};
  along.distance = 0.01;
  o.add.push_back(along);
  const FeatureSet f = find_features(m, adjacency, {}, o);
  std::size_t knuckle_edges = 0;
  for (std::size_t e = 0; e < adjacency.edges.size(); ++e) {
    if (!f.edge_knuckle[e]) continue;
    ++knuckle_edges;
    const MeshEdge& me = adjacency.edges[e];
    EXPECT_TRUE(me.v0 == s || me.v1 == s) << me.v0 << "-" << me.v1;  // not the side a-b
  }
  EXPECT_EQ(knuckle_edges, 2u);
  ASSERT_EQ(f.knuckles.size(), 1u);
  EXPECT_EQ(f.knuckles[0].vertices, (std::vector<Index>{a, s, b}));
  EXPECT_NEAR(f.knuckle_length(), 2 * std::hypot(0.5, 0.002), 1e-12);
}

TEST(Features, HintsAddAndSuppressKnuckles) {
  const Hull& h = hull(HullKind::kChine);
  const FeatureSet plain = features(h);
  ASSERT_FALSE(plain.knuckles.empty());

  // Suppress the transom knuckle by its plane x = 0; the chine stays.
  FeatureOptions o;
  KnuckleHint transom;
  transom.kind = KnuckleHint::Kind::kPlane;
  transom.plane_normal = {1, 0, 0};
  o.suppress.push_back(transom);
  const FeatureSet no_transom = features(h, o);
  EXPECT_EQ(no_transom.knuckles.size(), 1u);
  for (Index e = 0; e < h.adjacency.edges.size(); ++e) {
    const MeshEdge& me = h.adjacency.edges[e];
    if (no_transom.edge_knuckle[e]) {
      EXPECT_GT(h.tess.mesh.positions[me.v0].x + h.tess.mesh.positions[me.v1].x, 0.0);
    }
  }

  // Suppressing the only patch's pair with itself removes every knuckle inside it.
  FeatureOptions all;
  KnuckleHint pair;
  pair.kind = KnuckleHint::Kind::kPatchPair;
  pair.patch_a = pair.patch_b = 0;
  all.suppress.push_back(pair);
  EXPECT_TRUE(features(h, all).knuckles.empty());

  // Add a line of smooth edges on the Wigley (the waterline row at the design draft) by points,
  // and suppress wins where both match.
  const Hull& w = hull(HullKind::kWigley);
  const SurfaceMesh& m = w.tess.mesh;
  double row = 0, best = INFINITY;
  for (const Vec3d& p : m.positions) {
    if (std::abs(p.z - 4.0) < best) best = std::abs(p.z - 4.0), row = p.z;
  }
  std::vector<Vec3d> polyline;
  for (int i = 0; i <= 400; ++i) {
    const double x = 100.0 * i / 400, s = 2 * x / 100 - 1, t = row / 6.25 - 1;
    polyline.push_back({x, 5.0 * (1 - s * s) * (1 - t * t), row});
  }
  FeatureOptions add;
  KnuckleHint points;
  points.kind = KnuckleHint::Kind::kPoints;
  points.points = polyline;
  points.distance = 0.05;
  add.add.push_back(points);
  const FeatureSet added = features(w, add);
  ASSERT_EQ(added.knuckles.size(), 1u);
  for (Index v : added.knuckles[0].vertices) EXPECT_NEAR(m.positions[v].z, row, 1e-9);
  EXPECT_NEAR(added.knuckle_length(), 100.0, 5.0);  // about L along the waterline

  KnuckleHint fore;
  fore.kind = KnuckleHint::Kind::kPlane;
  fore.plane_point = {75, 0, 0};
  fore.plane_normal = {1, 0, 0};
  fore.distance = 25;
  add.suppress.push_back(fore);
  const FeatureSet half = features(w, add);
  EXPECT_LT(half.knuckle_length(), 0.6 * added.knuckle_length());
}

TEST(Features, CornersWhereKnucklesMeetBoundariesAndEachOther) {
  const Hull& h = hull(HullKind::kChine);
  const FeatureSet f = features(h);
  ASSERT_TRUE(std::is_sorted(f.corners.begin(), f.corners.end()));
  for (const FeatureLine& l : f.knuckles) {
    ASSERT_FALSE(l.closed);
    EXPECT_EQ(f.vertex_feature[l.vertices.front()], VertexFeature::kCorner);
    EXPECT_EQ(f.vertex_feature[l.vertices.back()], VertexFeature::kCorner);
    for (std::size_t i = 1; i + 1 < l.vertices.size(); ++i) {
      EXPECT_EQ(f.vertex_feature[l.vertices[i]], VertexFeature::kOnLine);
    }
  }
  for (Index c : f.corners) EXPECT_EQ(f.vertex_feature[c], VertexFeature::kCorner);
}

void expect_same_features(const FeatureSet& a, const FeatureSet& b) {
  EXPECT_EQ(a.edge_knuckle, b.edge_knuckle);
  EXPECT_EQ(a.corners, b.corners);
  EXPECT_EQ(a.candidates_rejected_by_nurbs, b.candidates_rejected_by_nurbs);
  ASSERT_EQ(a.knuckles.size(), b.knuckles.size());
  for (std::size_t i = 0; i < a.knuckles.size(); ++i) {
    EXPECT_EQ(a.knuckles[i].vertices, b.knuckles[i].vertices);
    EXPECT_EQ(a.knuckles[i].length, b.knuckles[i].length);
  }
  ASSERT_EQ(a.boundaries.size(), b.boundaries.size());
  for (std::size_t i = 0; i < a.boundaries.size(); ++i) {
    EXPECT_EQ(a.boundaries[i].vertices, b.boundaries[i].vertices);
    EXPECT_EQ(a.boundaries[i].kind, b.boundaries[i].kind);
  }
}

TEST(Features, SameResultWithOneTwoAndEightThreads) {
  const Hull& h = hull(HullKind::kChine);
  FeatureOptions o;
  o.knuckle_angle_deg = 4;  // many candidates, so the NURBS check runs in parallel
  const auto run = [&](int threads) {
    return hm::test::with_threads(threads, [&] { return features(h, o); });
  };
  const FeatureSet a = run(1);
  for (int threads : {2, 8}) {
    SCOPED_TRACE(threads);
    expect_same_features(a, run(threads));
  }
}

TEST(Features, RejectsNonManifoldMeshAndBadHints) {
  SurfaceMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  m.faces = {{0, 1, 2, kInvalid}, {1, 0, 3, kInvalid}, {0, 1, 4, kInvalid}};
  m.face_patch = {0, 0, 0};
  const EdgeAdjacency adjacency = build_edge_adjacency(m.faces, m.vertex_count());
  FeatureOptions o;
  o.confirm_on_nurbs = false;
  EXPECT_THROW(find_features(m, adjacency, {}, o), GeometryError);

  m.faces.pop_back();
  m.face_patch.pop_back();
  const EdgeAdjacency two = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_NO_THROW(find_features(m, two, {}, o));
  EXPECT_THROW(find_features(m, two, {}, FeatureOptions{}), GeometryError);  // no patch 0
  KnuckleHint bad;
  bad.kind = KnuckleHint::Kind::kPlane;
  o.add.push_back(bad);
  EXPECT_THROW(find_features(m, two, {}, o), UsageError);
}

TEST(Features, BoundaryKindNames) {
  EXPECT_STREQ(to_string(BoundaryKind::kDeckEdge), "deck edge");
  EXPECT_STREQ(to_string(BoundaryKind::kTransomEdge), "transom edge");
  EXPECT_STREQ(to_string(BoundaryKind::kCentrePlane), "centre plane");
  EXPECT_STREQ(to_string(BoundaryKind::kWaterline), "waterline");
  EXPECT_STREQ(to_string(BoundaryKind::kHole), "hole");
}

}  // namespace
}  // namespace hm
