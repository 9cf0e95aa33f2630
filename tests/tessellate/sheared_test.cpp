// Sheared patches: four-sided plates with two sides in line, whose parameter lines run side by
// side in 3D. The structured grid crowds there (and crosses itself where the parametrisation
// folds), so they are meshed from their sides and a thinned grid on a plane chart instead.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nurbs/generate_hull.h"
#include "nurbs/nurbs_surface.h"
#include "nurbs/patch.h"
#include "support/test_support.h"
#include "tess_fixtures.h"
#include "tessellate/flip_edges.h"
#include "tessellate/tessellate.h"

namespace hm {
namespace {

// A bilinear plate in z = 0 with corners (0, 0), (40, 0), (40, 1.6) and (30, 1.2 + lift): the
// sides u = 0 and v = 1 meet at (30, 1.2) in one straight line for lift = 0, so su x sv vanishes
// at that corner; a negative lift folds the plate over a hair there (as ship_449's keel plate,
// DE 8385, does), a positive one leaves a shallow corner.
Patch keel_plate(double lift) {
  Patch p;
  NurbsSurface& s = p.surface;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.points = {{0, 0, 0}, {40, 0, 0}, {30, 1.2 + lift, 0}, {40, 1.6, 0}};
  s.weights = {1, 1, 1, 1};
  p.wrapping = Wrapping::kGenerated;
  return p;
}

struct PlateMesh {
  Tessellation t;
  double area = 0;          // of the triangles, m^2
  std::size_t against = 0;  // triangles whose normal points down (against su x sv)
};

PlateMesh mesh_plate(double lift, double h) {
  PlateMesh r;
  TessellateOptions o;
  o.edge_length = h;
  o.chord_tolerance = 1e-3;
  r.t = tessellate(std::vector<Patch>{keel_plate(lift)}, o, silent_progress());
  for (const Face& f : r.t.mesh.faces) {
    const Vec3d& a = r.t.mesh.positions[f[0]];
    const Vec3d n = cross(r.t.mesh.positions[f[1]] - a, r.t.mesh.positions[f[2]] - a);
    r.area += 0.5 * norm(n);
    r.against += n.z <= 0;
  }
  return r;
}

TEST(ShearedPatch, FoldedKeelPlateIsMeshedOnceWithTrianglesOfTheEdgeLength) {
  const double h = 0.3;
  const Patch plate = keel_plate(-0.01);
  const double area = patch_area(plate);
  const PlateMesh m = mesh_plate(-0.01, h);
  // The grid would have 133 x 100 cells, two triangles each; the plate needs about 2 A / h^2.
  EXPECT_LT(double(m.t.mesh.face_count()), 3 * 2 * area / (h * h));
  EXPECT_EQ(m.against, 0u);  // the fold is not meshed: no triangle lies upside down on another
  EXPECT_NEAR(m.area, area, 1e-3 * area);
  const test::Topology top = test::patch_topology(m.t.mesh, 0);
  EXPECT_TRUE(top.manifold);
  EXPECT_TRUE(top.oriented);
  EXPECT_EQ(top.boundary_loops, 1);
  EXPECT_EQ(top.euler, 1);
  EXPECT_LE(m.t.summary.max_chord_error, m.t.summary.chord_tolerance);
  // Every vertex is on the plate, at its own (u, v).
  for (std::size_t v = 0; v < m.t.mesh.vertex_count(); ++v) {
    const Vec2d w = m.t.mesh.vertex_uv[v];
    ASSERT_LT(norm(evaluate(plate.surface, w.x, w.y) - m.t.mesh.positions[v]), 1e-9);
  }
}

TEST(ShearedPatch, AStraightCornerPlateGetsRoundTriangles) {
  const PlateMesh m = mesh_plate(0.0, 0.3);
  std::size_t thin = 0;
  for (std::size_t f = 0; f < m.t.mesh.face_count(); ++f)
    thin += test::min_angle_deg(m.t.mesh, f) < 15;
  // Along the sides the triangles fan from border samples; inside they are about equilateral.
  EXPECT_LT(double(thin), 0.05 * double(m.t.mesh.face_count()));
  EXPECT_EQ(m.against, 0u);
}

// The generated full round-bilge hull of 100 patches with 0.1 m gaps has a transom patch at its
// foot whose u runs across the transom and back: sheared, triangulated on a plane chart. Its
// refinement split edges at their (u, v) middles and tested the new points in (u, v), where the
// chart's triangles say nothing: at 40,000 triangles an edge 0.28 m long was split at a point
// 0.75 m off it, and a child triangle lay turned over its neighbours (the merge then had 14 and
// 20 pairs of faces through each other, with gaps, and with every defect). Every triangle of
// the tessellation now faces as its patch does.
TEST(ShearedPatch, RefinementTurnsNoTriangleOver) {
  HullSpec spec;
  spec.kind = HullKind::kRoundBilge;
  spec.patches = 100;
  spec.full_hull = true;
  spec.defects.gap = 0.1;
  const std::vector<Patch> patches = generate_hull(spec).patches;
  TessellateOptions o;
  o.edge_length = edge_length_for_triangles(patches, 40000);
  const Tessellation t = tessellate(patches, o, silent_progress());
  const SurfaceMesh& m = t.mesh;
  ASSERT_EQ(m.vertex_uv.size(), m.vertex_count());
  std::size_t turned = 0;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const Face& face = m.faces[f];
    const Vec3d& a = m.positions[face[0]];
    const Vec3d n = cross(m.positions[face[1]] - a, m.positions[face[2]] - a);
    const Vec2d uv =
        (1.0 / 3.0) * (m.vertex_uv[face[0]] + m.vertex_uv[face[1]] + m.vertex_uv[face[2]]);
    const NurbsSurface& s = patches[m.face_patch[f]].surface;
    turned += dot(n, normal(s, uv.x, uv.y)) < 0;
  }
  EXPECT_EQ(turned, 0u);
}

TEST(ShearedPatch, SameBytesWithOneAndTwoThreads) {
  const auto run = [](int threads) {
    return test::with_threads(threads, [] { return mesh_plate(-0.01, 0.3).t.mesh; });
  };
  const SurfaceMesh a = run(1), b = run(2);
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.faces.size(), b.faces.size());
  for (std::size_t v = 0; v < a.positions.size(); ++v) ASSERT_EQ(a.positions[v], b.positions[v]);
  for (std::size_t f = 0; f < a.faces.size(); ++f) ASSERT_EQ(a.faces[f], b.faces[f]);
}

