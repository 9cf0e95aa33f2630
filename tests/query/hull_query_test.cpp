#include "query/hull_query.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/error.h"
#include "query_test_geometry.h"
#include "support/test_support.h"

namespace hm {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR = 2.0, kH = 3.0;               // cylinder radius and height (m)
constexpr double kL = 10.0, kB = 1.0, kT = 0.625;  // Wigley length, beam, draft (m)

struct Scene {
  std::vector<Patch> patches;
  SurfaceMesh mesh;
  HullQuery query() const { return HullQuery(patches, mesh); }
};

Scene quarter_cylinder_scene(bool reversed = false) {
  Scene s;
  s.patches.push_back(test::make_patch(test::quarter_cylinder(kR, kH), reversed));
  test::add_grid(s.mesh, s.patches[0], 0, 12, 6);
  return s;
}

Scene wigley_scene() {
  Scene s;
  s.patches.push_back(test::make_patch(test::wigley(kL, kB, kT)));
  test::add_grid(s.mesh, s.patches[0], 0, 40, 12);
  return s;
}

// The Wigley hull as two patches meeting at x = 0; welded: the border is a shared mesh edge
// chain; not welded: each side has its own border vertices at different spacings.
Scene split_wigley_scene(bool welded) {
  Scene s;
  auto [left, right] = test::split_bezier_u(test::wigley(kL, kB, kT));
  s.patches.push_back(test::make_patch(left));
  s.patches.push_back(test::make_patch(right));
  test::add_grid(s.mesh, s.patches[0], 0, 20, 12);
  test::add_grid(s.mesh, s.patches[1], 1, 20, welded ? 12 : 17);
  if (welded) test::weld(s.mesh, 1e-12);
  return s;
}

// The whole cylinder as one closed patch whose seam vertices are shared.
Scene full_cylinder_scene() {
  Scene s;
  s.patches.push_back(test::make_patch(test::full_cylinder(kR, kH)));
  test::add_grid(s.mesh, s.patches[0], 0, 48, 6);
  test::weld(s.mesh, 1e-12);
  return s;
}

double radius(const Vec3d& p) { return std::hypot(p.x, p.y); }

TEST(HullQuery, RaysFromTheAxisHitTheCylinderAtItsRadius) {
  const Scene scene = quarter_cylinder_scene();
  const HullQuery q = scene.query();
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> angle(0.02, kPi / 2 - 0.02), z(0.7, 2.3), dz(-0.3, 0.3);
  for (int i = 0; i < 500; ++i) {
    const double a = angle(rng);
    const Ray ray{{0, 0, z(rng)}, {std::cos(a), std::sin(a), dz(rng)}};
    const RayHit h = q.first_hit(ray);
    ASSERT_TRUE(h.valid()) << i;
    ASSERT_TRUE(h.on_surface) << i;
    EXPECT_EQ(h.patch, 0u);
    EXPECT_NEAR(radius(h.point), kR, 1e-12);
    EXPECT_LT(norm(ray.origin + h.t * ray.dir - h.point), 1e-12);
    // Outward normal: the patch is not reversed and su x sv points away from the axis.
    EXPECT_NEAR(h.normal.x, h.point.x / kR, 1e-9);
    EXPECT_NEAR(h.normal.y, h.point.y / kR, 1e-9);
  }
}

TEST(HullQuery, RaysFromOutsideHitAndReversedPatchesFlipTheNormal) {
  const Scene scene = quarter_cylinder_scene(/*reversed=*/true);
  const HullQuery q = scene.query();
  const Ray ray{{5, 5, 1.0}, {-1, -1, 0.1}};
  const RayHit h = q.first_hit(ray);
  ASSERT_TRUE(h.valid());
  EXPECT_NEAR(radius(h.point), kR, 1e-12);
  EXPECT_NEAR(h.point.x, kR / std::sqrt(2.0), 1e-12);
  EXPECT_LT(dot(h.normal, h.point - Vec3d{0, 0, h.point.z}), 0);  // inward: reversed
  // The same ray stopped short, and a ray pointing away, miss.
  EXPECT_FALSE(q.first_hit({ray.origin, ray.dir, 0.5}).valid());
  EXPECT_FALSE(q.first_hit({ray.origin, -ray.dir}).valid());
}

TEST(HullQuery, AllHitsThroughTwoParallelPlatesAreFoundInOrder) {
  Scene s;
  s.patches.push_back(test::make_patch(test::plate_x(0.0, 1.0)));
  s.patches.push_back(test::make_patch(test::plate_x(1.0, 1.0)));
  test::add_grid(s.mesh, s.patches[0], 0, 4, 4);
  test::add_grid(s.mesh, s.patches[1], 1, 4, 4);
  const HullQuery q = s.query();
  // Through the middle of a triangle, and exactly through grid edges and vertices (y = z = 0).
  for (const Vec3d& o : {Vec3d{-1, 0.31, -0.27}, Vec3d{-1, 0, 0}, Vec3d{-1, 0.5, 0.13}}) {
    const std::vector<RayHit> hits = q.all_hits({o, {2, 0.01, 0.02}});
    ASSERT_EQ(hits.size(), 2u) << o.y << " " << o.z;
    EXPECT_EQ(hits[0].patch, 0u);
    EXPECT_EQ(hits[1].patch, 1u);
    EXPECT_LT(hits[0].t, hits[1].t);
    EXPECT_NEAR(hits[0].point.x, 0.0, 1e-12);
    EXPECT_NEAR(hits[1].point.x, 1.0, 1e-12);
    EXPECT_NEAR(hits[0].t, 0.5, 1e-12);
    const std::vector<RayHit> back = q.all_hits({{2, o.y, o.z}, {-1, 0, 0}});
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back[0].patch, 1u);
    EXPECT_EQ(back[1].patch, 0u);
  }
  // tmax between the plates keeps only the first.
  EXPECT_EQ(q.all_hits({{-1, 0.2, 0.2}, {1, 0, 0}, 1.5}).size(), 1u);
}

