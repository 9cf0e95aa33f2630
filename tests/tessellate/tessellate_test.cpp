// Properties of the whole tessellation: exact grids, chord error measured on the NURBS, manifold
// patch disks, collapsed edges, trims with holes, thread-count independence.
#include "tessellate/tessellate.h"

#include <gtest/gtest.h>

#include <cstring>
#include <numbers>
#include <vector>

#include "core/error.h"
#include "support/test_support.h"
#include "tess_fixtures.h"

namespace hm {
namespace {

using test::patch_topology;

Tessellation run(const std::vector<Patch>& patches, TessellateOptions o) {
  return tessellate(patches, o, silent_progress());
}

TEST(Tessellate, FlatPatchGivesExactlyTheExpectedGrid) {
  const std::vector<Patch> patches{test::flat_square(1.0)};
  TessellateOptions o;
  o.edge_length = 0.25;
  o.chord_tolerance = 1e-6;
  const Tessellation t = run(patches, o);
  ASSERT_EQ(t.mesh.vertex_count(), 25u);
  ASSERT_EQ(t.mesh.face_count(), 32u);
  for (std::size_t j = 0; j < 5; ++j) {
    for (std::size_t i = 0; i < 5; ++i) {
      const std::size_t k = i + 5 * j;
      EXPECT_DOUBLE_EQ(t.mesh.vertex_uv[k].x, 0.25 * i);
      EXPECT_DOUBLE_EQ(t.mesh.vertex_uv[k].y, 0.25 * j);
      EXPECT_DOUBLE_EQ(t.mesh.positions[k].x, 0.25 * i);
      EXPECT_DOUBLE_EQ(t.mesh.positions[k].y, 0.25 * j);
      EXPECT_EQ(t.mesh.positions[k].z, 0.0);
    }
  }
  // Cell (i, j) is split along its (i, j)-(i+1, j+1) diagonal (both diagonals are equal here).
  for (std::size_t c = 0; c < 16; ++c) {
    const Index a = Index(c % 4 + 5 * (c / 4));
    const Face f0 = t.mesh.faces[2 * c], f1 = t.mesh.faces[2 * c + 1];
    EXPECT_EQ(f0, (Face{a, a + 1, a + 6, kInvalid}));
    EXPECT_EQ(f1, (Face{a, a + 6, a + 5, kInvalid}));
    EXPECT_DOUBLE_EQ(test::triangle_area(t.mesh, 2 * c), 0.03125);
  }
  EXPECT_LE(t.summary.max_chord_error, 1e-15);  // flat: round-off only
}

TEST(Tessellate, QuarterCylinderChordErrorWithinToleranceAndDecreasing) {
  const std::vector<Patch> patches{test::quarter_cylinder(1.0, 2.0)};
  TessellateOptions o;
  o.edge_length = 0.5;
  o.max_refine_levels = 8;
  double previous = 0;
  std::size_t previous_triangles = 0;
  for (double tol : {1e-2, 1e-3, 1e-4}) {
    o.chord_tolerance = tol;
    const Tessellation t = run(patches, o);
    EXPECT_LE(t.summary.max_chord_error, tol) << "tolerance " << tol;
    EXPECT_GT(t.summary.max_chord_error, 0.0);
    // The measured error is the true one: recompute it from the exact circle for the centroids.
    for (std::size_t f = 0; f < t.mesh.face_count(); ++f) {
      const Vec3d c = face_centroid(t.mesh.positions, t.mesh.faces[f]);
      const double sag = 1.0 - std::hypot(c.x, c.y);  // centroid depth below the cylinder
      ASSERT_LE(sag, tol * (1 + 1e-9) + 1e-12);
    }
    if (previous_triangles > 0) {
      EXPECT_LT(t.summary.max_chord_error, previous);
      EXPECT_GT(t.summary.triangles, previous_triangles);
    }
    previous = t.summary.max_chord_error;
    previous_triangles = t.summary.triangles;
  }
}

TEST(Tessellate, NoZeroAreaTriangles) {
  const std::vector<Patch> patches{test::quarter_cylinder(1.0, 2.0), test::apex_patch(),
                                   test::closed_cylinder(0.5, 1.0)};
  TessellateOptions o;
  o.edge_length = 0.2;
  o.chord_tolerance = 1e-4;
  const Tessellation t = run(patches, o);
  ASSERT_GT(t.mesh.face_count(), 0u);
  for (std::size_t f = 0; f < t.mesh.face_count(); ++f)
    ASSERT_GT(test::triangle_area(t.mesh, f), 1e-9 * o.edge_length * o.edge_length) << f;
}

TEST(Tessellate, UntrimmedPatchIsAnEdgeManifoldDisk) {
  const std::vector<Patch> patches{test::flat_square(1.0), test::quarter_cylinder(1.0, 2.0),
                                   test::apex_patch()};
  TessellateOptions o;
  o.edge_length = 0.3;
  o.chord_tolerance = 1e-4;
  const Tessellation t = run(patches, o);
  for (PatchId p = 0; p < patches.size(); ++p) {
    const test::Topology top = patch_topology(t.mesh, p);
    EXPECT_TRUE(top.manifold) << "patch " << p;
    EXPECT_TRUE(top.oriented) << "patch " << p;
    EXPECT_EQ(top.boundary_loops, 1) << "patch " << p;
    EXPECT_EQ(top.euler, 1) << "patch " << p;
  }
}

TEST(Tessellate, ClosedCylinderSeamIsJoined) {
  const std::vector<Patch> patches{test::closed_cylinder(0.5, 1.0)};
  TessellateOptions o;
  o.edge_length = 0.25;
  o.chord_tolerance = 1e-4;
  const Tessellation t = run(patches, o);
  const test::Topology top = patch_topology(t.mesh, 0);
  EXPECT_TRUE(top.manifold);
  EXPECT_TRUE(top.oriented);
  EXPECT_EQ(top.boundary_loops, 2);  // the two rims: the seam is interior
  EXPECT_EQ(top.euler, 0);
  EXPECT_LE(t.summary.max_chord_error, o.chord_tolerance);
}

TEST(Tessellate, CollapsedEdgeHasOneApexVertexAndNoSlivers) {
  const std::vector<Patch> patches{test::apex_patch()};
  TessellateOptions o;
  o.edge_length = 0.15;
  o.chord_tolerance = 1e-4;
  o.max_refine_levels = 8;
  const Tessellation t = run(patches, o);
  const Vec3d apex{0, 0.2, 1.0};
  int at_apex = 0;
  for (const Vec3d& p : t.mesh.positions) at_apex += norm(p - apex) < 1e-9;
  EXPECT_EQ(at_apex, 1);
  // No two vertices coincide anywhere.
  std::vector<Vec3d> pts = t.mesh.positions;
  std::sort(pts.begin(), pts.end(), [](const Vec3d& a, const Vec3d& b) { return a.x < b.x; });
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t k = i + 1; k < pts.size() && pts[k].x - pts[i].x < 1e-9; ++k)
      ASSERT_GT(norm(pts[k] - pts[i]), 1e-9);
  // Grid cells that touch the collapsed edge would give zero-area twins and needles; joined into
  // one apex they give a fan. Cells near a cone point are anisotropic in 3D by nature (their width
  // shrinks with the distance to the apex), so the bound is on near-degenerate triangles.
  double worst = 180;
  for (std::size_t f = 0; f < t.mesh.face_count(); ++f)
    worst = std::min(worst, test::min_angle_deg(t.mesh, f));
  EXPECT_GT(worst, 0.5);
  EXPECT_LE(t.summary.max_chord_error, o.chord_tolerance);
}

TEST(Tessellate, SquareWithCircularHole) {
  const double side = 2.0, r_uv = 0.25, r = r_uv * side;
  Patch p = test::flat_square(side);
  p.loops.push_back(test::circle_loop({0.5, 0.5}, r_uv, false));  // the outer loop is the domain
  p.wrapping = Wrapping::kTrimmed;
  const std::vector<Patch> patches{p};
  TessellateOptions o;
  o.edge_length = 0.1;
  o.chord_tolerance = 1e-4;
  const Tessellation t = run(patches, o);
  ASSERT_GT(t.mesh.face_count(), 0u);
  const Vec3d c{side / 2, side / 2, 0};
  int on_circle = 0;
  for (const Vec3d& q : t.mesh.positions) {
    const double d = norm(q - c);
    EXPECT_GE(d, r - o.chord_tolerance) << "a vertex inside the hole";
    if (d < r + 0.25 * o.edge_length) {
      EXPECT_NEAR(d, r, o.chord_tolerance);
      ++on_circle;
    }
  }
  EXPECT_GE(on_circle, 16);
  double area = 0;
  for (std::size_t f = 0; f < t.mesh.face_count(); ++f) area += test::triangle_area(t.mesh, f);
  const double exact = side * side - std::numbers::pi * r * r;
  EXPECT_NEAR(area, exact, 2 * std::numbers::pi * r * o.chord_tolerance);
  const test::Topology top = patch_topology(t.mesh, 0);
  EXPECT_TRUE(top.manifold);
  EXPECT_TRUE(top.oriented);
  EXPECT_EQ(top.boundary_loops, 2);
  EXPECT_EQ(top.euler, 0);
}

TEST(Tessellate, TrimmedOuterLoopAndHole) {
  Patch p = test::quarter_cylinder(1.0, 2.0);
  p.loops.push_back(test::square_loop(0.1, 0.9));
  p.loops.push_back(test::circle_loop({0.5, 0.5}, 0.2, false));
  p.wrapping = Wrapping::kTrimmed;
  const std::vector<Patch> patches{p};
  TessellateOptions o;
  o.edge_length = 0.1;
  o.chord_tolerance = 1e-4;
  const Tessellation t = run(patches, o);
  EXPECT_LE(t.summary.max_chord_error, o.chord_tolerance);
  for (const Vec2d& w : t.mesh.vertex_uv) {
    EXPECT_GE(w.x, 0.1 - 1e-12);
    EXPECT_LE(w.x, 0.9 + 1e-12);
    EXPECT_GE(std::hypot(w.x - 0.5, w.y - 0.5), 0.2 - 1e-3);
  }
  const test::Topology top = patch_topology(t.mesh, 0);
  EXPECT_TRUE(top.manifold);
  EXPECT_EQ(top.boundary_loops, 2);
  EXPECT_EQ(top.euler, 0);
}

TEST(Tessellate, EveryVertexUvEvaluatesToItsPosition) {
  Patch holed = test::flat_square(1.0);
  holed.loops.push_back(test::circle_loop({0.4, 0.6}, 0.2, false));
  const std::vector<Patch> patches{test::quarter_cylinder(1.0, 2.0), test::apex_patch(),
                                   test::closed_cylinder(0.5, 1.0), holed};
  TessellateOptions o;
  o.edge_length = 0.2;
  o.chord_tolerance = 1e-4;
  const Tessellation t = run(patches, o);
  ASSERT_EQ(t.mesh.vertex_patch.size(), t.mesh.vertex_count());
  ASSERT_EQ(t.mesh.vertex_uv.size(), t.mesh.vertex_count());
  for (std::size_t v = 0; v < t.mesh.vertex_count(); ++v) {
    const NurbsSurface& s = patches[t.mesh.vertex_patch[v]].surface;
    const Vec2d w = t.mesh.vertex_uv[v];
    ASSERT_LE(norm(evaluate(s, w.x, w.y) - t.mesh.positions[v]), 1e-12) << v;
  }
  for (std::size_t f = 0; f < t.mesh.face_count(); ++f)
    for (int i = 0; i < 3; ++i)
      ASSERT_EQ(t.mesh.vertex_patch[t.mesh.faces[f][i]], t.mesh.face_patch[f]);
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

TEST(Tessellate, OneTwoAndEightThreadsGiveIdenticalArrays) {
  Patch holed = test::flat_square(1.0);
  holed.loops.push_back(test::circle_loop({0.4, 0.6}, 0.2, false));
  std::vector<Patch> patches;
  for (int k = 0; k < 3; ++k) {
    patches.push_back(test::quarter_cylinder(1.0 + 0.1 * k, 2.0));
    patches.push_back(test::apex_patch());
    patches.push_back(holed);
  }
  TessellateOptions o;
  o.edge_length = 0.05;  // large patches too, so that their inner loops run in parallel
  o.chord_tolerance = 1e-4;
  const Tessellation one = hm::test::with_threads(1, [&] { return run(patches, o); });
  ASSERT_GT(one.mesh.face_count(), 10000u);
  for (int threads : {2, 8}) {
    SCOPED_TRACE(threads);
    const Tessellation two = hm::test::with_threads(threads, [&] { return run(patches, o); });
    EXPECT_TRUE(same_bytes(one.mesh.positions, two.mesh.positions));
    EXPECT_TRUE(same_bytes(one.mesh.vertex_uv, two.mesh.vertex_uv));
    EXPECT_TRUE(same_bytes(one.mesh.vertex_patch, two.mesh.vertex_patch));
    EXPECT_TRUE(same_bytes(one.mesh.faces, two.mesh.faces));
    EXPECT_TRUE(same_bytes(one.mesh.face_patch, two.mesh.face_patch));
    EXPECT_TRUE(same_bytes(one.chord_error, two.chord_error));
  }
}

// Callers that read no chord error (the structured mesher, the merge) skip its measurement:
// the mesh is the same to the byte, the errors and their maximum are left empty and 0.
TEST(Tessellate, SkippingTheChordMeasurementLeavesTheMeshAlone) {
  Patch holed = test::flat_square(1.0);
  holed.loops.push_back(test::circle_loop({0.4, 0.6}, 0.2, false));
  const std::vector<Patch> patches{test::quarter_cylinder(1.0, 2.0), test::apex_patch(), holed};
  TessellateOptions o;
  o.edge_length = 0.1;
  o.chord_tolerance = 1e-4;
  const Tessellation measured = run(patches, o);
  o.measure_chord = false;
  const Tessellation skipped = run(patches, o);
  EXPECT_TRUE(same_bytes(measured.mesh.positions, skipped.mesh.positions));
  EXPECT_TRUE(same_bytes(measured.mesh.faces, skipped.mesh.faces));
  EXPECT_TRUE(same_bytes(measured.mesh.vertex_uv, skipped.mesh.vertex_uv));
  EXPECT_EQ(measured.chord_error.size(), measured.mesh.face_count());
  EXPECT_GT(measured.summary.max_chord_error, 0.0);
  EXPECT_TRUE(skipped.chord_error.empty());
  EXPECT_EQ(skipped.summary.max_chord_error, 0.0);
}

TEST(Tessellate, DefaultsFollowTheHullSize) {
  const std::vector<Patch> patches{test::quarter_cylinder(10.0, 40.0)};
  const TessellateOptions o = resolve_options(patches, {});
  EXPECT_DOUBLE_EQ(o.edge_length, 0.4);
  EXPECT_DOUBLE_EQ(o.chord_tolerance, 4e-3);
  EXPECT_DOUBLE_EQ(o.max_area, 0.16);
  EXPECT_THROW(resolve_options(std::vector<Patch>{}, {}), UsageError);
}

TEST(Tessellate, TriangleLimitIsChecked) {
  const std::vector<Patch> patches{test::flat_square(1.0)};
  TessellateOptions o;
  o.edge_length = 1e-4;  // 10^8 cells
  EXPECT_THROW(run(patches, o), LimitError);
}

}  // namespace
}  // namespace hm
