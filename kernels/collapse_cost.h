// The numeric core of the coarsening cost (issue 5): the paper's per-criterion qualities of one
// candidate collapse, as plain functions over corner positions. Each q_i lies in [0, 1], 1 best.
//
// Shapes and units: positions in metres; a triangle is three corners; sizes are edge lengths in
// metres. Depends on core alone.
#pragma once

#include <span>

#include "core/vec.h"

namespace hm::kernel {

// q1, the shape of one triangle: 4 sqrt(3) A / (l0^2 + l1^2 + l2^2). 1 for an equilateral
// triangle, 0 for a degenerate one; a triangle whose smallest angle is 30 degrees scores 0.6 to
// 0.76 depending on its other angles.
double triangle_shape(const Vec3d& a, const Vec3d& b, const Vec3d& c);

// The edge length of the equilateral triangle of area A: sqrt(4 A / sqrt(3)), metres.
double equilateral_edge(double area);

// q3 and q4, a size criterion: r is a panel's equilateral edge over the edge the size field
// wants there. 1 at r = 0, 1/2 at the wanted size, 0 at twice it and beyond: smaller results
// score higher, so the coarsening grows the panels evenly against the field.
inline double size_quality(double r) { return r >= 2 ? 0.0 : (r <= 0 ? 1.0 : 1.0 - 0.5 * r); }

// q2, the area ratio of neighbouring panels: smallest area over largest among `areas` (the
// panels around the vertex that survives a collapse). 1 when all are equal, 0 when one is zero.
double area_ratio_quality(std::span<const double> areas);
// The same from the smallest and largest area alone (any common scale).
inline double area_ratio_quality(double smallest, double largest) {
  return largest > 0 ? smallest / largest : 0;
}

// The paper's weighted index q = sum_i (w_i q_i) / n over n = 4 criteria (shape, area ratio,
// curvature size, source size).
struct CollapseQualities {
  double shape = 0, area_ratio = 0, curvature = 0, sources = 0;
};
struct CollapseWeights {
  double shape = 1, area_ratio = 1, curvature = 1, sources = 1;
};
inline double weighted_index(const CollapseQualities& q, const CollapseWeights& w) {
  return (w.shape * q.shape + w.area_ratio * q.area_ratio + w.curvature * q.curvature +
          w.sources * q.sources) /
         4.0;
}

// Squared distance from p to the triangle (a, b, c) (closest point on its interior, edges or
// corners), m^2. Degenerate triangles give the distance to their longest edge.
double point_triangle_distance2(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c);

// Scores a batch of triangles: shape[i] = triangle_shape of corners (3 i, 3 i + 1, 3 i + 2).
// The batched form the benchmark measures; each i writes its own slot.
void triangle_shapes(std::span<const Vec3d> corners, std::span<double> shape);

}  // namespace hm::kernel
