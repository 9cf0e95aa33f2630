// Edge adjacency of a surface mesh, built by sorting edge keys (no pointer chasing).
//
// Corner c of face f owns the directed edge faces[f][c] -> faces[f][(c + 1) % n]; its slot is
// 4 f + c (4 slots per face; a triangle's fourth slot stays kInvalid). Undirected edges are
// numbered in the order of their sorted (min vertex, max vertex) keys, so every array here is
// independent of the thread count and of the order faces were visited.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "mesh/surface_mesh.h"

namespace hm {

struct MeshEdge {
  Index v0 = kInvalid, v1 = kInvalid;  // v0 < v1
  Index first_slot = kInvalid;         // 4 f + c of the first use (lowest slot)
  Index uses = 0;                      // 1: boundary, 2: interior, > 2: non-manifold
  // For uses == 2: true when both faces traverse the edge in the same direction (one of the two
  // faces is flipped relative to the other).
  bool same_direction = false;
};

// A chain of boundary vertices following the faces' orientation (v[i] -> v[i + 1] is a boundary
// edge as its face traverses it). closed: the last vertex connects back to the first.
struct BoundaryLoop {
  std::vector<Index> vertices;
  std::vector<Index> edges;  // edge ids, edges[i] joins vertices[i] and vertices[i + 1] (or [0])
  bool closed = false;
};

struct EdgeAdjacency {
  std::vector<MeshEdge> edges;
  // Per corner slot (4 per face): the undirected edge id, and across it the face and the corner
  // of that face owning the same edge. kInvalid for a boundary or non-manifold edge (and for a
  // triangle's unused fourth slot).
  std::vector<Index> slot_edge;
  std::vector<Index> opposite_face;
  std::vector<std::uint8_t> opposite_corner;
  // Edge ids, ascending.
  std::vector<Index> boundary_edges;
  std::vector<Index> nonmanifold_edges;
  std::vector<Index> inconsistent_edges;  // interior edges used twice in the same direction
  std::vector<BoundaryLoop> boundary_loops;

  bool watertight() const { return boundary_edges.empty() && nonmanifold_edges.empty(); }
};

// Builds the adjacency. Faces with a repeated vertex keep their degenerate edges out (a collapsed
// edge a -> a is not an edge). Throws GeometryError when a face names a vertex >= vertex_count.
EdgeAdjacency build_edge_adjacency(std::span<const Face> faces, std::size_t vertex_count);

// The id of the edge joining a and b (either order), by binary search over the sorted keys;
// kInvalid when the mesh has no such edge.
Index find_edge(const EdgeAdjacency& adj, Index a, Index b);

// Brings `adj` up to date after the triangles with reversed[f] != 0 were reversed by swapping
// their corners 1 and 2 (faces as they are now): the same as building it again, for a fraction
// of the cost. Throws GeometryError when adj is not of this mesh or a reversed face is no
// triangle.
void reverse_in_adjacency(EdgeAdjacency& adj, std::span<const Face> faces,
                          std::span<const std::uint8_t> reversed);

// The corner slot of every boundary edge (used by one face), in the order of
// EdgeAdjacency::boundary_edges, without the rest of the adjacency: for callers that need only
// the border.
std::vector<Index> boundary_slots(std::span<const Face> faces, std::size_t vertex_count);

}  // namespace hm
