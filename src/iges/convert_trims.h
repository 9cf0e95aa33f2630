// Trimmed and bounded surfaces and B-rep faces: 144 (with 142 curves on surface), 143 (with
// 141 boundaries) and 510 faces (508 loops over 504 edges and 502 vertices). Each becomes one
// Patch whose loops are in the surface's (u, v) space; a model-space-only trim curve is projected
// onto the surface and fitted with a polyline within tolerance.
#pragma once

#include <optional>

#include "core/diagnostics.h"
#include "iges/iges_context.h"
#include "nurbs/patch.h"

namespace hm::iges {

bool is_wrapper_type(int type);  // 143, 144, 510

// Directory index of the surface a 143/144/510 wraps, or -1 when it cannot be read.
int wrapped_surface(const Context& ctx, int index);

// The patch of a 143/144/510 entity, in model units (not yet metres). `reversed` is the face's
// orientation from its 514 shell and 186 solid. nullopt when the wrapped surface is an unbounded
// plane that the trim curves do not bound either. Throws EntityFault / LimitError; a malformed
// trim loop is dropped with a warning in `diags` and the patch kept.
std::optional<Patch> convert_wrapped(const Context& ctx, int index, bool reversed,
                                     Diagnostics& diags);

// True when the loop runs along the boundary of the patch's parameter domain (within a small
// relative tolerance) and encloses all of it.
bool is_natural_boundary(const TrimLoop& loop, const NurbsSurface& s);

}  // namespace hm::iges
