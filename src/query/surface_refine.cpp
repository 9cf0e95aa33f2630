#include "query/surface_refine.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hm::query {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxNewton = 30;
// Newton keeps going below the accepted residual down to this fraction of it, so that converged
// answers sit at round-off, not just inside the tolerance (quadratic convergence makes that one
// extra step).
constexpr double kPolish = 1e-4;

double wrap(double x, double lo, double hi) {
  const double period = hi - lo;
  double r = x - period * std::floor((x - lo) / period);
  return std::clamp(r, lo, hi);
}

// Plane residual along one domain side: Newton on the free parameter only (the other is fixed at
// the bound the 2D iteration ran into).
bool plane_on_side(const NurbsSurface& s, const ParamDomain& d, const Vec3d& n, const Vec3d& p,
                   bool u_fixed, double tol, Vec2d& uv, Vec3d& point) {
  for (int it = 0; it < kMaxNewton; ++it) {
    const SurfaceDerivs dv = evaluate_derivs(s, uv.x, uv.y, 1);
    point = dv.p;
    const double g = dot(n, dv.p - p);
    if (std::abs(g) <= kPolish * tol) return true;
    const double slope = dot(n, u_fixed ? dv.sv : dv.su);
    if (!(std::abs(slope) > 0)) break;
    Vec2d next = uv;
    (u_fixed ? next.y : next.x) -= g / slope;
    next = d.map(next);
    if (next == uv) break;
    uv = next;
  }
  point = evaluate(s, uv.x, uv.y);
  return std::abs(dot(n, point - p)) <= tol;
}

// Fallback when the edge's parameter segment does not bracket the plane (corner positions off
// the surface, a seam or a trim): the point of the section curve nearest the estimate, with the
// curve tangent T = n x N frozen at the start. Equations: n.(S - p) = 0 and T.(S - estimate) = 0.
RefinedPlanePoint plane_nearest(const NurbsSurface& s, const ParamDomain& d, const Vec3d& n,
                                const Vec3d& p, Vec2d uv, const Vec3d& estimate, double tol) {
  RefinedPlanePoint out;
  const SurfaceDerivs d0 = evaluate_derivs(s, uv.x, uv.y, 1);
  const Vec3d tangent = normalized(cross(n, cross(d0.su, d0.sv)));
  if (tangent == Vec3d{}) {
    out.uv = uv;
    out.point = d0.p;
    return out;
  }
  bool clamped_u = false, clamped_v = false;
  for (int it = 0; it < kMaxNewton; ++it) {
    const SurfaceDerivs dv = evaluate_derivs(s, uv.x, uv.y, 1);
    const double f1 = dot(n, dv.p - p);
    const double f2 = dot(tangent, dv.p - estimate);
    if (std::abs(f1) <= kPolish * tol && std::abs(f2) <= kPolish * tol) break;
    const double a = dot(n, dv.su), b = dot(n, dv.sv);
    const double c = dot(tangent, dv.su), e = dot(tangent, dv.sv);
    const double det = a * e - b * c;
    if (!(std::abs(det) > 0)) break;
    const Vec2d raw{uv.x - (f1 * e - f2 * b) / det, uv.y - (a * f2 - c * f1) / det};
    const Vec2d next = d.map(raw);
    clamped_u = next.x != raw.x && !d.closed_u;
    clamped_v = next.y != raw.y && !d.closed_v;
    if (next == uv) break;
    uv = next;
  }
  out.point = evaluate(s, uv.x, uv.y);
  out.uv = uv;
  if (std::abs(dot(n, out.point - p)) <= tol) {
    out.converged = true;
  } else if (clamped_u || clamped_v) {
    out.converged = plane_on_side(s, d, n, p, clamped_u, tol, out.uv, out.point);
  }
  return out;
}

}  // namespace

Vec2d ParamDomain::map(Vec2d uv) const {
  uv.x = closed_u ? wrap(uv.x, u0, u1) : std::clamp(uv.x, u0, u1);
  uv.y = closed_v ? wrap(uv.y, v0, v1) : std::clamp(uv.y, v0, v1);
  return uv;
}