std::vector<Ray> random_rays(const BBox3d& box, int count, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  const Vec3d c = box.center(), e = box.extent();
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3d o = c + Vec3d{e.x * unit(rng), e.y * unit(rng), e.z * unit(rng)};
    const Vec3d target = c + 0.5 * Vec3d{e.x * unit(rng), e.y * unit(rng), e.z * unit(rng)};
    rays.push_back({o, target - o});
  }
  return rays;
}

TEST(HullQuery, BatchedFirstHitsEqualSingleOnes) {
  const Scene scene = split_wigley_scene(true);
  const HullQuery q = scene.query();
  const std::vector<Ray> rays = random_rays(q.bbox(), 3000, 7);
  std::vector<RayHit> batch(rays.size());
  q.first_hits(rays, batch);
  int hits = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const RayHit one = q.first_hit(rays[i]);
    ASSERT_EQ(one.valid(), batch[i].valid()) << i;
    if (!one.valid()) continue;
    ++hits;
    EXPECT_EQ(one.patch, batch[i].patch);
    EXPECT_EQ(one.point, batch[i].point);
    EXPECT_EQ(one.t, batch[i].t);
    EXPECT_TRUE(one.on_surface);
    EXPECT_NEAR(one.point.y, test::wigley_y(kL, kB, kT, one.point.x, one.point.z), 1e-9 * kL);
  }
  EXPECT_GT(hits, 300);  // the rays aim at the hull's box, so many hit
}

TEST(HullQuery, ClosestPointOnTheCylinderMatchesTheAnalyticAnswer) {
  const Scene scene = quarter_cylinder_scene();
  const HullQuery q = scene.query();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> angle(0.01, kPi / 2 - 0.01), r(0.3 * kR, 1.7 * kR),
      z(0.05 * kH, 0.95 * kH);
  std::vector<Vec3d> points;
  for (int i = 0; i < 400; ++i) {
    const double a = angle(rng), rr = r(rng);
    points.push_back({rr * std::cos(a), rr * std::sin(a), z(rng)});
  }
  std::vector<ClosestPoint> batch(points.size());
  q.closest_points(points, batch);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3d& p = points[i];
    const Vec3d expected{kR * p.x / radius(p), kR * p.y / radius(p), p.z};
    const ClosestPoint c = q.closest_point(p);
    ASSERT_TRUE(c.valid());
    EXPECT_LT(norm(c.point - expected), 1e-10) << i;
    EXPECT_NEAR(c.distance, std::abs(radius(p) - kR), 1e-10);
    EXPECT_NEAR(dot(c.normal, expected / kR - Vec3d{0, 0, p.z / kR}), 1.0, 1e-9);
    EXPECT_EQ(batch[i].point, c.point);
  }
  // Beyond the patch's end the nearest point is on its edge z = H.
  const ClosestPoint top = q.closest_point({1.0, 1.0, kH + 1});
  EXPECT_NEAR(top.point.z, kH, 1e-10);
  EXPECT_NEAR(radius(top.point), kR, 1e-10);
}

