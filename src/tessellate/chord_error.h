// Measured chord error: how far the exact surface is from each flat triangle.
#pragma once

#include <vector>

#include "nurbs/nurbs_surface.h"
#include "tessellate/patch_mesh.h"

namespace hm {

// Where the chord error is sampled.
//   kParametric: the NURBS point at each edge's middle (u, v) and at the centroid (u, v), and its
//     distance to the flat triangle. Cheap, and exact where the parametrisation is close to
//     affine over a triangle.
//   kFromTriangle: each edge's 3D middle and the 3D centroid, and their distance to the surface
//     (closest point, Newton from the matching (u, v)). For sheared patches, where the (u, v)
//     middle of a good 3D triangle lands far from it in the tangent plane: the parametric samples
//     would read that tangential shift as a chord error and refine a flat plate without end.
enum class ChordSampling { kParametric, kFromTriangle };

// Per triangle (m): the largest distance of the samples. Parallel over triangles.
// Samples next to a collapsed side follow CollapsedSides' rules.
std::vector<double> measure_chord_error(const NurbsSurface& s, const PatchMesh& m,
                                        const CollapsedSides& collapsed = {},
                                        ChordSampling sampling = ChordSampling::kParametric);

// The chord error of one flat triangle (a, b, c) whose corners have parameters w.
double triangle_chord_error(const NurbsSurface& s, const Vec3d& a, const Vec3d& b, const Vec3d& c,
                            const TriUv& w, const CollapsedSides& collapsed,
                            ChordSampling sampling = ChordSampling::kParametric);

// Distance from p to the triangle (a, b, c) in 3D, degenerate triangles included.
double point_triangle_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c);

}  // namespace hm
