#include "nurbs/nurbs_surface.h"

#include "nurbs/basis.h"

namespace hm {

bool NurbsSurface::rational() const {
  for (const double w : weights) {
    if (w != weights.front()) return true;
  }
  return false;
}

void validate_surface(const NurbsSurface& s) {
  check_direction("NURBS surface, u direction", s.degree_u, s.count_u, s.knots_u, s.u0, s.u1);
  check_direction("NURBS surface, v direction", s.degree_v, s.count_v, s.knots_v, s.v0, s.v1);
  check_net("NURBS surface", s.points, s.weights,
            static_cast<long long>(s.count_u) * static_cast<long long>(s.count_v));
}

Vec3d evaluate(const NurbsSurface& s, double u, double v) {
  return kernel::surface_point(surface_arrays(s), u, v);
}

SurfaceDerivs evaluate_derivs(const NurbsSurface& s, double u, double v, int order) {
  Vec3d d[6];
  if (order < 0) order = 0;
  if (order > 2) order = 2;
  kernel::surface_derivs(surface_arrays(s), u, v, order, d);
  return SurfaceDerivs{d[0], d[1], d[2], d[3], d[4], d[5]};
}

Vec3d normal(const NurbsSurface& s, double u, double v) {
  return kernel::surface_normal(surface_arrays(s), u, v);
}

std::vector<double> span_breaks_u(const NurbsSurface& s) {
  return span_breaks(s.knots_u, s.u0, s.u1);
}

std::vector<double> span_breaks_v(const NurbsSurface& s) {
  return span_breaks(s.knots_v, s.v0, s.v1);
}

}  // namespace hm