// Two triangles (0, 1, 2) and (0, 2, 3) sharing the edge (0, 2), with 3D positions and a chart.
PatchMesh quad(const std::array<Vec3d, 4>& xyz, const std::array<Vec2d, 4>& uv) {
  PatchMesh m;
  for (int i = 0; i < 4; ++i) m.add_vertex(xyz[i], uv[i], 0);
  m.add_tri({0, 1, 2}, {uv[0], uv[1], uv[2]});
  m.add_tri({0, 2, 3}, {uv[0], uv[2], uv[3]});
  return m;
}

TEST(FlipEdges, TheShortDiagonalOfARhombusReplacesTheLongOne) {
  // A rhombus in 3D with its long diagonal (0, 2) as the edge: corners of 5.7 degrees; cut along
  // (1, 3) its smallest corner is 11.4 degrees. The chart is the unit square.
  PatchMesh m = quad({Vec3d{0, 0, 0}, {5, -0.5, 0}, {10, 0, 0}, {5, 0.5, 0}},
                     {Vec2d{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_EQ(flip_edges_3d(m, m.uv), 1u);
  int shared = 0;  // both triangles now hold 1 and 3
  for (const Tri& t : m.tris)
    for (Index v : t) shared += (v == 1 || v == 3);
  EXPECT_EQ(shared, 4);
  for (const Tri& t : m.tris) {
    const Vec3d n = cross(m.xyz[t[1]] - m.xyz[t[0]], m.xyz[t[2]] - m.xyz[t[0]]);
    EXPECT_GT(n.z, 0);  // still facing the same way
  }
  EXPECT_EQ(flip_edges_3d(m, m.uv), 0u);  // and it stays
}

TEST(FlipEdges, NeverFlipsIntoAQuadThatIsNotConvexInTheChart) {
  // The same rhombus in 3D, but the chart is a dart with its reflex corner at 0: the diagonal
  // (1, 3) runs outside the quad there, and triangle (3, 0, 1) would be clockwise.
  PatchMesh m = quad({Vec3d{0, 0, 0}, {5, -0.5, 0}, {10, 0, 0}, {5, 0.5, 0}},
                     {Vec2d{0.7, 0.7}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_EQ(flip_edges_3d(m, m.uv), 0u);
}

TEST(FlipEdges, BoundaryEdgesNeverFlip) {
  PatchMesh m;
  m.add_vertex({0, 0, 0}, {0, 0}, 0);
  m.add_vertex({10, 0, 0}, {1, 0}, 0);
  m.add_vertex({5, 0.1, 0}, {0.5, 1}, 0);
  m.add_tri({0, 1, 2}, {m.uv[0], m.uv[1], m.uv[2]});
  EXPECT_EQ(flip_edges_3d(m, m.uv), 0u);
}

}  // namespace
}  // namespace hm
