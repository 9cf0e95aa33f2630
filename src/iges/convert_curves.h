// Curve entities to rational B-splines: 100 circular arc, 102 composite, 104 conic arc,
// 106 copious data (polylines), 110 line, 112 parametric spline, 126 rational B-spline.
// Exact where the curve has an exact NURBS form; the hyperbola is sampled within tolerance.
#pragma once

#include <vector>

#include "iges/iges_context.h"
#include "nurbs/nurbs_curve.h"

namespace hm::iges {

bool is_curve_type(int type);

// The curve of entity `index` as a head-to-tail chain (one curve except for 102), in the
// definition space of whoever references it: the entity's own 124 chain is applied. Model units.
// Throws EntityFault when malformed, LimitError when a declared size is over the limits.
std::vector<NurbsCurve> convert_curve(const Context& ctx, int index, int depth = 0);

// The chain joined into a single clamped curve (for surfaces built from curves).
NurbsCurve convert_single_curve(const Context& ctx, int index);

// Applies x -> a(x) to the control points (exact for rational curves).
void apply(const Affine& a, NurbsCurve& c);

}  // namespace hm::iges
