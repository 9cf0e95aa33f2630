// The modified butterfly subdivision rules (Zorin, Schroeder, Sweldens 1996), used to predict the
// 3D position of a new edge midpoint before it is projected onto the NURBS.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "tessellate/patch_mesh.h"

namespace hm {

// One-rings of every vertex: neighbours in counter-clockwise order. A closed ring has one
// neighbour per incident triangle; an open one (a boundary fan) one more, from the first to the
// last boundary neighbour. kNone marks a vertex whose fan is not a single disk or half-disk (a
// hanging node of an adaptive mesh, a non-manifold vertex): no rule applies there.
enum class RingKind : std::uint8_t { kNone, kClosed, kOpen };

struct VertexRings {
  std::vector<Index> offset;  // vertex v's ring is ring[offset[v], offset[v] + size[v])
  std::vector<Index> size;
  std::vector<Index> ring;
  std::vector<RingKind> kind;

  std::span<const Index> of(Index v) const { return {ring.data() + offset[v], size[v]}; }
};

VertexRings build_rings(std::span<const Tri> tris, std::size_t vertex_count);

// Zorin's weight s_j of the j-th ring neighbour (j = 0 is the other end of the edge) for an
// extraordinary vertex of valence k; the vertex itself weighs 3/4.
double extraordinary_weight(int k, int j);

// Predicted midpoint of edge (a, b): the 10-point stencil (tension w) when both ends are regular
// interior vertices (valence 6), the extraordinary rule of the irregular end(s) otherwise, the
// 4-point rule when (a, b) is a boundary edge between boundary vertices (is_boundary[v] true), and
// the plain midpoint where the neighbourhood supports no rule.
Vec3d butterfly_midpoint(const VertexRings& rings, std::span<const Vec3d> p,
                         std::span<const std::uint8_t> is_boundary, Index a, Index b,
                         bool boundary_edge, double w);

}  // namespace hm
