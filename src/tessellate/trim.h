// Trimmed and bounded patches: meshed only inside their loops, holes included. The sampled loops
// become the mesh boundary, so boundary vertices lie on the trim curves within tolerance.
#pragma once

#include "nurbs/patch.h"
#include "tessellate/initial_grid.h"
#include "tessellate/patch_mesh.h"

namespace hm {

// Loops are sampled within chord_tolerance (turned into parameter units with the grid's largest
// speed) and split so that no boundary segment is longer than edge_length in 3D. Grid points
// inside the region and clear of every loop (by kLoopClearance edges) are added, and the whole is
// triangulated by a constrained Delaunay triangulation in (u, v) scaled by the mean speeds (so
// close to isotropic in 3D). Throws GeometryError when the loops cannot be triangulated.
PatchMesh trimmed_mesh(const Patch& p, const GridLines& lines, double edge_length,
                       double chord_tolerance);

inline constexpr double kLoopClearance = 0.5;

}  // namespace hm
