#include <cmath>

#include "nurbs/basis.h"
#include "nurbs/nurbs_surface.h"

namespace hm {
namespace {

constexpr double kCurvatureRatio = 1e-4;

}  // namespace

// The shape operator is written in the orthonormal tangent frame e1 = Su / |Su|, e2 = n x e1,
// where it is a symmetric 2 x 2 matrix whose eigen-decomposition is stable even at umbilics.
PrincipalCurvature principal_curvature(const NurbsSurface& s, double u, double v) {
  const kernel::SurfaceArrays a = surface_arrays(s);
  Vec3d d[6];
  kernel::surface_derivs(a, u, v, 2, d);
  if (kernel::normal_degenerate(d[1], d[2], s.u1 - s.u0, s.v1 - s.v0)) {
    // Curvature needs a better-conditioned first fundamental form than the normal does (its
    // inverse enters): step in until the area element is 1e-4 of the edge lengths squared.
    if (!kernel::regular_param(a, u, v, kCurvatureRatio)) return {};  // a point or a curve
    kernel::surface_derivs(a, u, v, 2, d);
  }
  const Vec3d& su = d[1];
  const Vec3d& sv = d[2];
  const Vec3d n = normalized(cross(su, sv));
  const double e = dot(su, su);
  const double f = dot(su, sv);
  const double g = dot(sv, sv);
  const double l = dot(d[3], n);
  const double m = dot(d[4], n);
  const double nn = dot(d[5], n);

  // Parameter-space coordinates (x, y) of e1 and e2 (tangent = x Su + y Sv).
  const Vec3d e1 = su / std::sqrt(e);
  const Vec3d e2 = cross(n, e1);
  const double det = e * g - f * f;
  const double b1 = dot(su, e2);
  const double b2 = dot(sv, e2);
  const double x1 = 1.0 / std::sqrt(e);
  const double x2 = (g * b1 - f * b2) / det;
  const double y2 = (e * b2 - f * b1) / det;
  // Second fundamental form on the frame: II(a, b) = [ax ay] [l m; m n] [bx by]^T.
  const double p = l * x1 * x1;
  const double q = (l * x2 + m * y2) * x1;
  const double r = l * x2 * x2 + 2 * m * x2 * y2 + nn * y2 * y2;

  PrincipalCurvature pc;
  const double mean = 0.5 * (p + r);
  const double half_gap = std::hypot(0.5 * (p - r), q);
  pc.k1 = mean + half_gap;
  pc.k2 = mean - half_gap;
  const double theta = 0.5 * std::atan2(2 * q, p - r);
  pc.d1 = std::cos(theta) * e1 + std::sin(theta) * e2;
  pc.d2 = cross(n, pc.d1);
  return pc;
}

}  // namespace hm
