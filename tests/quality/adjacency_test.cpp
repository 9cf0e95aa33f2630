#include "mesh/adjacency.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

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

// Every edge is found from its two vertices in either order; a face diagonal is no edge.
TEST(Adjacency, FindEdgeNamesEachEdgeByItsVertices) {
  const SurfaceMesh m = test::box_mesh({0, 0, 0}, {1, 1, 1}, 1);
  const EdgeAdjacency a = build_edge_adjacency(m.faces, m.vertex_count());
  for (std::size_t e = 0; e < a.edges.size(); ++e) {
    EXPECT_EQ(find_edge(a, a.edges[e].v0, a.edges[e].v1), e);
    EXPECT_EQ(find_edge(a, a.edges[e].v1, a.edges[e].v0), e);
  }
  const Face& f = m.faces[0];
  EXPECT_EQ(find_edge(a, f[0], f[2]), kInvalid);
  EXPECT_EQ(find_edge(a, f[0], static_cast<Index>(m.vertex_count())), kInvalid);
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

// A triangulated 6 x 5 grid with a hole (one cell left out), a fin on an interior edge (three
// faces there) and every seventh face wound against the rest: boundary loops, non-manifold and
// inconsistent edges all occur.
std::vector<Face> awkward_triangles(std::size_t& vertex_count) {
  constexpr Index kNx = 6, kNy = 5;
  std::vector<Face> faces;
  for (Index j = 0; j + 1 < kNy; ++j) {
    for (Index i = 0; i + 1 < kNx; ++i) {
      if (i == 2 && j == 2) continue;
      const Index a = j * kNx + i, b = a + 1, c = a + kNx + 1, d = a + kNx;
      faces.push_back({a, b, c, kInvalid});
      faces.push_back({a, c, d, kInvalid});
    }
  }
  faces.push_back({kNx + 1, 2 * kNx + 2, kNx * kNy, kInvalid});  // the fin, on a diagonal
  for (std::size_t f = 0; f < faces.size(); f += 7) std::swap(faces[f][1], faces[f][2]);
  vertex_count = kNx * kNy + 1;
  return faces;
}

void expect_same_adjacency(const EdgeAdjacency& a, const EdgeAdjacency& b) {
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t e = 0; e < a.edges.size(); ++e) {
    EXPECT_EQ(a.edges[e].v0, b.edges[e].v0);
    EXPECT_EQ(a.edges[e].v1, b.edges[e].v1);
    EXPECT_EQ(a.edges[e].first_slot, b.edges[e].first_slot) << "edge " << e;
    EXPECT_EQ(a.edges[e].uses, b.edges[e].uses);
    EXPECT_EQ(a.edges[e].same_direction, b.edges[e].same_direction) << "edge " << e;
  }
  EXPECT_EQ(a.slot_edge, b.slot_edge);
  EXPECT_EQ(a.opposite_face, b.opposite_face);
  EXPECT_EQ(a.opposite_corner, b.opposite_corner);
  EXPECT_EQ(a.boundary_edges, b.boundary_edges);
  EXPECT_EQ(a.nonmanifold_edges, b.nonmanifold_edges);
  EXPECT_EQ(a.inconsistent_edges, b.inconsistent_edges);
  ASSERT_EQ(a.boundary_loops.size(), b.boundary_loops.size());
  for (std::size_t l = 0; l < a.boundary_loops.size(); ++l) {
    EXPECT_EQ(a.boundary_loops[l].vertices, b.boundary_loops[l].vertices);
    EXPECT_EQ(a.boundary_loops[l].edges, b.boundary_loops[l].edges);
    EXPECT_EQ(a.boundary_loops[l].closed, b.boundary_loops[l].closed);
  }
}

TEST(Adjacency, ReversingFacesInPlaceEqualsBuildingAgain) {
  std::size_t nv = 0;
  std::vector<Face> faces = awkward_triangles(nv);
  EdgeAdjacency adj = build_edge_adjacency(faces, nv);
  ASSERT_FALSE(adj.nonmanifold_edges.empty());
  ASSERT_FALSE(adj.inconsistent_edges.empty());
  ASSERT_GE(adj.boundary_loops.size(), 2u);
  // Three rounds of pseudo-random subsets, each applied to the result of the last.
  std::uint32_t state = 12345;
  for (int round = 0; round < 3; ++round) {
    std::vector<std::uint8_t> reversed(faces.size(), 0);
    for (std::size_t f = 0; f < faces.size(); ++f) {
      state = state * 1664525u + 1013904223u;
      reversed[f] = (state >> 28) < 6;  // about 3 in 8
      if (reversed[f]) std::swap(faces[f][1], faces[f][2]);
    }
    reverse_in_adjacency(adj, faces, reversed);
    SCOPED_TRACE("round " + std::to_string(round));
    expect_same_adjacency(adj, build_edge_adjacency(faces, nv));
  }
  // Turning every face turns every loop: still the same as a fresh build.
  std::vector<std::uint8_t> all(faces.size(), 1);
  for (Face& f : faces) std::swap(f[1], f[2]);
  reverse_in_adjacency(adj, faces, all);
  expect_same_adjacency(adj, build_edge_adjacency(faces, nv));
}

