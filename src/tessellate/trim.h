// Trimmed and bounded patches: meshed only inside their loops, holes included. The sampled loops
// become the mesh boundary, so boundary vertices lie on the trim curves within tolerance.
#pragma once

#include "nurbs/patch.h"
#include "tessellate/initial_grid.h"
#include "tessellate/patch_mesh.h"
#include "tessellate/sample_normals.h"

namespace hm {

// Loops are sampled within chord_tolerance (turned into parameter units with the grid's largest
// speed) and split so that no boundary segment is longer than edge_length in 3D. An untrimmed
// patch has one loop, the sides of its domain. Grid points inside the region and clear of every
// loop (by kLoopClearance edges) are added, and the whole is triangulated by a constrained
// Delaunay triangulation in (u, v) scaled by the mean speeds (so close to isotropic in 3D).
//
// sheared (its normal samples; null when not): the patch's parameter lines run nearly side by
// side in 3D somewhere (a three-sided plate modelled with four sides, two of them almost in
// line), so the grid crowds there and the scaled (u, v) plane is far from isotropic. The grid
// points are then thinned to about kShearedSpacing edges apart in 3D, the points triangulated on
// a plane the patch is a graph over (when the samples show one), and the triangulation improved
// by 3D edge flips. Throws GeometryError when the loops cannot be triangulated.
PatchMesh trimmed_mesh(const Patch& p, const GridLines& lines, double edge_length,
                       double chord_tolerance, const NormalSamples* sheared = nullptr);

inline constexpr double kLoopClearance = 0.5;
inline constexpr double kShearedSpacing = 0.7;

}  // namespace hm
