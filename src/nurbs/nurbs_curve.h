// Rational B-spline curves, used for trim loops (in parameter space, z = 0) and model-space
// boundary curves.
#pragma once

#include <vector>

#include "core/vec.h"

namespace hm {

// points has count values, knots count + degree + 1, weights one positive value per point.
struct NurbsCurve {
  int degree = 0;
  std::vector<double> knots;
  std::vector<Vec3d> points;
  std::vector<double> weights;
  double t0 = 0, t1 = 1;  // parameter range actually used
  bool periodic = false;

  int count() const { return static_cast<int>(points.size()); }
};

void validate_curve(const NurbsCurve& c);
Vec3d evaluate(const NurbsCurve& c, double t);
// Position and first derivative.
void evaluate_derivs(const NurbsCurve& c, double t, Vec3d& p, Vec3d& dp);

// A polyline through the curve from t0 to t1, both ends included, with chord error at most tol
// (length units of the curve). At least min_segments segments.
std::vector<Vec3d> sample_curve(const NurbsCurve& c, double tol, int min_segments = 1);

// Exact NURBS forms of simple curves (used by the importer and the generator).
NurbsCurve make_line(const Vec3d& a, const Vec3d& b);
NurbsCurve make_polyline(const std::vector<Vec3d>& pts);  // degree 1 through all points
// Circular arc in the plane z = zt: centre c, from a to b counter-clockwise (seen from +z).
NurbsCurve make_circular_arc(const Vec3d& c, const Vec3d& a, const Vec3d& b);

}  // namespace hm
