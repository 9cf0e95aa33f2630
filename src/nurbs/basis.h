// Internal to src/nurbs: views of the NURBS types as the raw arrays the kernels take. The basis
// functions themselves live in kernels/bspline_basis.h (written once, shared with the kernel).
#pragma once

#include <span>
#include <vector>

#include "kernels/evaluate_nurbs.h"
#include "nurbs/nurbs_surface.h"

namespace hm {

inline kernel::SurfaceArrays surface_arrays(const NurbsSurface& s) {
  kernel::SurfaceArrays a;
  a.degree_u = s.degree_u;
  a.degree_v = s.degree_v;
  a.count_u = s.count_u;
  a.count_v = s.count_v;
  a.knots_u = s.knots_u;
  a.knots_v = s.knots_v;
  a.points = s.points;
  a.weights = s.weights;
  a.u0 = s.u0;
  a.u1 = s.u1;
  a.v0 = s.v0;
  a.v1 = s.v1;
  return a;
}

// Checks one direction of a B-spline: degree in [1, kMaxDegree], count > degree, knots.size() ==
// count + degree + 1, finite non-decreasing knots with a non-empty valid range, and a domain
// [t0, t1] with t0 < t1 inside [knots[degree], knots[count]] (to 1e-9 of the range). Throws
// GeometryError naming `what` (for example "NURBS surface, u direction").
void check_direction(const char* what, int degree, long long count, std::span<const double> knots,
                     double t0, double t1);
// Checks that there are `expected` finite points and positive finite weights.
void check_net(const char* what, std::span<const Vec3d> points, std::span<const double> weights,
               long long expected);

// Distinct knot values strictly inside (t0, t1), with t0 and t1 added: the span boundaries.
std::vector<double> span_breaks(std::span<const double> knots, double t0, double t1);

}  // namespace hm