TEST(HullQuery, ClosestPointAcrossASeamAndBetweenPatches) {
  const Scene cyl = full_cylinder_scene();
  const HullQuery q = cyl.query();
  for (double a : {-1e-3, 0.0, 1e-3, 2.0, 4.0}) {
    const Vec3d p{1.3 * kR * std::cos(a), 1.3 * kR * std::sin(a), 1.1};
    const ClosestPoint c = q.closest_point(p);
    EXPECT_LT(norm(c.point - Vec3d{kR * std::cos(a), kR * std::sin(a), 1.1}), 1e-10) << a;
  }
  // Near the border x = 0 of the split Wigley hull, the answer lies on either side.
  const Scene split = split_wigley_scene(false);
  const HullQuery w = split.query();
  for (double x : {-0.3, -1e-3, 0.0, 1e-3, 0.4}) {
    const Vec3d surface{x, test::wigley_y(kL, kB, kT, x, -0.2), -0.2};
    const ClosestPoint c = w.closest_point(surface + Vec3d{0, 1e-3, 0});
    EXPECT_LT(c.distance, 1e-3 + 1e-12) << x;
    EXPECT_NEAR(c.point.y, test::wigley_y(kL, kB, kT, c.point.x, c.point.z), 1e-10);
    EXPECT_EQ(c.patch, x < 0 ? 0u : (x > 0 ? 1u : c.patch));
  }
}

// A merge stitches a patch's border to an overlapping patch's cut with triangles named for the
// first patch, reaching up to a panel past its end. Here the first column of the forward half's
// triangles is named for the aft half: their forward corners project onto the aft half's end,
// 0.25 m away. A point just off them is still answered from the surface it lies on.
TEST(HullQuery, ClosestPointOnTrianglesReachingPastTheirPatch) {
  Scene split = split_wigley_scene(true);
  const double column = 0.5 * kL / 20;
  std::vector<Index> renamed;
  for (std::size_t f = 0; f < split.mesh.face_count(); ++f) {
    if (split.mesh.face_patch[f] != 1) continue;
    const Vec3d c = face_centroid(split.mesh.positions, split.mesh.faces[f]);
    if (c.x < column) {
      split.mesh.face_patch[f] = 0;
      renamed.push_back(static_cast<Index>(f));
    }
  }
  ASSERT_EQ(renamed.size(), 24u);
  const HullQuery w = split.query();
  for (Index f : renamed) {
    const auto& face = split.mesh.faces[f];
    const Vec3d c = face_centroid(split.mesh.positions, face);
    const Vec3d n =
        normalized(cross(split.mesh.positions[face[1]] - split.mesh.positions[face[0]],
                         split.mesh.positions[face[2]] - split.mesh.positions[face[0]]));
    const ClosestPoint cp = w.closest_point(c + 1e-3 * n);
    EXPECT_LT(cp.distance, 1.01e-3) << f;
    EXPECT_NEAR(cp.point.y, test::wigley_y(kL, kB, kT, cp.point.x, cp.point.z), 1e-10) << f;
  }
}

void expect_on_wigley(const SectionPolyline& line, const Plane& plane) {
  const Vec3d n = normalized(plane.normal);
  for (const SectionPoint& p : line.points) {
    EXPECT_LT(std::abs(p.point.y - test::wigley_y(kL, kB, kT, p.point.x, p.point.z)), 1e-9 * kL);
    EXPECT_LT(std::abs(dot(n, p.point - plane.point)), 1e-9 * kL);
  }
}

TEST(HullQuery, WigleyStationsLieOnTheClosedFormAndThePlane) {
  const Scene scene = wigley_scene();
  const HullQuery q = scene.query();
  for (double x : {-4.9, -3.33, -1.0, 0.0, 0.77, 2.5, 4.5}) {
    const Plane plane{{x, 0, 0}, {1, 0, 0}};
    const Section s = q.section(plane);
    ASSERT_EQ(s.polylines.size(), 1u) << x;
    const SectionPolyline& line = s.polylines[0];
    EXPECT_FALSE(line.closed);
    expect_on_wigley(line, plane);
    // From the keel (z = -T, y = 0) up to the waterline z = 0.
    EXPECT_NEAR(line.points.front().point.z, -kT, 1e-9);
    EXPECT_NEAR(line.points.front().point.y, 0.0, 1e-9);
    EXPECT_NEAR(line.points.back().point.z, 0.0, 1e-9);
    for (std::size_t i = 1; i < line.points.size(); ++i) {
      EXPECT_GT(line.points[i].point.z, line.points[i - 1].point.z);
    }
  }
}

