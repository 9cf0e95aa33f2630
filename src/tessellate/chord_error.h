// Measured chord error: how far the exact surface is from each flat triangle.
#pragma once

#include <vector>

#include "nurbs/nurbs_surface.h"
#include "tessellate/patch_mesh.h"

namespace hm {

// Per triangle (m): the largest distance from the NURBS point at each edge's middle (u, v) and
// at the centroid (u, v) to the flat triangle. Parallel over triangles.
// Samples next to a collapsed side follow CollapsedSides' rules.
std::vector<double> measure_chord_error(const NurbsSurface& s, const PatchMesh& m,
                                        const CollapsedSides& collapsed = {});

// The chord error of one flat triangle (a, b, c) whose corners have parameters w.
double triangle_chord_error(const NurbsSurface& s, const Vec3d& a, const Vec3d& b, const Vec3d& c,
                            const TriUv& w, const CollapsedSides& collapsed);

// Distance from p to the triangle (a, b, c) in 3D, degenerate triangles included.
double point_triangle_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c);

}  // namespace hm
