// Two sides meshed apart, joined on the centre plane y = 0: nodes that meet are welded, others
// go into the other side's edges, and the seam is closed with no free edge and no panel turned.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured.h"

namespace hm {
namespace {

// A strip of quads on one side of the plane: nodes at x_i on y = 0 and at y = +-1 (port +1),
// in z = 0, every normal up (+z). One block, named.
StructuredMesh side(const std::vector<double>& xs, bool port) {
  StructuredMesh s;
  SurfaceMesh& m = s.mesh;
  const double y = port ? 1 : -1;
  for (double x : xs) {
    m.positions.push_back({x, 0, 0});
    m.positions.push_back({x, y, 0});
  }
  for (Index i = 0; i + 1 < xs.size(); ++i) {
    const Index a = 2 * i, b = 2 * i + 2;  // on the plane
    Face f = port ? Face{a, b, b + 1, a + 1} : Face{a, a + 1, b + 1, b};
    m.faces.push_back(f);
    m.face_patch.push_back(port ? 0 : 1);
    m.face_block.push_back(0);
  }
  m.vertex_patch.assign(m.positions.size(), port ? 0 : 1);
  m.vertex_uv.assign(m.positions.size(), Vec2d{0, 0});
  BlockReport b;
  b.lower = "lower end";
  b.quads = m.faces.size();
  s.report.blocks.push_back(b);
  s.report.quads = m.faces.size();
  return s;
}

SeamPlanes seam() {
  SeamPlanes p;
  p.centre_tol = 1e-9;
  return p;
}

// Boundary edges with both ends on y = 0 (the seam left open), and faces whose normal is not +z.
std::size_t open_seam_edges(const SurfaceMesh& m) {
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  std::size_t open = 0;
  for (Index e : adj.boundary_edges) {
    const MeshEdge& me = adj.edges[e];
    if (m.positions[me.v0].y == 0 && m.positions[me.v1].y == 0) ++open;
  }
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  return open;
}

std::size_t faces_turned(const SurfaceMesh& m) {
  std::size_t turned = 0;
  for (const Face& f : m.faces) turned += face_normal(m.positions, f).z > 0 ? 0 : 1;
  return turned;
}

double total_area(const SurfaceMesh& m) {
  double a = 0;
  for (const Face& f : m.faces) a += face_area(m.positions, f);
  return a;
}

// Port: one triangle with its side (0, 0)-(2, 0) on the seam, 1.7 high; one block.
StructuredMesh one_triangle_port() {
  StructuredMesh port;
  SurfaceMesh& m = port.mesh;
  m.positions = {{0, 0, 0}, {2, 0, 0}, {1, 1.7, 0}};
  m.faces = {{0, 1, 2, kInvalid}};
  m.face_patch = {0};
  m.face_block = {0};
  m.vertex_patch.assign(3, 0);
  m.vertex_uv.assign(3, Vec2d{0, 0});
  BlockReport b;
  b.triangles = 1;
  port.report.blocks.push_back(b);
  port.report.triangles = 1;
  return port;
}

// Every face has an area over 1e-3 of its longest side squared.
void expect_no_needle(const SurfaceMesh& m) {
  for (const Face& f : m.faces) {
    double longest = 0;
    for (int k = 0; k < corner_count(f); ++k)
      longest = std::max(
          longest, squared_norm(m.positions[f[(k + 1) % corner_count(f)]] - m.positions[f[k]]));
    EXPECT_GT(face_area(m.positions, f), 1e-3 * longest);
  }
}

TEST(JoinSides, NodesThatMeetAreWelded) {
  SideJoin c;
  const StructuredMesh j =
      join_sides(side({0, 1, 2, 3}, true), side({0, 1, 2, 3}, false), seam(), &c);
  EXPECT_EQ(c.seam_nodes, 8u);
  EXPECT_EQ(c.welded, 4u);
  EXPECT_EQ(c.inserted, 0u);
  EXPECT_EQ(j.mesh.vertex_count(), 12u);
  EXPECT_EQ(j.mesh.face_count(), 6u);
  EXPECT_EQ(open_seam_edges(j.mesh), 0u);
  EXPECT_EQ(faces_turned(j.mesh), 0u);
  // Starboard's block follows port's, named by its side.
  ASSERT_EQ(j.report.blocks.size(), 2u);
  EXPECT_EQ(j.report.blocks[1].id, 1u);
  EXPECT_EQ(j.report.blocks[0].lower, "port: lower end");
  EXPECT_EQ(j.report.blocks[1].lower, "starboard: lower end");
  EXPECT_EQ(j.mesh.face_block.back(), 1u);
}

TEST(JoinSides, ANodeNearlyOnAnotherIsWeldedAndThePortNodeStays) {
  SideJoin c;
  const StructuredMesh j =
      join_sides(side({0, 1, 2, 3}, true), side({0, 1.1, 2, 3}, false), seam(), &c);
  EXPECT_EQ(c.welded, 4u);
  EXPECT_EQ(c.inserted, 0u);
  EXPECT_EQ(open_seam_edges(j.mesh), 0u);
  const auto& p = j.mesh.positions;
  EXPECT_TRUE(std::any_of(p.begin(), p.end(), [](const Vec3d& v) { return v.x == 1 && v.y == 0; }));
  EXPECT_FALSE(
      std::any_of(p.begin(), p.end(), [](const Vec3d& v) { return v.x == 1.1 && v.y == 0; }));
}

TEST(JoinSides, NodesBetweenTheOthersGoIntoTheirEdgesAndThePanelsSplit) {
  SideJoin c;
  // Port has two panels along the seam, starboard three: the middle nodes fall inside edges.
  const StructuredMesh j =
      join_sides(side({0, 1.5, 3}, true), side({0, 1, 2, 3}, false), seam(), &c);
  EXPECT_EQ(c.welded, 2u);    // the ends
  EXPECT_EQ(c.inserted, 3u);  // 1 and 2 into port's edges, 1.5 into starboard's
  EXPECT_EQ(open_seam_edges(j.mesh), 0u);
  EXPECT_EQ(faces_turned(j.mesh), 0u);
  EXPECT_NEAR(total_area(j.mesh), 6.0, 1e-12);  // no panel overlaps another
  // A quad split by one node keeps a quad beside a triangle.
  std::size_t quads = 0;
  for (const Face& f : j.mesh.faces) quads += is_triangle(f) ? 0 : 1;
  EXPECT_EQ(quads, j.report.quads);
  EXPECT_EQ(quads, 5u);
  EXPECT_EQ(j.report.triangles, 3u);
  std::size_t block_faces = 0;
  for (const BlockReport& b : j.report.blocks) block_faces += b.quads + b.triangles;
  EXPECT_EQ(block_faces, j.mesh.face_count());
}

// A node put into a triangle's side lies on a line with that side's ends. Cutting the ear of
// the best shape first (here the whole triangle's far corner) left the node and the side's ends
// as the last triangle, of no area; the ear is now chosen with the triangle it leaves.
TEST(JoinSides, ATriangleSplitAtANodeOnItsSideLeavesNoFlatPiece) {
  const StructuredMesh port = one_triangle_port();
  SideJoin c;
  const StructuredMesh j = join_sides(port, side({0, 1.9, 2}, false), seam(), &c);
  EXPECT_EQ(c.inserted, 1u);
  EXPECT_EQ(open_seam_edges(j.mesh), 0u);
  EXPECT_EQ(faces_turned(j.mesh), 0u);
  EXPECT_NEAR(total_area(j.mesh), 1.7 + 2.0, 1e-12);
  expect_no_needle(j.mesh);
}

// The same with the node a hair off the side (4e-4 m, 2e-4 of its length, in the plane): not
// flat, so the rule above let the whole triangle's far corner go first, and the node and the
// side's ends were left as a needle of 4e-4 m^2 beside a panel of 1.7 m^2. The ear is now
// judged by the smaller angle of both triangles it makes.
TEST(JoinSides, ATriangleSplitAtANodeJustOffItsSideLeavesNoNeedle) {
  const StructuredMesh port = one_triangle_port();
  StructuredMesh starboard = side({0, 1.9, 2}, false);
  starboard.mesh.positions[2].z = 4e-4;  // the node at x = 1.9 on the seam
  SideJoin c;
  const StructuredMesh j = join_sides(port, starboard, seam(), &c);
  ASSERT_EQ(c.inserted, 1u);
  EXPECT_EQ(open_seam_edges(j.mesh), 0u);
  expect_no_needle(j.mesh);
}

TEST(JoinSides, ASeamEndBeyondTheOtherSideStaysOpen) {
  SideJoin c;
  // Starboard's seam runs one panel further aft: that edge has nothing to meet.
  const StructuredMesh j =
      join_sides(side({0, 1, 2}, true), side({-1, 0, 1, 2}, false), seam(), &c);
  EXPECT_EQ(c.welded, 3u);
  EXPECT_EQ(c.inserted, 0u);
  EXPECT_EQ(open_seam_edges(j.mesh), 1u);
}

TEST(JoinSides, AHoleTheSeamsLeaveInThePlaneIsFilled) {
  // Starboard's seam turns a corner 1 m below port's straight seam (a skeg's trailing edge that
  // one side cuts across): too far for its node to go into port's edge.
  StructuredMesh stbd = side({-1, 0, 1.5, 3, 4}, false);
  stbd.mesh.positions[4].z = -1;
  SideJoin c;
  const StructuredMesh j = join_sides(side({-1, 0, 3, 4}, true), std::move(stbd), seam(), &c);
  EXPECT_EQ(c.welded, 4u);
  EXPECT_EQ(c.inserted, 0u);
  EXPECT_EQ(c.holes_filled, 1u);
  EXPECT_EQ(open_seam_edges(j.mesh), 0u);
  EXPECT_EQ(j.mesh.face_count(), 8u);  // 3 + 4 quads and the triangle in the plane
  EXPECT_EQ(j.report.blocks[0].triangles, 1u);
}

TEST(JoinSides, PanelsBackToBackInThePlaneGo) {
  // Both sides end in the same triangle lying in the plane (a cap panel at a stern's corner).
  StructuredMesh port = side({0, 1, 2}, true), stbd = side({0, 1, 2}, false);
  for (StructuredMesh* s : {&port, &stbd}) {
    SurfaceMesh& m = s->mesh;
    m.positions.push_back({1, 0, -1});
    const Index v = static_cast<Index>(m.positions.size() - 1);
    m.vertex_patch.push_back(0);
    m.vertex_uv.push_back({0, 0});
    // Wound as each side's own faces run the seam edge 0-1 (port 0 -> 1), from the other side.
    m.faces.push_back(s == &port ? Face{2, 0, v, kInvalid} : Face{0, 2, v, kInvalid});
    m.face_patch.push_back(0);
    m.face_block.push_back(0);
    ++s->report.blocks[0].triangles;
  }
  SideJoin c;
  const StructuredMesh j = join_sides(std::move(port), std::move(stbd), seam(), &c);
  EXPECT_EQ(c.back_to_back, 1u);
  EXPECT_EQ(j.mesh.face_count(), 4u);
  EXPECT_EQ(j.report.blocks[0].triangles + j.report.blocks[1].triangles, 0u);
  const EdgeAdjacency adj = build_edge_adjacency(j.mesh.faces, j.mesh.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
}

TEST(JoinSides, EdgesAlongTheWaterlineInThePlaneAreNoSeam) {
  // Each side's border runs along y = 0 on the waterline z = 0 from x = 0 to 1 before its seam
  // goes down (a keel rising through the waterline at a small angle): those edges stay
  // waterline, and the seams meet at their ends on the waterline.
  SeamPlanes planes = seam();
  planes.waterline = 0;
  planes.waterline_tol = 1e-9;
  StructuredMesh port = side({0, 1, 2, 3}, true), stbd = side({0, 1, 2, 3}, false);
  for (StructuredMesh* s : {&port, &stbd}) {
    s->mesh.positions[4].z = -1;
    s->mesh.positions[6].z = -1;
  }
  // Starboard's seam leaves the waterline a little farther forward: its end welds to port's.
  stbd.mesh.positions[2].x = 1.2;
  SideJoin c;
  const StructuredMesh j = join_sides(std::move(port), std::move(stbd), planes, &c);
  EXPECT_EQ(c.seam_nodes, 6u);
  EXPECT_EQ(c.welded, 3u);
  EXPECT_EQ(c.inserted, 0u);
  EXPECT_EQ(open_seam_edges(j.mesh), 2u);  // the two waterline edges
}

}  // namespace
}  // namespace hm