// A vertex whose (u, v) is that of the patch's border below it (as a merge repair can leave one
// at a corner it moved onto another patch): the crossings on its edges would refine along a
// parameter segment that runs down to the keel. They stay on the edges instead, so the station
// stays in order from keel to waterline.
TEST(HullQuery, CrossingsWithAFarCornerUvStayOnTheirEdges) {
  Scene scene = wigley_scene();
  auto nearest = [&](const Vec3d& target) {
    Index best = 0;
    for (Index v = 0; v < scene.mesh.vertex_count(); ++v) {
      if (squared_norm(scene.mesh.positions[v] - target) <
          squared_norm(scene.mesh.positions[best] - target))
        best = v;
    }
    return best;
  };
  const Index bad = nearest({0.77, 0.4, -0.3});
  const Vec3d at = scene.mesh.positions[bad];
  scene.mesh.vertex_uv[bad] = scene.mesh.vertex_uv[nearest({at.x, 0, -kT})];
  const HullQuery q = scene.query();
  const Plane plane{{scene.mesh.positions[bad].x + 0.05, 0, 0}, {1, 0, 0}};
  const Section s = q.section(plane);
  ASSERT_EQ(s.polylines.size(), 1u);
  const SectionPolyline& line = s.polylines[0];
  for (std::size_t i = 0; i < line.points.size(); ++i) {
    const Vec3d& p = line.points[i].point;
    EXPECT_LT(std::abs(p.x - plane.point.x), 1e-9 * kL);
    // On the NURBS, or on a fine edge within its chord error.
    EXPECT_LT(std::abs(p.y - test::wigley_y(kL, kB, kT, p.x, p.z)), 1e-2);
    if (i > 0) {
      EXPECT_GT(p.z, line.points[i - 1].point.z) << i;
    }
  }
}

TEST(HullQuery, UnrefinedSectionsStayOnTheTriangles) {
  const Scene scene = wigley_scene();
  const HullQuery q = scene.query();
  SectionOptions quick;
  quick.refine = false;
  const Plane plane{{1.7, 0, 0}, {1, 0, 0.2}};
  const Section exact = q.section(plane), rough = q.section(plane, quick);
  ASSERT_EQ(rough.polylines.size(), 1u);
  ASSERT_EQ(rough.polylines[0].points.size(), exact.polylines[0].points.size());
  double worst = 0;
  for (const SectionPoint& p : rough.polylines[0].points) {
    EXPECT_LT(std::abs(dot(normalized(plane.normal), p.point - plane.point)), 1e-12 * kL);
    worst = std::max(worst, std::abs(p.point.y - test::wigley_y(kL, kB, kT, p.point.x, p.point.z)));
  }
  // Off the surface by about the chord error of a 40 x 12 grid, not by round-off.
  EXPECT_GT(worst, 1e-7);
  EXPECT_LT(worst, 1e-2);
}

TEST(HullQuery, WaterlineIsOneOpenOrderedPolylineFromEndToEnd) {
  const Scene scene = wigley_scene();
  const HullQuery q = scene.query();
  const Plane plane{{0, 0, -0.3 * kT}, {0, 0, 1}};
  const Section s = q.section(plane);
  ASSERT_EQ(s.polylines.size(), 1u);
  const SectionPolyline& line = s.polylines[0];
  EXPECT_FALSE(line.closed);
  expect_on_wigley(line, plane);
  EXPECT_NEAR(line.points.front().point.x, -kL / 2, 1e-9);
  EXPECT_NEAR(line.points.back().point.x, kL / 2, 1e-9);
  for (std::size_t i = 1; i < line.points.size(); ++i) {
    EXPECT_GT(line.points[i].point.x, line.points[i - 1].point.x);
  }
}