ParamDomain make_domain(const NurbsSurface& s, double tol) {
  ParamDomain d{s.u0, s.u1, s.v0, s.v1, true, true};
  constexpr int kSamples = 5;
  for (int i = 0; i < kSamples; ++i) {
    const double f = (i + 0.5) / kSamples;
    const double v = d.v0 + f * (d.v1 - d.v0);
    const double u = d.u0 + f * (d.u1 - d.u0);
    if (norm(evaluate(s, d.u0, v) - evaluate(s, d.u1, v)) > tol) d.closed_u = false;
    if (norm(evaluate(s, u, d.v0) - evaluate(s, u, d.v1)) > tol) d.closed_v = false;
  }
  return d;
}

void unwrap_corners(const ParamDomain& d, Vec2d* uv, int count) {
  auto unwrap = [&](double Vec2d::*c, double lo, double hi) {
    double mn = kInf, mx = -kInf;
    for (int i = 0; i < count; ++i) {
      mn = std::min(mn, uv[i].*c);
      mx = std::max(mx, uv[i].*c);
    }
    const double period = hi - lo;
    if (mx - mn <= 0.5 * period) return;
    for (int i = 0; i < count; ++i) {
      if (uv[i].*c - lo < 0.5 * period) uv[i].*c += period;
    }
  };
  if (d.closed_u) unwrap(&Vec2d::x, d.u0, d.u1);
  if (d.closed_v) unwrap(&Vec2d::y, d.v0, d.v1);
}

RefinedRay refine_ray(const NurbsSurface& s, const ParamDomain& d, const Vec3d& o, const Vec3d& dir,
                      double t0, Vec2d uv0, double tol) {
  Vec2d uv = d.map(uv0);
  double t = t0;
  RefinedRay best;
  double best_residual = kInf;
  int worse = 0;
  for (int it = 0; it < kMaxNewton; ++it) {
    const SurfaceDerivs dv = evaluate_derivs(s, uv.x, uv.y, 1);
    const Vec3d f = dv.p - (o + t * dir);
    const double residual = norm(f);
    if (residual < best_residual) {
      best_residual = residual;
      best = {t, uv, dv.p, false};
      worse = 0;
    } else if (++worse >= 2) {
      break;  // round-off floor, or clamped against a domain side
    }
    if (residual <= kPolish * tol) break;
    // [su sv -dir] (du, dv, dt) = -f by Cramer's rule.
    const Vec3d c = -dir;
    const double det = dot(dv.su, cross(dv.sv, c));
    if (!(std::abs(det) > 0)) break;
    const Vec3d r = -f;
    const Vec2d next =
        d.map({uv.x + dot(r, cross(dv.sv, c)) / det, uv.y + dot(dv.su, cross(r, c)) / det});
    const double dt = dot(dv.su, cross(dv.sv, r)) / det;
    if (next == uv && dt == 0) break;
    uv = next;
    t += dt;
  }
  best.converged = best_residual <= tol;
  // The parameter of the ray point nearest the surface point (exact when converged).
  best.t = dot(best.point - o, dir) / dot(dir, dir);
  return best;
}

