// Rational B-spline (NURBS) surfaces: the one exact surface type every imported entity becomes.
// Positions in metres once imported (the IGES reader converts units), in the file's model frame
// with every 124 transform already applied.
#pragma once

#include <memory>
#include <vector>

#include "core/vec.h"

namespace hm {

// Control net of (count_u x count_v) points, u varying fastest: point (i, j) is
// points[i + count_u * j], as IGES 128 stores them. knots_u has count_u + degree_u + 1 values,
// non-decreasing. weights has one positive value per point (all 1 for a polynomial surface).
// The parameter domain is [u0, u1] x [v0, v1], inside the knot range.
struct NurbsSurface {
  int degree_u = 0;
  int degree_v = 0;
  int count_u = 0;
  int count_v = 0;
  std::vector<double> knots_u;
  std::vector<double> knots_v;
  std::vector<Vec3d> points;
  std::vector<double> weights;
  bool periodic_u = false;  // IGES PROP4/PROP5: informational, the knot vector is clamped or not
  bool periodic_v = false;
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;

  const Vec3d& point(int i, int j) const { return points[i + count_u * j]; }
  double weight(int i, int j) const { return weights[i + count_u * j]; }
  bool rational() const;
};

// Position and partial derivatives at (u, v). Second derivatives are filled when asked for.
struct SurfaceDerivs {
  Vec3d p, su, sv, suu, suv, svv;
};

struct PrincipalCurvature {
  double k1 = 0, k2 = 0;  // k1 >= k2, signed with respect to the unit normal (1/m)
  Vec3d d1, d2;           // unit principal directions in model space
  double gaussian() const { return k1 * k2; }
  double mean() const { return 0.5 * (k1 + k2); }
};

struct SurfaceProjection {
  double u = 0, v = 0;
  Vec3d point;
  double distance = 0;
  bool converged = false;
};

// Throws GeometryError when the surface is malformed (validate_surface is the full check).
void validate_surface(const NurbsSurface& s);

Vec3d evaluate(const NurbsSurface& s, double u, double v);
SurfaceDerivs evaluate_derivs(const NurbsSurface& s, double u, double v, int order = 1);

// Unit normal su x sv. Where that vanishes (an edge collapsed to a point, a zero-length row of
// control points) the normal is taken from a nearby interior parameter, never NaN.
Vec3d normal(const NurbsSurface& s, double u, double v);

// Principal curvatures from the first and second fundamental forms, with the same fallback.
PrincipalCurvature principal_curvature(const NurbsSurface& s, double u, double v);

// Closest point on the surface (within its domain) to q: a coarse grid search for the start,
// then Newton iterations clamped to the domain.
SurfaceProjection closest_point(const NurbsSurface& s, const Vec3d& q);
// Newton from a given start, for callers that already know a good (u, v).
SurfaceProjection closest_point(const NurbsSurface& s, const Vec3d& q, double u_start,
                                double v_start);
// The same with net = net_size(s) computed once by the caller: the net's size sets Newton's
// tolerances, and measuring it visits every control point (a single-patch hull's 972 cost twice
// the Newton iterations).
SurfaceProjection closest_point(const NurbsSurface& s, const Vec3d& q, double u_start,
                                double v_start, double net);
// And the derivatives (to second order) at the answer's (u, v), which Newton evaluated last:
// the same bits as evaluate_derivs(s, u, v, 2) there.
SurfaceProjection closest_point(const NurbsSurface& s, const Vec3d& q, double u_start,
                                double v_start, double net, SurfaceDerivs& at_answer);
// Diagonal of the control net's bounding box (m; 1 for a net of one point).
double net_size(const NurbsSurface& s);

// Many projections onto one surface (a trim curve's samples): the evaluation arrays are built
// once, and the coarse start grid once, at the first global search, instead of per query. Gives
// the same answers as closest_point. The surface must outlive the projector. Not thread-safe:
// one projector per thread.
class SurfaceProjector {
 public:
  explicit SurfaceProjector(const NurbsSurface& s);
  ~SurfaceProjector();
  SurfaceProjector(const SurfaceProjector&) = delete;
  SurfaceProjector& operator=(const SurfaceProjector&) = delete;

  SurfaceProjection project(const Vec3d& q);
  SurfaceProjection project(const Vec3d& q, double u_start, double v_start);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Distinct knot values inside the domain in each direction (span boundaries), u0 and u1 included.
std::vector<double> span_breaks_u(const NurbsSurface& s);
std::vector<double> span_breaks_v(const NurbsSurface& s);

}  // namespace hm
