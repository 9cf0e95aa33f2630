// Newton refinements onto one NURBS patch in double precision: a ray crossing, and a plane
// crossing along a mesh edge. Model frame, metres. No Embree here.
#pragma once

#include "core/vec.h"
#include "nurbs/nurbs_surface.h"

namespace hm::query {

// The (u, v) domain of a patch, and whether the surface closes on itself across a domain side
// (a seam: S(u0, v) == S(u1, v)), in which case parameters wrap instead of being clamped.
struct ParamDomain {
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
  bool closed_u = false, closed_v = false;

  // Wrapped into the domain in closed directions, clamped in the others.
  Vec2d map(Vec2d uv) const;
};

// Finds the domain of s and tests it for seams with a tolerance tol (metres).
ParamDomain make_domain(const NurbsSurface& s, double tol);

// Moves the corner parameters of a triangle that straddles a seam onto one side of it, so that
// barycentric interpolation between them is meaningful (the result may leave the domain by less
// than a period; map() wraps it back).
void unwrap_corners(const ParamDomain& d, Vec2d* uv, int count);

struct RefinedRay {
  double t = 0;
  Vec2d uv;
  Vec3d point;
  bool converged = false;
};

// Crossing of the ray o + t d with the surface, Newton on (t, u, v) from (t0, uv0). tol is the
// residual |S(u, v) - (o + t d)| accepted as converged (metres).
RefinedRay refine_ray(const NurbsSurface& s, const ParamDomain& d, const Vec3d& o, const Vec3d& dir,
                      double t0, Vec2d uv0, double tol);

struct RefinedPlanePoint {
  Vec2d uv;
  Vec3d point;
  bool converged = false;
};

// The point where the plane n.(x - p) = 0 (n unit) crosses the surface image of the parameter
// segment uv_a -> uv_b of a mesh edge; s0 in [0, 1] is the linear estimate along the edge and
// estimate its 3D position. tol is the accepted plane residual (metres).
//
// Why this point rather than the point of the section curve nearest the estimate: the edge's
// corners lie on the surface on opposite sides of the plane, so the root is bracketed and a
// safeguarded Newton always converges; it depends on the edge alone, so both triangles of an edge
// agree; and a patch-border edge has its segment on the border, so the two patches land on the
// same border point and the join closes the gap to round-off. It lies within the chord error of
// the estimate. When the corners do not bracket the plane (a corner off the surface, a trim), the
// nearest point on the section curve is used instead (plane n.(S - p) = 0 and T.(S - estimate)
// = 0, with the curve tangent T = n x N frozen at the start).
RefinedPlanePoint refine_plane_edge(const NurbsSurface& s, const ParamDomain& d, const Vec3d& n,
                                    const Vec3d& p, Vec2d uv_a, Vec2d uv_b, double s0,
                                    const Vec3d& estimate, double tol);

// Newton steps on the stationarity of |S(u, v) - q|^2 from (u, v), with second derivatives; a
// parameter at a domain side whose gradient pushes outwards stays there. Polishes the answer of
// hm::closest_point (whose stop test is a cosine of 1e-7) to round-off; a step that moves S
// farther from q is not taken. at_uv holds the derivatives at the starting uv (Newton's last
// evaluation); point gets S at the returned (u, v).
Vec2d polish_closest(const NurbsSurface& s, const ParamDomain& d, const Vec3d& q, Vec2d uv,
                     const SurfaceDerivs& at_uv, Vec3d& point);

}  // namespace hm::query