TEST(Adjacency, BoundarySlotsAreThoseOfTheBoundaryEdges) {
  std::size_t nv = 0;
  const std::vector<Face> faces = awkward_triangles(nv);
  const EdgeAdjacency adj = build_edge_adjacency(faces, nv);
  const std::vector<Index> slots = boundary_slots(faces, nv);
  ASSERT_EQ(slots.size(), adj.boundary_edges.size());
  for (std::size_t i = 0; i < slots.size(); ++i) {
    EXPECT_EQ(slots[i], adj.edges[adj.boundary_edges[i]].first_slot);
  }
}

// A mesh big enough for the build's parallel loops to split (a 300 x 80 grid of quads and
// triangles, about 40,000 faces), with holes, fins, faces wound against the rest, faces with a
// repeated vertex, and the faces in a scrambled order.
std::vector<Face> large_awkward_faces(std::size_t& vertex_count) {
  constexpr Index kNx = 301, kNy = 81;
  std::vector<Face> faces;
  std::uint32_t state = 777;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  for (Index j = 0; j + 1 < kNy; ++j) {
    for (Index i = 0; i + 1 < kNx; ++i) {
      const Index a = j * kNx + i, b = a + 1, c = a + kNx + 1, d = a + kNx;
      const std::uint32_t r = next() >> 24;
      if (r < 3) continue;  // a hole
      if (r < 80) {
        faces.push_back({a, b, c, d});
      } else {
        faces.push_back({a, b, c, kInvalid});
        faces.push_back({a, c, d, kInvalid});
      }
      if (r > 250) faces.push_back({a, c, kNx * kNy + (r & 3), kInvalid});  // a fin or a third use
      if (r == 249) faces.push_back({a, a, b, kInvalid});                   // a collapsed corner
    }
  }
  for (Face& f : faces)
    if ((next() >> 28) < 2) std::swap(f[1], f[2]);
  for (std::size_t f = faces.size(); f > 1; --f) std::swap(faces[f - 1], faces[next() % f]);
  vertex_count = kNx * kNy + 4;
  return faces;
}

// The adjacency as its header defines it, from a map of each edge's slots.
EdgeAdjacency reference_adjacency(std::span<const Face> faces) {
  std::map<std::pair<Index, Index>, std::vector<Index>> uses;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const int n = corner_count(faces[f]);
    for (int c = 0; c < n; ++c) {
      const Index a = faces[f][c], b = faces[f][(c + 1) % n];
      if (a != b) uses[{std::min(a, b), std::max(a, b)}].push_back(Index(4 * f + c));
    }
  }
  EdgeAdjacency r;
  r.slot_edge.assign(4 * faces.size(), kInvalid);
  r.opposite_face.assign(4 * faces.size(), kInvalid);
  r.opposite_corner.assign(4 * faces.size(), 0xff);
  const auto tail = [&](Index slot) { return faces[slot / 4][slot % 4]; };
  for (const auto& [key, slots] : uses) {
    const Index id = Index(r.edges.size());
    MeshEdge e;
    e.v0 = key.first;
    e.v1 = key.second;
    e.first_slot = slots[0];
    e.uses = Index(slots.size());
    for (Index s : slots) r.slot_edge[s] = id;
    if (slots.size() == 1) r.boundary_edges.push_back(id);
    if (slots.size() > 2) r.nonmanifold_edges.push_back(id);
    if (slots.size() == 2) {
      e.same_direction = tail(slots[0]) == tail(slots[1]);
      if (e.same_direction) r.inconsistent_edges.push_back(id);
      r.opposite_face[slots[0]] = slots[1] / 4;
      r.opposite_corner[slots[0]] = std::uint8_t(slots[1] % 4);
      r.opposite_face[slots[1]] = slots[0] / 4;
      r.opposite_corner[slots[1]] = std::uint8_t(slots[0] % 4);
    }
    r.edges.push_back(e);
  }
  return r;
}

TEST(Adjacency, LargeMeshMatchesTheDefinitionOnOneAndManyThreads) {
  std::size_t nv = 0;
  const std::vector<Face> faces = large_awkward_faces(nv);
  ASSERT_GT(faces.size(), 35'000u);
  EdgeAdjacency one;
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    one = build_edge_adjacency(faces, nv);
  }
  const EdgeAdjacency many = build_edge_adjacency(faces, nv);
  ASSERT_FALSE(one.boundary_edges.empty());
  ASSERT_FALSE(one.nonmanifold_edges.empty());
  ASSERT_FALSE(one.inconsistent_edges.empty());
  expect_same_adjacency(one, many);
  EdgeAdjacency ref = reference_adjacency(faces);
  ref.boundary_loops = one.boundary_loops;  // the loops are chained alike; the test above checks
  expect_same_adjacency(one, ref);
}

// With several bad faces, the first one is named.
TEST(Adjacency, MissingVertexNamesTheFirstBadFaceOfALargeMesh) {
  std::size_t nv = 0;
  std::vector<Face> faces = large_awkward_faces(nv);
  faces[30'001][2] = Index(nv + 5);
  faces[20'002][1] = Index(nv + 9);
  try {
    build_edge_adjacency(faces, nv);
    FAIL() << "no GeometryError";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("face 20002 names vertex " + std::to_string(nv + 9)),
              std::string::npos)
        << e.what();
  }
}

TEST(Adjacency, MissingVertexThrowsGeometryError) {
  const std::vector<Face> faces = {{0, 1, 7, kInvalid}};
  EXPECT_THROW(build_edge_adjacency(faces, 3), GeometryError);
}

}  // namespace
}  // namespace hm
