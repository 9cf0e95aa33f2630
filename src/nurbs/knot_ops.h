// Exact knot operations on NURBS surfaces: Boehm knot insertion, exact splitting into sub-patches,
// sub-surface extraction and direction reversal. None of them changes the geometry; they change
// only the parameterization (and the control net that carries it). Used by the hull generator to
// cut a hull surface into N exact patches and to inject defects (gaps, overlaps, repeated rows).
//
// All operations work in homogeneous coordinates (w x, w y, w z, w), so rational surfaces stay
// exact. Knot vectors must be clamped at the ends that are cut (multiplicity degree + 1), which
// holds for every surface the generator makes; interior values must lie strictly inside the knot
// range. Violations throw GeometryError.
#pragma once

#include <vector>

#include "nurbs/nurbs_surface.h"

namespace hm {

// How many knots equal t exactly.
int knot_multiplicity(const std::vector<double>& knots, double t);

// Inserts t `times` more times in u (or v). The multiplicity after insertion may reach
// degree + 1 (two coinciding rows of control points). t must lie strictly inside the knot range.
NurbsSurface insert_knot_u(const NurbsSurface& s, double t, int times = 1);
NurbsSurface insert_knot_v(const NurbsSurface& s, double t, int times = 1);

// Splits the surface at sorted parameter values. `breaks` holds the ends too: breaks.front() and
// breaks.back() bound the kept domain, so piece k covers [breaks[k], breaks[k + 1]]. Pieces are
// clamped (end multiplicity degree + 1) and neighbouring pieces share their border row of control
// points bit for bit, because all pieces are sliced from one refined net.
std::vector<NurbsSurface> split_u(const NurbsSurface& s, const std::vector<double>& breaks);
std::vector<NurbsSurface> split_v(const NurbsSurface& s, const std::vector<double>& breaks);

// The exact surface over [ua, ub] x [va, vb] (inside the domain, ua < ub, va < vb), with clamped
// knots and domain [ua, ub] x [va, vb].
NurbsSurface extract_subsurface(const NurbsSurface& s, double ua, double ub, double va, double vb);

// Same geometry with u (v) running the other way: u' = u0 + u1 - u. Flips the sign of su x sv.
NurbsSurface reverse_u(const NurbsSurface& s);
NurbsSurface reverse_v(const NurbsSurface& s);

// Swaps the roles of u and v (point (i, j) becomes (j, i)). Flips the sign of su x sv.
NurbsSurface transpose_uv(const NurbsSurface& s);

}  // namespace hm
