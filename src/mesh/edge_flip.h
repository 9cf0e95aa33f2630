// Flipping an interior edge between two triangles to the pair's other diagonal, and the normal
// the fold tests compare. Shared by the merge (a fan folded over a border) and the structured
// mesher (an end cap's triangles folded onto each other).
#pragma once

#include <array>
#include <optional>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"

namespace hm {

// The unit normal of triangle f, or zero when it is flatter than min_shape (twice its area over
// its longest side squared: two corners on one spot, or all three on a line).
Vec3d unit_triangle_normal(const SurfaceMesh& mesh, const Face& f, double min_shape);

// The flip of edge e: face g runs a -> b along it, face h b -> a; c and d are their third
// corners. The flip's triangles t0 = (a, d, c) and t1 = (d, b, c) keep the pair's outline
// a -> d -> b -> c, and t0 takes g's slot, t1 h's.
struct EdgeFlip {
  Index g = kInvalid, h = kInvalid;
  Face t0, t1;
  std::array<Index, 2> made;  // the new edge (c, d), smaller index first
};

// nullopt unless e has exactly two faces wound consistently, both triangles with distinct third
// corners, and the edge c - d is not in adj already.
std::optional<EdgeFlip> edge_flip(const SurfaceMesh& mesh, const EdgeAdjacency& adj, Index e);

}  // namespace hm
