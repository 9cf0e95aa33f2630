// Coarsening the merged hull into panels: the bounds it promises (features kept, deviation under
// the bound, manifold and oriented), the effect of each criterion, sources, the serial reference
// and thread-count independence. Small generated hulls; one real hull end to end.
#include "unstructured/coarsen.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/error.h"
#include "iges/read_iges.h"
#include "kernels/collapse_cost.h"
#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "quality/quality_report.h"
#include "query/hull_query.h"
#include "support/hull_spec.h"
#include "support/test_support.h"
#include "tessellate/tessellate.h"
#include "unstructured/measure_deviation.h"
#include "unstructured/merge.h"

namespace hm {
namespace {

struct Fine {
  std::vector<Patch> patches;
  double chord_error = 0;
  MergedSurface merged;
  EdgeAdjacency adj;
  FeatureSet features;
};

Fine fine_hull(std::vector<Patch> patches, std::size_t triangles) {
  Fine f;
  f.patches = std::move(patches);
  TessellateOptions o;
  o.edge_length = edge_length_for_triangles(f.patches, triangles);
  const Tessellation t = tessellate(f.patches, o, silent_progress());
  f.chord_error = t.summary.max_chord_error;
  f.merged = merge_patches(f.patches, t.mesh, {}, silent_progress());
  f.adj = build_edge_adjacency(f.merged.mesh.faces, f.merged.mesh.vertex_count());
  f.features = find_features(f.merged.mesh, f.adj, f.patches, {});
  return f;
}

Fine generated(HullKind kind, int patches, std::size_t triangles) {
  HullSpec spec;
  spec.kind = kind;
  spec.patches = patches;
  return fine_hull(generate_hull(spec).patches, triangles);
}

CoarsenedMesh coarsen_of(const Fine& f, CoarsenOptions o) {
  o.fine_chord_error = f.chord_error;
  return coarsen(f.patches, f.merged.mesh, f.adj, f.features, o, silent_progress());
}

double mean_shape(const SurfaceMesh& m) {
  double s = 0;
  for (const Face& fc : m.faces) {
    s += kernel::triangle_shape(m.positions[fc[0]], m.positions[fc[1]], m.positions[fc[2]]);
  }
  return s / static_cast<double>(m.face_count());
}

double min_angle_deg(const SurfaceMesh& m, const Face& f) {
  double lo = 180;
  for (int c = 0; c < 3; ++c) {
    const Vec3d a = m.positions[f[(c + 1) % 3]] - m.positions[f[c]];
    const Vec3d b = m.positions[f[(c + 2) % 3]] - m.positions[f[c]];
    lo = std::min(lo, std::atan2(norm(cross(a, b)), dot(a, b)) * 180 / M_PI);
  }
  return lo;
}

double share_angles_30(const SurfaceMesh& m) {
  std::size_t ok = 0;
  for (const Face& f : m.faces) ok += min_angle_deg(m, f) >= 30;
  return static_cast<double>(ok) / static_cast<double>(m.face_count());
}

// Mean equilateral edge of the panels whose centroid lies within [r0, r1) of p.
double mean_panel_edge(const SurfaceMesh& m, const Vec3d& p, double r0, double r1) {
  double sum = 0;
  std::size_t n = 0;
  for (const Face& f : m.faces) {
    const double d = norm(face_centroid(m.positions, f) - p);
    if (d < r0 || d >= r1) continue;
    sum += kernel::equilateral_edge(face_area(m.positions, f));
    ++n;
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

double line_length(const SurfaceMesh& m, std::span<const std::array<Index, 2>> edges) {
  double l = 0;
  for (const auto& e : edges) l += norm(m.positions[e[1]] - m.positions[e[0]]);
  return l;
}

// The checks every coarsened hull must pass.
void expect_sound(const Fine& f, const CoarsenedMesh& c, const CoarsenOptions& o) {
  const EdgeAdjacency adj = build_edge_adjacency(c.mesh.faces, c.mesh.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  // The same boundary loops as the fine surface (no hole opened, none closed).
  EXPECT_EQ(adj.boundary_loops.size(), f.adj.boundary_loops.size());
  // Every panel on the NURBS within the bound (measured independently of the witnesses).
  const HullQuery q(f.patches, f.merged.mesh);
  const DeviationMeasure dev = measure_deviation(q, c.mesh);
  EXPECT_LE(dev.max, c.report.max_deviation)
      << "at " << dev.where.x << ", " << dev.where.y << ", " << dev.where.z;
  // Corners never move: every fine corner is a panel vertex at the same place.
  std::set<Index> kept(c.vert_new2old.begin(), c.vert_new2old.end());
  for (Index v : f.features.corners) {
    ASSERT_TRUE(kept.count(v)) << "corner " << v << " was collapsed";
  }
  for (std::size_t v = 0; v < c.vert_new2old.size(); ++v) {
    if (c.vertex_feature[v] == VertexFeature::kCorner) {
      EXPECT_EQ(c.mesh.positions[v], f.merged.mesh.positions[c.vert_new2old[v]]);
    }
  }
  // Provenance: one patch per face, within range.
  ASSERT_EQ(c.mesh.face_patch.size(), c.mesh.face_count());
  for (PatchId p : c.mesh.face_patch) EXPECT_LT(p, f.patches.size());
  if (o.target_panels > 0 && c.report.target_reached) {
    EXPECT_LE(c.mesh.face_count(), o.target_panels);
    EXPECT_GE(c.mesh.face_count() + 2, o.target_panels);
  }
}

TEST(Coarsen, ChineHullKeepsKnucklesBoundariesAndTheBound) {
  const Fine f = generated(HullKind::kChine, 8, 30'000);
  CoarsenOptions o;
  o.target_panels = 1000;
  const CoarsenedMesh c = coarsen_of(f, o);
  expect_sound(f, c, o);
  EXPECT_TRUE(c.report.target_reached);
  // Knuckle and boundary lines survive: their length is that of the fine lines to issue 5's
  // 0.1% (chords of a curved line are a little shorter; measured 1.4e-6 short).
  double fine_len = f.features.knuckle_length();
  for (const BoundaryRun& b : f.features.boundaries) fine_len += b.length;
  const double coarse_len = line_length(c.mesh, c.feature_edges);
  EXPECT_NEAR(coarse_len / fine_len, 1.0, 1e-3);
  EXPECT_GT(share_angles_30(c.mesh), 0.93);
}

TEST(Coarsen, RoundBilgeHullReachesTheTargetWithGoodPanels) {
  const Fine f = generated(HullKind::kRoundBilge, 12, 30'000);
  CoarsenOptions o;
  o.target_panels = 1200;
  const CoarsenedMesh c = coarsen_of(f, o);
  expect_sound(f, c, o);
  EXPECT_GT(share_angles_30(c.mesh), 0.93);
  EXPECT_GT(c.report.collapses, 10'000u);
}

TEST(Coarsen, SameBytesWithOneTwoAndEightThreads) {
  const Fine f = generated(HullKind::kRoundBilge, 6, 20'000);
  CoarsenOptions o;
  o.target_panels = 800;
  const CoarsenedMesh one = hm::test::with_threads(1, [&] { return coarsen_of(f, o); });
  for (int threads : {2, 8}) {
    const CoarsenedMesh two = hm::test::with_threads(threads, [&] { return coarsen_of(f, o); });
    ASSERT_EQ(one.mesh.face_count(), two.mesh.face_count()) << threads;
    EXPECT_EQ(one.mesh.faces, two.mesh.faces) << threads;
    EXPECT_EQ(one.mesh.positions, two.mesh.positions) << threads;
    EXPECT_EQ(one.vert_new2old, two.vert_new2old) << threads;
  }
}

TEST(Coarsen, BatchedMatchesTheSerialPriorityQueue) {
  const Fine f = generated(HullKind::kWigley, 4, 20'000);
  CoarsenOptions o;
  o.target_panels = 800;
  const CoarsenedMesh batched = coarsen_of(f, o);
  o.serial_reference = true;
  const CoarsenedMesh serial = coarsen_of(f, o);
  expect_sound(f, serial, o);
  // Both stop at the target (a boundary collapse removes one face, so within two of it).
  EXPECT_NEAR(double(batched.mesh.face_count()), double(serial.mesh.face_count()), 2.0);
  // Batches reorder collapses a little; the panels must be as good.
  EXPECT_GT(mean_shape(batched.mesh), mean_shape(serial.mesh) - 0.02);
  EXPECT_GT(share_angles_30(batched.mesh), share_angles_30(serial.mesh) - 0.03);
}

TEST(Coarsen, PointSourceHalvesThePanelsWhereItIsAndNowhereElse) {
  const Fine f = generated(HullKind::kWigley, 4, 30'000);
  // No panel target: the field's size decides where coarsening stops.
  CoarsenOptions o;
  o.panel_size = 3.0;
  const CoarsenedMesh ref = coarsen_of(f, o);
  // On the mid-ship side of the Wigley, where curvature hardly sizes the panels.
  const HullQuery q(f.patches, f.merged.mesh);
  const Vec3d p = q.closest_point({50, 5, 3}).point;
  const double radius = 20;
  o.sources.push_back({SizeSource::Kind::kPoint, p, {}, radius, 0.5 * o.panel_size});
  const CoarsenedMesh with = coarsen_of(f, o);
  const double near_ratio =
      mean_panel_edge(with.mesh, p, 0, radius / 4) / mean_panel_edge(ref.mesh, p, 0, radius / 4);
  const double far_ratio = mean_panel_edge(with.mesh, p, 1.5 * radius, 1e9) /
                           mean_panel_edge(ref.mesh, p, 1.5 * radius, 1e9);
  EXPECT_NEAR(near_ratio, 0.5, 0.1);
  EXPECT_NEAR(far_ratio, 1.0, 0.08);
  expect_sound(f, with, o);
}

TEST(Coarsen, WeightsMoveTheMeshTheWayTheirCriterionAsks) {
  const Fine f = generated(HullKind::kRoundBilge, 6, 15'000);
  CoarsenOptions o;
  o.target_panels = 600;
  o.improve_passes = 0;   // the collapses alone
  o.max_deviation = 1.0;  // loose: the criteria, not the bound, size the panels
  // Curvature: with its weight up, panels on the curved bilge and bulb get smaller against
  // those on the flat side. (Weight 3: until the kernel stepped over knot spans of rounding
  // width, 39 fine vertices at patch borders had curvatures up to 8e13 1/m, and weight 2 made a
  // ratio of 0.75 partly from that noise; with the true curvatures it makes 0.82, weight 3 0.71.)
  auto curved_over_flat = [&](const CoarsenedMesh& c) {
    const std::vector<double> k = [&] {
      std::vector<double> out;
      for (std::size_t v = 0; v < c.mesh.vertex_count(); ++v) {
        const Patch& p = f.patches[c.mesh.vertex_patch[v]];
        const PrincipalCurvature pc =
            principal_curvature(p.surface, c.mesh.vertex_uv[v].x, c.mesh.vertex_uv[v].y);
        out.push_back(std::max(std::abs(pc.k1), std::abs(pc.k2)));
      }
      return out;
    }();
    double a_curved = 0, a_flat = 0;
    std::size_t n_curved = 0, n_flat = 0;
    for (const Face& fc : c.mesh.faces) {
      const double kf = std::min({k[fc[0]], k[fc[1]], k[fc[2]]});
      const double a = face_area(c.mesh.positions, fc);
      if (kf > 0.2) {
        a_curved += a;
        ++n_curved;
      } else if (kf < 0.02) {
        a_flat += a;
        ++n_flat;
      }
    }
    return (a_curved / std::max<std::size_t>(n_curved, 1)) /
           (a_flat / std::max<std::size_t>(n_flat, 1));
  };
  o.weights.curvature = 0;
  const double uniform = curved_over_flat(coarsen_of(f, o));
  o.weights.curvature = 3;
  const double adapted = curved_over_flat(coarsen_of(f, o));
  EXPECT_LT(adapted, 0.8 * uniform);
  // Shape: with its weight up, triangles come out closer to equilateral.
  o.weights.curvature = 1;
  o.weights.shape = 0.25;
  const double loose = mean_shape(coarsen_of(f, o).mesh);
  o.weights.shape = 4;
  const double strict = mean_shape(coarsen_of(f, o).mesh);
  EXPECT_GT(strict, loose);
}

TEST(Coarsen, TighterDeviationBoundKeepsMorePanelsOnCurves) {
  const Fine f = generated(HullKind::kRoundBilge, 6, 20'000);
  CoarsenOptions o;
  o.target_panels = 200;  // far below what the bound allows
  o.max_deviation = 0.04;
  const CoarsenedMesh c = coarsen_of(f, o);
  EXPECT_FALSE(c.report.target_reached);
  EXPECT_GT(c.mesh.face_count(), 200u);
  EXPECT_GT(c.report.rejected_deviation, 0u);
  expect_sound(f, c, o);
}

// A sparse fine mesh (about 6,000 triangles) and a bound the panels press on: the
// witnesses (fine vertices) sit away from the panels' centres, where a panel over a curved hull
// strays furthest. The samples' own check keeps the centres and edge midpoints inside the bound
// (without it: 0.0515 m against the 0.05 m bound, at x = 61 m).
TEST(Coarsen, PanelCentresKeepTheBoundWhereTheFineVerticesAreSparse) {
  const Fine f = generated(HullKind::kWigley, 4, 6'000);
  CoarsenOptions o;
  o.target_panels = 100;
  o.max_deviation = 0.05;
  const CoarsenedMesh c = coarsen_of(f, o);
  EXPECT_FALSE(c.report.target_reached);
  EXPECT_GT(c.report.rejected_deviation, 0u);
  expect_sound(f, c, o);
}

// The deviation the report gives comes from the closest-point query. A chine hull's patch folds
// at its transom (a repeated knot), and there the transom face barely moves with u as it narrows
// to the keel. A merged triangle beside the fold took corner (u, v) from that face, Newton
// stopped on it, and the report put a point on the bottom 0.5 m off the hull (property
// seed 1050 failed on such a point under --validate). The merged fine mesh measured as panels must
// come out within its own chord error.
TEST(Coarsen, DeviationOfTheFineMeshItselfIsWithinItsChordError) {
  const HullSpec spec =
      test::hull_spec(HullKind::kChine, 183.907, 16.8072, 7.20277, 9.69961, 2, /*full=*/true);
  const Fine f = fine_hull(generate_hull(spec).patches, 24'000);
  const HullQuery q(f.patches, f.merged.mesh);
  const DeviationMeasure dev = measure_deviation(q, f.merged.mesh);
  EXPECT_LE(dev.max, f.chord_error)
      << "at " << dev.where.x << ", " << dev.where.y << ", " << dev.where.z;
}

// The same patch's transom and bottom, wrapped into one: along the keel x moves 450 m per unit
// of u, across the transom a few metres. A merged triangle from the transom's far corner to the
// keel gave Newton a start on the transom, and the samples of its (u, v) box all fell beside the
// keel, so the point on the keel 0.8 m from the transom came out 0.8 m off the hull (property
// seed 1535 failed --validate on it). Points along the keel there must lie on the hull.
TEST(Coarsen, KeelPointsBesideATransomWrappedIntoThePatchAreOnTheHull) {
  HullSpec spec = test::hull_spec(HullKind::kChine, 194.434, 43.9488, 13.2013, 21.0994, 3, true);
  spec.defects.seed = 1535;
  spec.defects.gap = 0.0194434;
  spec.defects.overlap = 0.05;
  spec.defects.flip_every = 4;
  const Fine f = fine_hull(generate_hull(spec).patches, 24'000);
  const HullQuery q(f.patches, f.merged.mesh);
  double z_keel = std::numeric_limits<double>::infinity();
  for (const Vec3d& p : f.merged.mesh.positions) z_keel = std::min(z_keel, p.z);
  for (double x : {0.3, 0.806, 1.2, 2.0}) {
    const ClosestPoint c = q.closest_point({x, 0.0, z_keel});
    // The halves' keels lie 9.3 mm either side of y = 0 (the gap).
    EXPECT_LT(c.distance, 0.02) << "x " << x << ": nearest at " << c.point.x << ", " << c.point.y
                                << ", " << c.point.z;
  }
}

// A full Wigley's halves are tangent where its stem meets its keel, so a panel there whose corners
// lie on the stem and the keel lies in the centre plane on both sides: two panels back to back,
// which panel codes refuse. The hulls of property seeds 1133 and 1027 (full Wigleys with gaps of
// 1e-4 L) from 24,000 fine triangles; without the finish's flips apart, 1027's has 2 such pairs.
TEST(Coarsen, NoPanelsBackToBackWhereAFullWigleysHalvesAreTangent) {
  for (std::uint64_t seed : {1133u, 1027u}) {
    HullSpec spec =
        seed == 1133
            ? test::hull_spec(HullKind::kWigley, 151.886, 15.473, 4.22224, 5.36317, 9, true)
            : test::hull_spec(HullKind::kWigley, 116.467, 19.7171, 5.31376, 7.26129, 5, true);
    spec.defects.seed = seed;
    spec.defects.gap = spec.length * 1e-4;
    const Fine f = fine_hull(generate_hull(spec).patches, 24'000);
    CoarsenOptions o;
    o.target_panels = seed == 1133 ? 800 : 600;
    const CoarsenedMesh c = coarsen_of(f, o);
    QualityOptions qo;
    const QualityReport r = assess_quality(c.mesh, qo);
    EXPECT_EQ(r.close_centre_pairs, 0u) << "seed " << seed;
  }
}

TEST(Coarsen, RejectsBadOptionsAndBrokenInput) {
  const Fine f = generated(HullKind::kWigley, 1, 5'000);
  CoarsenOptions o;
  o.weights.shape = -1;
  EXPECT_THROW(coarsen_of(f, o), UsageError);
  o = {};
  o.weights = {0, 0, 0, 0};
  EXPECT_THROW(coarsen_of(f, o), UsageError);
  o = {};
  o.sources.push_back({SizeSource::Kind::kPoint, {0, 0, 0}, {}, 0.0, 1.0});
  EXPECT_THROW(coarsen_of(f, o), UsageError);
  o = {};
  o.mean_quality = 1.5;
  EXPECT_THROW(coarsen_of(f, o), UsageError);
  o = {};
  o.max_deviation = 1e-9;  // below the fine mesh's own chord error
  EXPECT_THROW(coarsen_of(f, o), UsageError);
  // Features of another mesh: sizes disagree.
  const Fine g = generated(HullKind::kWigley, 2, 6'000);
  EXPECT_THROW(coarsen(f.patches, f.merged.mesh, f.adj, g.features, {}, silent_progress()),
               GeometryError);
}

TEST(Coarsen, SharedKcsAtFourThousandPanels) {
  HM_REQUIRE_SHARED_HULL(path, "kcs.iges");
  const ImportResult hull = read_iges_file(path.string());
  const Fine f = fine_hull(hull.patches, 64'000);
  CoarsenOptions o;
  o.target_panels = 4000;
  const CoarsenedMesh c = coarsen_of(f, o);
  EXPECT_TRUE(c.report.target_reached);
  const EdgeAdjacency adj = build_edge_adjacency(c.mesh.faces, c.mesh.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  EXPECT_EQ(adj.boundary_loops.size(), f.adj.boundary_loops.size());
  EXPECT_GT(share_angles_30(c.mesh), 0.9);
}

}  // namespace
}  // namespace hm