TEST(HullQuery, SectionAcrossAPatchBorderIsOneChain) {
  for (bool welded : {true, false}) {
    const Scene scene = split_wigley_scene(welded);
    const HullQuery q = scene.query();
    for (const Plane& plane :
         {Plane{{0, 0, -0.4 * kT}, {0, 0, 1}}, Plane{{0, 0.3 * kB, 0}, {0, 1, 0}},
          Plane{{0, 0, -0.2}, {0.05, 0.2, 1}}}) {
      const Section s = q.section(plane);
      ASSERT_EQ(s.polylines.size(), 1u) << welded;
      const SectionPolyline& line = s.polylines[0];
      expect_on_wigley(line, plane);
      bool on0 = false, on1 = false;
      for (const SectionPoint& p : line.points) {
        on0 |= p.patch == 0;
        on1 |= p.patch == 1;
        const Vec3d again = evaluate(scene.patches[p.patch].surface, p.uv.x, p.uv.y);
        EXPECT_LT(norm(again - p.point), 1e-12);
      }
      EXPECT_TRUE(on0 && on1);
      for (std::size_t i = 1; i < line.points.size(); ++i) {
        EXPECT_GT(norm(line.points[i].point - line.points[i - 1].point), 1e-10 * kL);
      }
      // Welded, the shared mesh edges chain the two sides; not welded, the gap join does (the
      // refined border points coincide to round-off, so a tiny tolerance suffices, zero not).
      SectionOptions strict;
      strict.join_tolerance = 0;
      EXPECT_EQ(q.section(plane, strict).polylines.size(), welded ? 1u : 2u);
      strict.join_tolerance = 1e-12;
      EXPECT_EQ(q.section(plane, strict).polylines.size(), 1u);
    }
  }
}

TEST(HullQuery, ClosedSectionIsCounterClockwiseAboutTheNormal) {
  Scene s;  // the cylinder from four quarter patches sharing their borders
  for (int k = 0; k < 4; ++k) {
    NurbsSurface c = test::quarter_cylinder(kR, kH);
    const double a = k * kPi / 2;
    for (Vec3d& p : c.points) {
      p = {std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y, p.z};
    }
    s.patches.push_back(test::make_patch(c));
    test::add_grid(s.mesh, s.patches[k], k, 9, 4);
  }
  test::weld(s.mesh, 1e-12);
  const Scene seam = full_cylinder_scene();
  for (const Scene* scene : std::initializer_list<const Scene*>{&s, &seam}) {
    const HullQuery q = scene->query();
    for (double sign : {1.0, -1.0}) {
      const Section sec = q.section({{0, 0, 1.3}, {0.1, 0.0, sign}});
      ASSERT_EQ(sec.polylines.size(), 1u);
      const SectionPolyline& line = sec.polylines[0];
      EXPECT_TRUE(line.closed);
      double turn = 0;
      for (std::size_t i = 0; i < line.points.size(); ++i) {
        const Vec3d& a = line.points[i].point;
        const Vec3d& b = line.points[(i + 1) % line.points.size()].point;
        EXPECT_NEAR(radius(a), kR, 1e-9 * kR);
        turn += sign * (a.x * b.y - a.y * b.x);
      }
      EXPECT_GT(turn, 0);
    }
  }
}

// A plane through a random point of the Wigley's box below the waterline, any direction.
Plane random_plane(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const Vec3d point{0.5 * kL * unit(rng), 0.5 * kB * unit(rng), -kT * (0.5 + 0.5 * unit(rng))};
  return {point, {unit(rng), unit(rng), unit(rng)}};
}

TEST(HullQuery, BvhSectionEqualsBruteForce) {
  const Scene scene = split_wigley_scene(false);
  const HullQuery q = scene.query();
  std::mt19937_64 rng(11);
  int nonempty = 0;
  for (int i = 0; i < 60; ++i) {
    const Plane plane = random_plane(rng);
    const Section a = q.section(plane), b = q.section_brute_force(plane);
    ASSERT_EQ(a.polylines.size(), b.polylines.size());
    nonempty += !a.polylines.empty();
    for (std::size_t k = 0; k < a.polylines.size(); ++k) {
      ASSERT_EQ(a.polylines[k].points.size(), b.polylines[k].points.size());
      EXPECT_EQ(a.polylines[k].closed, b.polylines[k].closed);
      for (std::size_t j = 0; j < a.polylines[k].points.size(); ++j) {
        EXPECT_EQ(a.polylines[k].points[j].point, b.polylines[k].points[j].point);
        EXPECT_EQ(a.polylines[k].points[j].patch, b.polylines[k].points[j].patch);
      }
    }
  }
  EXPECT_GT(nonempty, 20);
}

