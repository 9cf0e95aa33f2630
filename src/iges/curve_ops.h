// Exact operations on rational B-spline curves used to build surfaces from curves (118 ruled,
// 120 revolution, 122 tabulated cylinder) and to join composite curves: knot insertion and
// refinement, degree elevation, cutting to the used range, reversal, exact circular arcs.
// Every operation works on homogeneous control points, so rational curves stay exact.
#pragma once

#include <cstdint>
#include <vector>

#include "nurbs/nurbs_curve.h"

namespace hm::iges {

// Reverses the direction of travel; the parameter range stays [t0, t1].
void reverse_curve(NurbsCurve& c);
// Maps the parameter range [t0, t1] linearly onto [a, b] (knots follow). Requires t1 > t0.
void reparametrize(NurbsCurve& c, double a, double b);
// Inserts the sorted knots x (values inside the knot range) in one pass.
void refine_knots(NurbsCurve& c, const std::vector<double>& x);
// Inserts knot u `times` times.
void insert_knot(NurbsCurve& c, double u, int times);
// Cuts the curve to [t0, t1] with clamped end knots (multiplicity degree + 1), so that the first
// and last control points are the end points. Also turns unclamped (periodic) knots clamped.
void clamp_to_range(NurbsCurve& c);
// Raises the degree to `target` (>= degree) exactly. The curve must be clamped. Fails (returns
// false) when the result would have more than max_points control points.
bool elevate_degree(NurbsCurve& c, int target, std::uint64_t max_points);
// Makes two clamped curves on [0, 1] share degree and knot vector (elevation, then refinement
// with the union of both knot vectors). Returns false when a size limit would be exceeded.
bool make_compatible(NurbsCurve& a, NurbsCurve& b, std::uint64_t max_points);
// Joins a head-to-tail chain into one clamped curve; component k keeps its own parameter length,
// shifted to follow the previous one (the IGES 102 parametrisation). End points that do not meet
// exactly are averaged. Returns false when a size limit would be exceeded.
bool join_chain(const std::vector<NurbsCurve>& chain, std::uint64_t max_points, NurbsCurve& out);

// Exact rational quadratic arc: p(theta) = c + cos(theta) x + sin(theta) y for theta in
// [theta0, theta1], at most a quarter turn per segment. Parameter = angle at the knots.
NurbsCurve rational_arc(const Vec3d& c, const Vec3d& x, const Vec3d& y, double theta0,
                        double theta1);

// Largest distance between consecutive control points' positions; a size for tolerances.
double control_extent(const NurbsCurve& c);

}  // namespace hm::iges
