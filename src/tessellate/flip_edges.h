// Edge flips that round a patch triangulation's triangles in 3D while it stays a valid
// triangulation of its (u, v) region. Used where the parameter plane is sheared in 3D (a patch
// whose parameter lines run nearly parallel), so that a Delaunay triangulation in (u, v) is far
// from one in 3D.
#pragma once

#include <cstddef>
#include <span>

#include "tessellate/patch_mesh.h"

namespace hm {

inline constexpr int kMaxFlipPasses = 32;

// Lawson's flips with the smallest 3D angle as the criterion. An interior edge is flipped when
//   - the smallest 3D angle of the two triangles that would replace its pair is larger,
//   - both stay counter-clockwise in the chart (the quad is strictly convex there), and
//   - both keep the side of the old pair's summed normal (no fold is made).
// Boundary edges never flip, so trim loops and domain sides stay. `plane` (per vertex) is the 2D
// chart the triangulation is counter-clockwise in: (u, v), scaled or not, or a plane the patch is
// a graph over; the flipped pair must stay counter-clockwise there. The mesh must have no seam
// (each triangle's corner (u, v) equal to its vertices' canonical ones). Serial, triangles in
// index order, up to max_passes passes: the same input gives the same output. Returns the flips.
std::size_t flip_edges_3d(PatchMesh& m, std::span<const Vec2d> plane,
                          int max_passes = kMaxFlipPasses);

}  // namespace hm