RefinedPlanePoint refine_plane_edge(const NurbsSurface& s, const ParamDomain& d, const Vec3d& n,
                                    const Vec3d& p, Vec2d uv_a, Vec2d uv_b, double s0,
                                    const Vec3d& estimate, double tol) {
  const Vec2d delta = uv_b - uv_a;
  auto at = [&](double f) { return d.map(uv_a + f * delta); };
  // Plain Newton on g(f) = n.(S(uv(f)) - p) from the linear estimate: from a start within the
  // chord error it converges in two or three steps. Leaving the edge or stalling sends it to the
  // bracketed search below.
  double f = std::clamp(s0, 0.0, 1.0);
  for (int it = 0; it < 5; ++it) {
    const Vec2d uv = at(f);
    const SurfaceDerivs dv = evaluate_derivs(s, uv.x, uv.y, 1);
    const double g = dot(n, dv.p - p);
    if (std::abs(g) <= kPolish * tol) return {uv, dv.p, true};
    const double slope = dot(n, dv.su * delta.x + dv.sv * delta.y);
    const double next = f - g / slope;
    if (!(next >= 0 && next <= 1)) break;
    f = next;
  }
  const Vec2d ua = at(0), ub = at(1);
  const Vec3d pa = evaluate(s, ua.x, ua.y), pb = evaluate(s, ub.x, ub.y);
  const double ga = dot(n, pa - p), gb = dot(n, pb - p);
  if (ga == 0) return {ua, pa, true};
  if (gb == 0) return {ub, pb, true};
  if ((ga > 0) == (gb > 0)) {
    return plane_nearest(s, d, n, p, at(std::clamp(s0, 0.0, 1.0)), estimate, tol);
  }
  // Bracketed Newton: Newton steps on g(f) = n.(S(uv(f)) - p), bisection whenever a step leaves
  // the bracket, so it always converges.
  double lo = 0, hi = 1;  // g(lo) has the sign of ga, g(hi) that of gb
  f = std::clamp(s0, 0.0, 1.0);
  if (f <= lo || f >= hi) f = 0.5;
  RefinedPlanePoint best{ua, pa, false};
  double best_g = std::abs(ga);
  if (std::abs(gb) < best_g) {
    best = {ub, pb, false};
    best_g = std::abs(gb);
  }
  for (int it = 0; it < 4 * kMaxNewton; ++it) {
    const Vec2d uv = at(f);
    const SurfaceDerivs dv = evaluate_derivs(s, uv.x, uv.y, 1);
    const double g = dot(n, dv.p - p);
    if (std::abs(g) < best_g) {
      best_g = std::abs(g);
      best = {uv, dv.p, false};
    }
    if (best_g <= kPolish * tol) break;
    ((g > 0) == (ga > 0) ? lo : hi) = f;
    if (hi - lo <= 4 * std::numeric_limits<double>::epsilon()) break;
    const double slope = dot(n, dv.su * delta.x + dv.sv * delta.y);
    double next = slope != 0 ? f - g / slope : lo;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    f = next;
  }
  best.converged = best_g <= tol;
  return best;
}

Vec2d polish_closest(const NurbsSurface& s, const ParamDomain& d, const Vec3d& q, Vec2d uv,
                     const SurfaceDerivs& at_uv, Vec3d& point) {
  SurfaceDerivs dv = at_uv;
  double dist2 = squared_norm(dv.p - q);
  for (int it = 0; it < 4; ++it) {
    const Vec3d r = dv.p - q;
    const double gu = dot(r, dv.su), gv = dot(r, dv.sv);
    const bool fix_u = !d.closed_u && ((uv.x <= d.u0 && gu > 0) || (uv.x >= d.u1 && gu < 0));
    const bool fix_v = !d.closed_v && ((uv.y <= d.v0 && gv > 0) || (uv.y >= d.v1 && gv < 0));
    const double huu = dot(dv.su, dv.su) + dot(r, dv.suu);
    const double huv = dot(dv.su, dv.sv) + dot(r, dv.suv);
    const double hvv = dot(dv.sv, dv.sv) + dot(r, dv.svv);
    Vec2d step;
    if (fix_u && fix_v) break;
    if (fix_u || fix_v) {
      const double h = fix_u ? hvv : huu;
      if (!(h > 0)) break;
      (fix_u ? step.y : step.x) = -(fix_u ? gv : gu) / h;
    } else {
      const double det = huu * hvv - huv * huv;
      if (!(huu > 0 && det > 0)) break;  // not at a minimum's basin: leave it as it is
      step = {(-gu * hvv + gv * huv) / det, (-gv * huu + gu * huv) / det};
    }
    const Vec2d next = d.map(uv + step);
    if (next == uv) break;
    const SurfaceDerivs nd = evaluate_derivs(s, next.x, next.y, 2);
    const double next_dist2 = squared_norm(nd.p - q);
    // Near the answer the distance changes at second order only, below its round-off: allow
    // round-off growth, reject real growth (a step out of the basin).
    if (!(next_dist2 <= dist2 * (1 + 1e-12) + 1e-300)) break;
    uv = next;
    dv = nd;
    dist2 = next_dist2;
  }
  point = dv.p;
  return uv;
}

}  // namespace hm::query
