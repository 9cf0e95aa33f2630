#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "kernels/quality_metrics.h"
#include "mesh_builders.h"
#include "quality/quality_report.h"
#include "support/test_support.h"

namespace hm {
namespace {

// Rules with every gate off except the one a test is about.
QualityRules only_shares() {
  QualityRules r;
  r.require_convex = r.require_no_zero_area = r.require_no_close_centres = false;
  r.require_consistent_orientation = r.require_normals_into_fluid = false;
  r.require_no_free_edges_below_waterline = r.require_manifold = false;
  return r;
}

SurfaceMesh single_face(std::vector<Vec3d> pts) {
  SurfaceMesh m;
  m.positions = std::move(pts);
  m.faces.push_back({0, 1, 2, m.positions.size() == 4 ? Index{3} : kInvalid});
  m.face_patch = {0};
  return m;
}

TEST(FaceMetrics, EquilateralTriangleHasQOneAndSixtyDegrees) {
  const SurfaceMesh m = single_face({{0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}});
  kernel::FaceMetricArrays a;
  kernel::face_metrics(m.positions, m.faces, 1e-10, a);
  EXPECT_NEAR(a.equilateral[0], 1.0, 1e-14);
  EXPECT_NEAR(a.min_angle_deg[0], 60.0, 1e-12);
  EXPECT_NEAR(a.max_angle_deg[0], 60.0, 1e-12);
  EXPECT_NEAR(a.aspect_ratio[0], 1.0, 1e-14);
  EXPECT_NEAR(a.area[0], std::sqrt(3.0) / 4, 1e-15);
  EXPECT_EQ(a.zero_area[0], 0);
}

TEST(FaceMetrics, RightIsoscelesTriangle) {
  const SurfaceMesh m = single_face({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  kernel::FaceMetricArrays a;
  kernel::face_metrics(m.positions, m.faces, 1e-10, a);
  EXPECT_NEAR(a.min_angle_deg[0], 45.0, 1e-12);
  EXPECT_NEAR(a.max_angle_deg[0], 90.0, 1e-12);
  EXPECT_NEAR(a.equilateral[0], 4 * std::sqrt(3.0) * 0.5 / 4, 1e-14);
}

TEST(FaceMetrics, WarpedQuadWarp) {
  const double h = 0.1;
  const SurfaceMesh m = single_face({{0, 0, 0}, {1, 0, h}, {1, 1, 0}, {0, 1, h}});
  kernel::FaceMetricArrays a;
  kernel::face_metrics(m.positions, m.faces, 1e-10, a);
  // Mean plane z = h / 2 (Newell normal +z): every corner h / 2 off; mean diagonal sqrt(2).
  EXPECT_NEAR(a.warp[0], (h / 2) / std::sqrt(2.0), 1e-14);
  // Split 0-2: normals (-h, -h, 1) and (h, h, 1) (unnormalised): angle 2 atan(sqrt(2) h).
  EXPECT_NEAR(a.warp_angle_deg[0], 2 * std::atan(std::sqrt(2.0) * h) * 180 / std::numbers::pi,
              1e-10);
  EXPECT_EQ(a.convex[0], 1);
  EXPECT_EQ(a.is_quad[0], 1);
}

TEST(FaceMetrics, NonConvexQuadIsFlagged) {
  const SurfaceMesh m = single_face({{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0}, {0, 2, 0}});
  kernel::FaceMetricArrays a;
  kernel::face_metrics(m.positions, m.faces, 1e-10, a);
  EXPECT_EQ(a.convex[0], 0);
}

TEST(Quality, OneByFiveQuadFailsTheSideRatioRule) {
  const SurfaceMesh m = single_face({{0, 0, 0}, {5, 0, 0}, {5, 1, 0}, {0, 1, 0}});
  const QualityReport r = assess_quality(m, {});
  EXPECT_NEAR(r.per_face.side_ratio[0], 5.0, 1e-14);
  EXPECT_NEAR(r.per_face.aspect_ratio[0], 5.0, 1e-14);
  EXPECT_EQ(r.side_ratio_share, 0.0);
  const QualityRules rules = only_shares();
  EXPECT_FALSE(r.passes(rules));
  ASSERT_EQ(r.failures(rules).size(), 1u);
  EXPECT_NE(r.failures(rules)[0].find("side ratio"), std::string::npos);
  // A 1 x 3 quad passes it.
  const SurfaceMesh ok = single_face({{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {0, 1, 0}});
  EXPECT_TRUE(assess_quality(ok, {}).passes(rules));
  ASSERT_FALSE(r.worst.empty());
  EXPECT_EQ(r.worst[0].rule, QualityRule::kSideRatio);
}

TEST(Quality, ClosedBoxPassesEveryRule) {
  const SurfaceMesh m = test::box_mesh({0, 0, 0}, {1, 1, 1}, 4);
  QualityOptions o;
  o.waterline_z = 2.0;  // fully submerged
  const QualityReport r = assess_quality(m, o);
  EXPECT_TRUE(r.topology.watertight);
  EXPECT_TRUE(r.topology.orientation_consistent);
  EXPECT_TRUE(r.topology.normals_into_fluid);
  EXPECT_NEAR(r.topology.enclosed_volume, 1.0, 1e-12);
  EXPECT_EQ(r.knuckle_edges, 4u * 4 * 3);  // the 12 cube edges, 4 panels each
  EXPECT_EQ(r.max_normal_angle_deg, 0.0);  // the 90-degree edges are knuckles
  EXPECT_TRUE(r.passes(o.rules)) << format_table(r, o.rules);
  EXPECT_TRUE(r.worst.empty());
}

TEST(Quality, OneFlippedFaceIsReportedAndNamed) {
  SurfaceMesh m = test::box_mesh({0, 0, 0}, {1, 1, 1}, 3);
  const Index flipped = 20;
  std::swap(m.faces[flipped][1], m.faces[flipped][3]);
  QualityOptions o;
  o.waterline_z = 2.0;
  const QualityReport r = assess_quality(m, o);
  EXPECT_FALSE(r.topology.orientation_consistent);
  EXPECT_EQ(r.topology.inconsistent_edges, 4u);
  EXPECT_EQ(r.topology.flipped_faces, 1u);
  EXPECT_EQ(r.per_face.flipped[flipped], 1.0);
  EXPECT_FALSE(r.passes(o.rules));
  ASSERT_FALSE(r.worst.empty());
  EXPECT_EQ(r.worst[0].face, flipped);
  EXPECT_EQ(r.worst[0].rule, QualityRule::kFlipped);
}

TEST(Quality, InwardNormalsFailTheFluidRule) {
  SurfaceMesh m = test::box_mesh({0, 0, 0}, {1, 1, 1}, 2);
  for (Face& f : m.faces) std::swap(f[1], f[3]);
  QualityOptions o;
  o.waterline_z = 0.5;
  const QualityReport r = assess_quality(m, o);
  EXPECT_TRUE(r.topology.orientation_consistent);
  EXPECT_FALSE(r.topology.normals_into_fluid);
  EXPECT_NEAR(r.topology.enclosed_volume, -0.5, 1e-12);
  EXPECT_FALSE(r.passes(o.rules));
}

TEST(Quality, CubeWithBottomRemovedHasFourFreeEdgesBelowTheWaterline) {
  SurfaceMesh m = test::box_mesh({0, 0, 0}, {1, 1, 1}, 1);
  m.faces.erase(m.faces.begin() + 4);  // z = 0
  QualityOptions o;
  o.waterline_z = 0.5;
  o.half_hull = false;
  const QualityReport r = assess_quality(m, o);
  EXPECT_EQ(r.topology.boundary_edges, 4u);
  EXPECT_EQ(r.topology.free_edges_below, 4u);
  EXPECT_FALSE(r.topology.watertight);
  EXPECT_FALSE(r.passes(o.rules));
  ASSERT_FALSE(r.worst.empty());
  EXPECT_EQ(r.worst[0].rule, QualityRule::kFreeEdgeBelowWaterline);
  // The top removed instead: its edges are above the waterline, not free.
  SurfaceMesh top = test::box_mesh({0, 0, 0}, {1, 1, 1}, 1);
  top.faces.erase(top.faces.begin() + 5);
  const QualityReport rt = assess_quality(top, o);
  EXPECT_EQ(rt.topology.free_edges_below, 0u);
  EXPECT_EQ(rt.topology.above_water_edges, 4u);
}

// A half box open on y = 0 and at the top, its top edge given a sheer (raised towards x = 2),
// and one bottom panel beside the centre plane taken out: uncut, the whole top edge is the deck
// edge and only the hole's edges are free; judged against a waterline at the top, as before, the
// deck edge below the top was called free as well.
TEST(Quality, AnUncutHullsSheeredDeckEdgeIsNoHoleButAGapBesideTheKeelIs) {
  SurfaceMesh m = test::box_mesh({0, 0, 0}, {2, 1, 1}, 4);
  std::vector<Face> kept;
  std::size_t dropped_bottom = 0;
  for (const Face& f : m.faces) {
    const Vec3d n = face_normal(m.positions, f);
    const Vec3d c = face_centroid(m.positions, f);
    if (n.y < -0.5 || n.z > 0.5) continue;  // the centre plane and the deck
    if (n.z < -0.5 && c.y < 0.25 && c.x > 0.5 && c.x < 1.0) {
      ++dropped_bottom;  // the panel of the bottom beside the keel, at x 0.5..1
      continue;
    }
    kept.push_back(f);
  }
  ASSERT_EQ(dropped_bottom, 1u);
  m.faces = kept;
  m.face_patch.assign(kept.size(), 0);
  for (Vec3d& p : m.positions) {
    if (p.z > 0.5) p.z += 0.1 * p.x;  // the sheer: the deck edge rises 0.2 towards x = 2
  }
  QualityOptions o;
  o.half_hull = true;
  const QualityReport cut = assess_quality(m, o);
  // The old reading: the deck edge below the top at x = 2 is free, as is the hole.
  EXPECT_GT(cut.topology.free_edges_below, 4u);
  o.uncut = true;
  const QualityReport r = assess_quality(m, o);
  EXPECT_TRUE(r.topology.uncut);
  EXPECT_EQ(r.topology.boundary_loops, 1u);  // the hole opens onto the centre plane
  // The hole's three edges off the centre plane (its fourth lies on y = 0).
  EXPECT_EQ(r.topology.free_edges_below, 3u);
  EXPECT_EQ(r.topology.waterline_edges, 0u);
  // The deck edge: 4 edges along the side y = 1 and 4 across each end, x = 0 and x = 2.
  EXPECT_EQ(r.topology.above_water_edges, 12u);
  const std::vector<std::string> why = r.failures(o.rules);
  bool named = false;
  for (const std::string& w : why) named = named || w.find("3 free edges off the deck edge") == 0;
  EXPECT_TRUE(named);
}

TEST(Quality, HalfBoxBoundaryOnCentrePlaneAndWaterlineIsExpected) {
  // The wetted part of a half box: y >= 0, z <= 0.5, open on y = 0 and at the waterline.
  SurfaceMesh m = test::box_mesh({0, 0, 0}, {2, 1, 0.5}, 2);
  std::vector<Face> kept;
  for (const Face& f : m.faces) {
    const Vec3d n = face_normal(m.positions, f);
    if (n.y < -0.5 || n.z > 0.5) continue;  // drop the y = 0 and z = 0.5 sides
    kept.push_back(f);
  }
  m.faces = kept;
  m.face_patch.assign(kept.size(), 0);
  QualityOptions o;
  o.waterline_z = 0.5;
  const QualityReport r = assess_quality(m, o);
  EXPECT_TRUE(r.half_hull);  // detected: every vertex has y >= 0
  EXPECT_EQ(r.topology.free_edges_below, 0u);
  // The y = 0 and z = 0.5 sides are gone, and with them the edge they shared: 6 + 6 edges.
  EXPECT_EQ(r.topology.centre_plane_edges, 6u);
  EXPECT_EQ(r.topology.waterline_edges, 6u);
  EXPECT_TRUE(r.topology.normals_into_fluid);
  EXPECT_NEAR(r.topology.enclosed_volume, 1.0, 1e-12);
}

TEST(Quality, NeighbourAreaRatioOnAGradedStrip) {
  // Cells along x grow by `growth`: every interior neighbour pair has area ratio `growth`.
  for (double growth : {1.5, 3.0}) {
    const int n = 6;
    const SurfaceMesh m = test::grid_mesh(n, 1, [&](double s, double t) {
      const double x = (std::pow(growth, s * n) - 1) / (growth - 1);
      return Vec3d{x, t, 0};
    });
    const QualityReport r = assess_quality(m, {});
    EXPECT_NEAR(r.max_area_ratio, growth, 1e-12);
    for (int f = 0; f < n; ++f) EXPECT_NEAR(r.per_face.neighbour_area_ratio[f], growth, 1e-12);
    EXPECT_EQ(r.area_ratio_share, growth < 2 ? 1.0 : 0.0);
    EXPECT_EQ(r.area_ratio_pair_share, growth < 2 ? 1.0 : 0.0);
    EXPECT_EQ(r.max_normal_angle_deg, 0.0);
  }
}

TEST(Quality, AreaRatioPerPairCountsEdgesWherePerPanelCountsPanels) {
  // Four unit-width cells along x of widths 1, 1, 1, 3: only the last pair breaks the rule.
  // Per panel the last two fail (each has that neighbour); per pair one of three edges fails.
  const double edges[] = {0, 1, 2, 3, 6};
  const SurfaceMesh m = test::grid_mesh(4, 1, [&](double s, double t) {
    return Vec3d{edges[int(std::lround(4 * s))], t, 0};
  });
  const QualityReport r = assess_quality(m, {});
  EXPECT_NEAR(r.area_ratio_share, 0.5, 1e-12);
  EXPECT_NEAR(r.area_ratio_pair_share, 2.0 / 3.0, 1e-12);
  const auto j = nlohmann::json::parse(to_json(r, QualityRules{}));
  EXPECT_NEAR(j["rules"]["area_ratio"]["pair_share"].get<double>(), 2.0 / 3.0, 1e-12);
}

TEST(Quality, NormalAngleBetweenNeighboursAwayFromKnuckles) {
  // Two quads folded by 20 degrees: fails the 15-degree rule unless the edge is a knuckle.
  const double a = 20 * std::numbers::pi / 180;
  SurfaceMesh m;
  m.positions = {{0, 0, 0},
                 {1, 0, 0},
                 {1, 1, 0},
                 {0, 1, 0},
                 {1 + std::cos(a), 0, std::sin(a)},
                 {1 + std::cos(a), 1, std::sin(a)}};
  m.faces = {{0, 1, 2, 3}, {1, 4, 5, 2}};
  m.face_patch = {0, 0};
  QualityOptions o;
  const QualityReport r = assess_quality(m, o);
  EXPECT_NEAR(r.max_normal_angle_deg, 20.0, 1e-10);
  EXPECT_EQ(r.normal_angle_share, 0.0);
  o.knuckle_edges = {{2, 1}};
  const QualityReport rk = assess_quality(m, o);
  EXPECT_EQ(rk.knuckle_edges, 1u);
  EXPECT_EQ(rk.normal_angle_share, 1.0);
  o.knuckle_edges.clear();
  o.knuckle_angle_deg = 10;
  EXPECT_EQ(assess_quality(m, o).normal_angle_share, 1.0);
}

TEST(Quality, WorstListNamesTheDegenerateFace) {
  SurfaceMesh m = test::grid_mesh(4, 4, [](double s, double t) { return Vec3d{s, t, 0}; });
  // Face 9 becomes corners (0, 1, 1', 0) with 1' a coincident copy of corner 1: zero area.
  m.positions.push_back(m.positions[m.faces[9][1]]);
  m.faces[9][2] = static_cast<Index>(m.positions.size() - 1);
  m.faces[9][3] = m.faces[9][0];
  const QualityReport r = assess_quality(m, {});
  EXPECT_EQ(r.zero_area, 1u);
  EXPECT_EQ(r.per_face.zero_area[9], 1.0);
  ASSERT_FALSE(r.worst.empty());
  EXPECT_EQ(r.worst[0].face, 9u);
  EXPECT_EQ(r.worst[0].rule, QualityRule::kZeroArea);
  EXPECT_FALSE(r.passes({}));
}

TEST(Quality, DuplicatedPanelGivesACloseCentrePair) {
  SurfaceMesh m = test::grid_mesh(5, 5, [](double s, double t) { return Vec3d{s, t, 0}; });
  const Face dup = m.faces[7];
  m.faces.push_back(dup);
  m.face_patch.push_back(0);
  const QualityReport r = assess_quality(m, {});
  EXPECT_EQ(r.close_centre_pairs, 1u);
  EXPECT_EQ(r.per_face.close_centre[7], 1.0);
  EXPECT_EQ(r.per_face.close_centre[25], 1.0);
  EXPECT_EQ(r.per_face.close_centre[8], 0.0);
  EXPECT_GE(r.topology.nonmanifold_edges, 1u);  // the duplicate shares edges three times
}

TEST(Quality, WaveFiguresFromSpeedAndFroude) {
  // A 100 m x 10 m flat "hull side" at the waterline z = 0 with 50 panels along x.
  const SurfaceMesh m = test::grid_mesh(50, 5, [](double s, double t) {
    return Vec3d{100 * s, 0, -10 * t};
  });
  QualityOptions o;
  o.waterline_z = 0.0;
  o.waves.speed = 10.0;
  const QualityReport r = assess_quality(m, o);
  const double lambda = 2 * std::numbers::pi * 100 / 9.80665;
  EXPECT_NEAR(r.waves.wavelength, lambda, 1e-12);
  EXPECT_NEAR(r.waves.panel_length_x, 2.0, 1e-12);
  EXPECT_NEAR(r.waves.panels_per_wavelength, lambda / 2, 1e-10);
  EXPECT_FALSE(r.waves.warn);
  EXPECT_NEAR(r.waves.length, 100.0, 1e-12);
  o.waves.speed.reset();
  o.waves.froude = 0.1;  // U = 0.1 sqrt(g 100): lambda = 2 pi 0.01 L = 6.28 m, ~3 panels
  const QualityReport rf = assess_quality(m, o);
  EXPECT_NEAR(rf.waves.wavelength, 2 * std::numbers::pi * 0.01 * 100, 1e-10);
  EXPECT_TRUE(rf.waves.warn);
}

TEST(Quality, IdenticalForOneAndEightThreads) {
  const SurfaceMesh m = test::sphere_mesh(1.0, {0, 0, 0}, 48, 24);
  const QualityReport r1 = hm::test::with_threads(1, [&] { return assess_quality(m, {}); });
  const QualityReport r2 = hm::test::with_threads(8, [&] { return assess_quality(m, {}); });
  EXPECT_EQ(to_json(r1, {}), to_json(r2, {}));
  EXPECT_EQ(r1.per_face.neighbour_normal_angle, r2.per_face.neighbour_normal_angle);
  EXPECT_EQ(r1.per_face.equilateral, r2.per_face.equilateral);
}

// The crossing count is measured by the caller (the BVH lives in src/query); unmeasured, the rule
// is not applied and the outputs say so.
TEST(Quality, CrossingPanelsFailAHardRuleWhenMeasured) {
  const SurfaceMesh m = test::box_mesh({0, 0, 0}, {1, 1, 1}, 4);
  QualityOptions o;
  o.waterline_z = 2.0;
  const QualityReport unmeasured = assess_quality(m, o);
  EXPECT_TRUE(unmeasured.passes(o.rules));
  EXPECT_TRUE(nlohmann::json::parse(to_json(unmeasured, o.rules))["crossing_pairs"].is_null());
  EXPECT_NE(format_table(unmeasured, o.rules).find("not checked"), std::string::npos);
  o.crossing_pairs = 3;
  o.crossing_where = {0.5, 0.25, 1};
  const QualityReport r = assess_quality(m, o);
  ASSERT_FALSE(r.passes(o.rules));
  ASSERT_EQ(r.failures(o.rules).size(), 1u);
  EXPECT_NE(r.failures(o.rules)[0].find("3 pairs of panels pass through each other"),
            std::string::npos);
  EXPECT_NE(r.failures(o.rules)[0].find("x 0.5, y 0.25, z 1 m"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(to_json(r, o.rules))["crossing_pairs"].get<int>(), 3);
  o.rules.require_no_crossing = false;
  EXPECT_TRUE(r.passes(o.rules));
}

TEST(Quality, JsonTableAndFieldsAgree) {
  const SurfaceMesh m = test::sphere_mesh(1.0, {0, 0, 0}, 24, 12);
  QualityOptions o;
  o.waterline_z = 0.0;
  const QualityReport r = assess_quality(m, o);
  const nlohmann::json j = nlohmann::json::parse(to_json(r, o.rules));
  EXPECT_EQ(j["faces"].get<std::size_t>(), m.face_count());
  EXPECT_EQ(j["passes"].get<bool>(), r.passes(o.rules));
  EXPECT_EQ(j["triangles"].get<std::size_t>(), 48u);  // the pole caps
  const std::string table = format_table(r, o.rules);
  EXPECT_NE(table.find(r.passes(o.rules) ? "PASS" : "FAIL"), std::string::npos);
  for (const FaceField& f : face_fields(r)) EXPECT_EQ(f.values.size(), m.face_count()) << f.name;
  // A UV sphere's pole triangles are slivers in angle terms, but every panel is convex.
  EXPECT_EQ(r.non_convex, 0u);
  EXPECT_EQ(r.zero_area, 0u);
  EXPECT_TRUE(r.topology.watertight);
}

}  // namespace
}  // namespace hm
