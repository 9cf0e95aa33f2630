// Batched surface evaluation: many parameters at once through the kernel, parallel over rows.
// Results are bit-identical to evaluate() / normal() point by point, for any thread count.
#pragma once

#include <span>
#include <vector>

#include "core/vec.h"
#include "nurbs/nurbs_surface.h"

namespace hm {

// Positions (m, model frame) and, when asked for, unit normals (Su x Sv, with the degenerate
// fallback of normal()). For a grid, sample (i, j) is at index i + us.size() * j (u fastest).
struct SurfaceSamples {
  std::vector<Vec3d> positions;
  std::vector<Vec3d> normals;  // empty unless with_normals
};

// The grid us x vs (parameters outside the knot range are clamped into it).
SurfaceSamples evaluate_grid(const NurbsSurface& s, std::span<const double> us,
                             std::span<const double> vs, bool with_normals = false);

// The uniform n_u x n_v grid over the whole domain, ends included (n_u, n_v >= 2).
SurfaceSamples evaluate_grid(const NurbsSurface& s, int n_u, int n_v, bool with_normals = false);

// A list of (u, v) pairs, in order.
SurfaceSamples evaluate_uv(const NurbsSurface& s, std::span<const Vec2d> uv,
                           bool with_normals = false);

// n >= 2 values from a to b, both included, evenly spaced.
std::vector<double> uniform_params(double a, double b, int n);

}  // namespace hm
