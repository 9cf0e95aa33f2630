// Parameter-space curves from model-space curves: sample the curve, project each sample onto the
// surface (closest point, warm-started from the previous one) and refine until the polyline in
// (u, v), mapped back through the surface, stays within tolerance of the curve.
#pragma once

#include <cstdint>
#include <vector>

#include "nurbs/nurbs_curve.h"
#include "nurbs/nurbs_surface.h"

namespace hm::iges {

// Degree-1 curve in (u, v) (z = 0). tol is in model units; max_distance returns the largest
// distance between a curve sample and its projection (the curve's offset from the surface).
// Each projection uses one unit of `budget`; when it runs out the result is incomplete and
// budget is 0 (the caller reports the entity).
NurbsCurve project_to_uv(const NurbsSurface& s, const NurbsCurve& c, double tol,
                         double& max_distance, std::uint64_t& budget);

// Points along the curve: the control points of a polyline, else a few per knot span.
std::vector<Vec3d> sample_points(const NurbsCurve& c, int per_span = 8);

}  // namespace hm::iges
