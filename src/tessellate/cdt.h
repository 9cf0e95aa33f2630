// Constrained Delaunay triangulation of a planar region bounded by closed polygons, used to mesh
// trimmed patches in their (scaled) parameter plane.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "tessellate/patch_mesh.h"

namespace hm {

using Segment = std::array<Index, 2>;

// Delaunay triangulation of `points` (Bowyer-Watson), then every segment made an edge (Sloan's
// flips; a segment through a point is split there), then the triangles kept whose depth inside
// the segments is odd: inside an outer loop and outside its holes. Returns counter-clockwise
// triangles indexing `points`. Points closer than 1e-12 of the extent are one point (the first).
// Throws GeometryError when a segment cannot be recovered (crossing loops).
std::vector<Tri> triangulate_region(std::span<const Vec2d> points,
                                    std::span<const Segment> segments);

}  // namespace hm
