// Surface entities to one exact rational B-spline patch each: 128 rational B-spline, 118 ruled,
// 120 surface of revolution, 122 tabulated cylinder, 108 plane, 190 plane surface, 114
// parametric spline surface.
#pragma once

#include <optional>
#include <vector>

#include "core/diagnostics.h"
#include "iges/iges_context.h"
#include "nurbs/patch.h"

namespace hm::iges {

bool is_surface_type(int type);

// Curves that bound an otherwise unbounded plane (108 form 0, 190) when a 143/144 wraps it:
// model-space curves in the plane's definition space, or curves in its (u, v) space.
struct PlaneBounds {
  std::vector<NurbsCurve> model_curves;
  std::vector<NurbsCurve> uv_curves;
};

struct ConvertedSurface {
  NurbsSurface surface;
  std::vector<TrimLoop> loops;  // a bounded 108 plane's bounding curve, in (u, v)
};

// The surface of entity `index` in model units with its own 124 chain applied. nullopt when the
// entity describes no bounded surface (an unbounded plane with no bounds). Throws EntityFault for
// malformed data, LimitError for declared sizes over the limits. Notes (approximations made) go
// to `notes`.
std::optional<ConvertedSurface> convert_surface(const Context& ctx, int index,
                                                const PlaneBounds* bounds, Diagnostics& notes);

// Applies x -> a(x) to the control points (exact for rational surfaces).
void apply(const Affine& a, NurbsSurface& s);

// Number of parameters the entity's own definition uses (the 406 property pointers follow);
// 0 when unknown.
std::size_t own_parameter_count(const Params& p);

}  // namespace hm::iges
