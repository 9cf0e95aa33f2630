#include "mesh/adjacency.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "mesh_builders.h"

namespace hm {
namespace {

TEST(Adjacency, ClosedCubeIsWatertightAndConsistent) {
  const SurfaceMesh m = test::box_mesh({0, 0, 0}, {1, 1, 1}, 1);
  const EdgeAdjacency a = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_EQ(a.edges.size(), 12u);
  EXPECT_TRUE(a.watertight());
  EXPECT_TRUE(a.inconsistent_edges.empty());
  EXPECT_TRUE(a.boundary_loops.empty());
  for (std::size_t f = 0; f < m.face_count(); ++f)
    for (int c = 0; c < 4; ++c) {
      const Index g = a.opposite_face[4 * f + c];
      ASSERT_NE(g, kInvalid);
      // The opposite corner points back.
      EXPECT_EQ(a.opposite_face[4 * g + a.opposite_corner[4 * f + c]], f);
    }
}

TEST(Adjacency, OpenCubeHasOneClosedBoundaryLoopOfFourEdges) {
  SurfaceMesh m = test::box_mesh({0, 0, 0}, {1, 1, 1}, 1);
  m.faces.erase(m.faces.begin() + 4);  // the side z = 0 (axis 2, side 0)
  const EdgeAdjacency a = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_EQ(a.boundary_edges.size(), 4u);
  ASSERT_EQ(a.boundary_loops.size(), 1u);
  EXPECT_TRUE(a.boundary_loops[0].closed);
  EXPECT_EQ(a.boundary_loops[0].vertices.size(), 4u);
  for (Index v : a.boundary_loops[0].vertices) EXPECT_EQ(m.positions[v].z, 0.0);
}

TEST(Adjacency, ThreeFacesOnOneEdgeAreNonManifold) {
  const std::vector<Face> faces = {{0, 1, 2, kInvalid}, {1, 0, 3, kInvalid}, {0, 1, 4, kInvalid}};
  const EdgeAdjacency a = build_edge_adjacency(faces, 5);
  ASSERT_EQ(a.nonmanifold_edges.size(), 1u);
  EXPECT_EQ(a.edges[a.nonmanifold_edges[0]].v0, 0u);
  EXPECT_EQ(a.edges[a.nonmanifold_edges[0]].uses, 3u);
  EXPECT_FALSE(a.watertight());
}

TEST(Adjacency, OpenStripChainsIntoOneClosedLoop) {
  const SurfaceMesh m = test::grid_mesh(3, 2, [](double s, double t) { return Vec3d{s, t, 0}; });
  const EdgeAdjacency a = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_EQ(a.boundary_edges.size(), 10u);
  ASSERT_EQ(a.boundary_loops.size(), 1u);
  EXPECT_TRUE(a.boundary_loops[0].closed);
  EXPECT_EQ(a.boundary_loops[0].edges.size(), 10u);
}

TEST(Adjacency, MissingVertexThrowsGeometryError) {
  const std::vector<Face> faces = {{0, 1, 7, kInvalid}};
  EXPECT_THROW(build_edge_adjacency(faces, 3), GeometryError);
}

}  // namespace
}  // namespace hm
