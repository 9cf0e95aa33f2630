#include "tessellate/sample_normals.h"

namespace hm {

double NormalSamples::share_beyond(const Vec3d& dir, double cos_limit) const {
  if (!(total > 0)) return 0;
  double beyond = 0;
  for (const Vec3d& j : jac) {
    const double m = norm(j);
    if (dot(j, dir) < cos_limit * m) beyond += m;
  }
  return beyond / total;
}

NormalSamples sample_normals(const NurbsSurface& s) {
  NormalSamples ns;
  ns.jac.reserve(kNormalSamples * kNormalSamples);
  ns.at.reserve(kNormalSamples * kNormalSamples);
  for (int j = 0; j < kNormalSamples; ++j) {
    for (int i = 0; i < kNormalSamples; ++i) {
      const double u = s.u0 + (s.u1 - s.u0) * i / (kNormalSamples - 1);
      const double v = s.v0 + (s.v1 - s.v0) * j / (kNormalSamples - 1);
      const SurfaceDerivs d = evaluate_derivs(s, u, v, 1);
      ns.jac.push_back(cross(d.su, d.sv));
      ns.at.push_back(d.p);
      ns.sum += ns.jac.back();
      ns.total += norm(ns.jac.back());
    }
  }
  return ns;
}

}  // namespace hm