// The search alone: the BVH and the loop list the same faces, and every listed face has corners
// on both sides of the plane (the grid's faces are quads, so a face's crossed halves both count).
TEST(HullQuery, CrossedFacesThroughTheBvhEqualTheLoopAndStraddleThePlane) {
  const Scene scene = split_wigley_scene(false);
  const HullQuery q = scene.query();
  std::mt19937_64 rng(12);
  int nonempty = 0;
  for (int i = 0; i < 40; ++i) {
    const Plane plane = random_plane(rng);
    const std::vector<Index> a = q.crossed_faces(plane), b = q.crossed_faces_brute_force(plane);
    ASSERT_EQ(a, b);
    nonempty += !a.empty();
    const Vec3d n = normalized(plane.normal);
    for (Index f : a) {
      double lo = 1e300, hi = -1e300;
      for (Index v : scene.mesh.faces[f]) {
        if (v == kInvalid) continue;
        const double d = dot(n, scene.mesh.positions[v] - plane.point);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
      EXPECT_LT(lo, 1e-12);
      EXPECT_GE(hi, -1e-12);
    }
  }
  EXPECT_GT(nonempty, 15);
  // A plane that misses crosses nothing.
  EXPECT_TRUE(q.crossed_faces({{0, 0, 0.5}, {0, 0, 1}}).empty());
}

TEST(HullQuery, PlanesThatMissTheHullGiveNothing) {
  const Scene scene = wigley_scene();
  const HullQuery q = scene.query();
  EXPECT_TRUE(q.section({{0, 0, 0.5}, {0, 0, 1}}).polylines.empty());
  EXPECT_TRUE(q.section({{kL, 0, 0}, {1, 0, 0}}).polylines.empty());
  EXPECT_TRUE(q.section({{0, -0.1, 0}, {0, 1, 0}}).polylines.empty());
  EXPECT_THROW(q.section({{0, 0, 0}, {0, 0, 0}}), GeometryError);
}

TEST(HullQuery, ThreadCountDoesNotChangeResults) {
  const Scene scene = split_wigley_scene(false);
  const HullQuery q = scene.query();
  const std::vector<Ray> rays = random_rays(q.bbox(), 2000, 5);
  std::vector<Vec3d> points;
  for (const Ray& r : rays) points.push_back(r.origin);
  std::vector<Plane> planes;
  for (int i = 0; i < 300; ++i) planes.push_back({{-4.9 + 9.8 * i / 299, 0, 0}, {1, 0, 0.1}});

  auto run = [&](int threads) {
    return hm::test::with_threads(threads, [&] {
      std::vector<RayHit> hits(rays.size());
      std::vector<ClosestPoint> near(points.size());
      q.first_hits(rays, hits);
      q.closest_points(points, near);
      return std::make_tuple(hits, near, q.sections(planes));
    });
  };
  const auto [h1, c1, s1] = run(1);
  const auto [h2, c2, s2] = run(8);
  for (std::size_t i = 0; i < h1.size(); ++i) {
    ASSERT_EQ(h1[i].point, h2[i].point);
    ASSERT_EQ(c1[i].point, c2[i].point);
  }
  ASSERT_EQ(s1.size(), s2.size());
  for (std::size_t i = 0; i < s1.size(); ++i) {
    ASSERT_EQ(s1[i].polylines.size(), 1u);
    ASSERT_EQ(s1[i].polylines.size(), s2[i].polylines.size());
    const auto& a = s1[i].polylines[0].points;
    const auto& b = s2[i].polylines[0].points;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t j = 0; j < a.size(); ++j) ASSERT_EQ(a[j].point, b[j].point);
    // Batched equals one by one.
    const Section one = q.section(planes[i]);
    ASSERT_EQ(one.polylines[0].points.size(), a.size());
    EXPECT_EQ(one.polylines[0].points.back().point, a.back().point);
  }
}

TEST(HullQuery, InconsistentMeshIsAGeometryError) {
  Scene s = wigley_scene();
  s.mesh.face_patch[3] = 5;
  EXPECT_THROW(s.query(), GeometryError);
  Scene t = wigley_scene();
  t.mesh.faces[0][1] = 1u << 30;
  EXPECT_THROW(t.query(), GeometryError);
  Scene u = wigley_scene();
  u.mesh.vertex_uv.pop_back();
  EXPECT_THROW(u.query(), GeometryError);
}

TEST(HullQuery, MeshWithoutUvIsProjected) {
  Scene s = split_wigley_scene(true);
  s.mesh.vertex_uv.clear();
  s.mesh.vertex_patch.clear();
  const HullQuery q = s.query();
  const Plane plane{{1.1, 0, 0}, {1, 0, 0}};
  const Section sec = q.section(plane);
  ASSERT_EQ(sec.polylines.size(), 1u);
  expect_on_wigley(sec.polylines[0], plane);
}

}  // namespace
}  // namespace hm
