#include "iges/convert_curves.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "iges/curve_ops.h"
#include "iges/work_budget.h"

namespace hm::iges {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

NurbsCurve polyline(std::vector<Vec3d> pts) {
  NurbsCurve c;
  c.degree = 1;
  const std::size_t n = pts.size();
  c.knots.reserve(n + 2);
  c.knots.push_back(0);
  for (std::size_t i = 0; i < n; ++i) c.knots.push_back(static_cast<double>(i));
  c.knots.push_back(static_cast<double>(n - 1));
  c.points = std::move(pts);
  c.weights.assign(n, 1.0);
  c.t0 = 0;
  c.t1 = static_cast<double>(n - 1);
  return c;
}

// A polyline through f on [t0, t1] with chord deviation under tol (midpoint test), at most
// 2^12 segments.
NurbsCurve sample_function(const std::function<Vec3d(double)>& f, double t0, double t1,
                           double tol) {
  std::vector<Vec3d> pts{f(t0)};
  std::function<void(double, double, const Vec3d&, const Vec3d&, int)> rec =
      [&](double a, double b, const Vec3d& pa, const Vec3d& pb, int depth) {
        const double m = 0.5 * (a + b);
        const Vec3d pm = f(m);
        if (depth < 12 && (depth < 3 || norm(pm - 0.5 * (pa + pb)) > tol)) {
          rec(a, m, pa, pm, depth + 1);
          rec(m, b, pm, pb, depth + 1);
        } else {
          pts.push_back(pb);
        }
      };
  rec(t0, t1, pts.front(), f(t1), 0);
  return polyline(std::move(pts));
}

NurbsCurve line_110(const Params& p) {
  p.require(6, "a line");
  return polyline({{p.real(1), p.real(2), p.real(3)}, {p.real(4), p.real(5), p.real(6)}});
}

NurbsCurve arc_100(const Params& p) {
  p.require(7, "a circular arc");
  const double zt = p.real(1);
  const Vec3d c{p.real(2), p.real(3), zt};
  const Vec3d a{p.real(4), p.real(5), zt};
  const Vec3d b{p.real(6), p.real(7), zt};
  const double r = norm(a - c);
  if (!(r > 0)) p.fault("circular arc of zero radius");
  const double th0 = std::atan2(a.y - c.y, a.x - c.x);
  double th1 = std::atan2(b.y - c.y, b.x - c.x);
  // Counter-clockwise from start to end; coincident ends make a full circle.
  while (th1 <= th0 + 1e-12) th1 += kTwoPi;
  if (norm(b - a) <= 1e-12 * r) th1 = th0 + kTwoPi;
  return rational_arc(c, {r, 0, 0}, {0, r, 0}, th0, th1);
}

// Symmetric 2x2 eigen-frame: e1 along the eigenvalue l1, e2 = e1 rotated by +90 degrees.
void eigen2(double a, double b, double c, double& l1, double& l2, Vec3d& e1, Vec3d& e2) {
  const double phi = 0.5 * std::atan2(2 * b, a - c);
  e1 = {std::cos(phi), std::sin(phi), 0};
  e2 = {-e1.y, e1.x, 0};
  l1 = a * e1.x * e1.x + 2 * b * e1.x * e1.y + c * e1.y * e1.y;
  l2 = a * e2.x * e2.x + 2 * b * e2.x * e2.y + c * e2.y * e2.y;
}

NurbsCurve conic_104(const Params& p, double tol_rel) {
  p.require(11, "a conic arc");
  const double A = p.real(1), B = p.real(2), C = p.real(3), D = p.real(4), E = p.real(5),
               F = p.real(6), zt = p.real(7);
  const Vec3d s{p.real(8), p.real(9), 0}, t{p.real(10), p.real(11), 0};
  double l1, l2;
  Vec3d e1, e2;
  eigen2(A, 0.5 * B, C, l1, l2, e1, e2);
  const double scale = std::max({std::fabs(l1), std::fabs(l2), 1e-300});
  const Vec3d z{0, 0, zt};
  if (std::fabs(l1) < 1e-12 * scale || std::fabs(l2) < 1e-12 * scale) {
    // Parabola: in the eigen-frame, y' is a quadratic polynomial of x' (exact Bezier).
    if (std::fabs(l1) < std::fabs(l2)) {
      std::swap(l1, l2);
      std::swap(e1, e2);
      e2 = -e2;
    }
    const double dx = D * e1.x + E * e1.y, dy = D * e2.x + E * e2.y;
    if (std::fabs(dy) < 1e-300) p.fault("degenerate parabola");
    auto y = [&](double x) { return -(l1 * x * x + dx * x + F) / dy; };
    auto dydx = [&](double x) { return -(2 * l1 * x + dx) / dy; };
    const double x0 = dot(s, e1), x1 = dot(t, e1);
    const double xm = 0.5 * (x0 + x1);
    const Vec3d p0 = x0 * e1 + y(x0) * e2 + z, p2 = x1 * e1 + y(x1) * e2 + z;
    const Vec3d p1 = xm * e1 + (y(x0) + dydx(x0) * 0.5 * (x1 - x0)) * e2 + z;
    NurbsCurve c;
    c.degree = 2;
    c.knots = {0, 0, 0, 1, 1, 1};
    c.points = {p0, p1, p2};
    c.weights = {1, 1, 1};
    return c;
  }
  // Centre, then lambda1 x'^2 + lambda2 y'^2 + f = 0 around it.
  const double det = A * C - 0.25 * B * B;
  const double cx = (-0.5 * D * C + 0.25 * B * E) / det, cy = (-0.5 * E * A + 0.25 * B * D) / det;
  const double f = A * cx * cx + B * cx * cy + C * cy * cy + D * cx + E * cy + F;
  const Vec3d ctr{cx, cy, 0};
  const Vec3d ls = s - ctr, lt = t - ctr;
  if (l1 * l2 > 0) {
    const double a2 = -f / l1, b2 = -f / l2;
    if (!(a2 > 0 && b2 > 0)) p.fault("conic coefficients do not describe a real ellipse");
    const double a = std::sqrt(a2), b = std::sqrt(b2);
    const double th0 = std::atan2(dot(ls, e2) / b, dot(ls, e1) / a);
    double th1 = std::atan2(dot(lt, e2) / b, dot(lt, e1) / a);
    while (th1 <= th0 + 1e-12) th1 += kTwoPi;
    if (norm(t - s) <= 1e-12 * std::max(a, b)) th1 = th0 + kTwoPi;
    return rational_arc(ctr + z, a * e1, b * e2, th0, th1);
  }
  // Hyperbola: put the transverse axis on e1, then sample x' = +-a cosh(u), y' = b sinh(u).
  if (-f / l1 < 0) {
    std::swap(l1, l2);
    std::swap(e1, e2);
    e2 = -e2;
  }
  const double a = std::sqrt(-f / l1), b = std::sqrt(f / l2);
  if (!(a > 0 && b > 0)) p.fault("conic coefficients do not describe a real hyperbola");
  const double branch = dot(ls, e1) < 0 ? -1.0 : 1.0;
  const double u0 = std::asinh(dot(ls, e2) / b), u1 = std::asinh(dot(lt, e2) / b);
  auto at = [&](double u) {
    return ctr + z + branch * a * std::cosh(u) * e1 + b * std::sinh(u) * e2;
  };
  const double size = std::max({norm(at(u0) - at(u1)), a, b});
  return sample_function(at, u0, u1, tol_rel * size);
}

NurbsCurve copious_106(const Context& ctx, const Params& p) {
  const int ip = p.bounded(1, 1, 3, "copious data interpretation flag IP");
  const std::int64_t n = p.integer(2);
  if (n < 2) p.fault("copious data with " + std::to_string(n) + " points cannot form a curve");
  ctx.check_limit(p.index(), static_cast<std::uint64_t>(n), ctx.options.limits.max_control_points,
                  "points", "max_control_points");
  const std::uint64_t stride = ip == 1 ? 2 : (ip == 2 ? 3 : 6);
  const std::size_t first = ip == 1 ? 4 : 3;
  p.require(first - 1 + stride * static_cast<std::uint64_t>(n), "the copious data points");
  const double zt = ip == 1 ? p.real(3) : 0.0;
  std::vector<Vec3d> pts(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const std::size_t k = first + stride * i;
    pts[i] = {p.real(k), p.real(k + 1), ip == 1 ? zt : p.real(k + 2)};
  }
  if (p.entry().form == 63 && !(pts.front() == pts.back())) pts.push_back(pts.front());
  return polyline(std::move(pts));
}

NurbsCurve spline_112(const Context& ctx, const Params& p) {
  p.require(4, "a parametric spline curve");
  const std::int64_t n = p.integer(4);
  if (n < 1) p.fault("parametric spline with " + std::to_string(n) + " segments");
  ctx.check_limit(p.index(), static_cast<std::uint64_t>(n), ctx.options.limits.max_knots,
                  "segments", "max_knots");
  const std::size_t segs = static_cast<std::size_t>(n);
  p.require(4 + (segs + 1) + 12 * segs, "the spline coefficients");
  std::vector<double> breaks(segs + 1);
  for (std::size_t i = 0; i <= segs; ++i) {
    breaks[i] = p.real(5 + i);
    if (i > 0 && !(breaks[i] > breaks[i - 1]))
      p.fault("parametric spline break points do not increase");
  }
  NurbsCurve c;
  c.degree = 3;
  c.points.assign(3 * segs + 1, Vec3d{});
  c.weights.assign(3 * segs + 1, 1.0);
  std::vector<int> hits(3 * segs + 1, 0);
  const std::size_t base = 5 + segs + 1;
  for (std::size_t i = 0; i < segs; ++i) {
    const double h = breaks[i + 1] - breaks[i];
    double bez[4][3];
    for (int axis = 0; axis < 3; ++axis) {
      double a[4];
      for (int k = 0; k < 4; ++k)
        a[k] = p.real(base + 12 * i + 4 * static_cast<std::size_t>(axis) +
                      static_cast<std::size_t>(k)) *
               std::pow(h, k);
      bez[0][axis] = a[0];
      bez[1][axis] = a[0] + a[1] / 3;
      bez[2][axis] = a[0] + 2 * a[1] / 3 + a[2] / 3;
      bez[3][axis] = a[0] + a[1] + a[2] + a[3];
    }
    for (int k = 0; k < 4; ++k) {
      c.points[3 * i + static_cast<std::size_t>(k)] += Vec3d{bez[k][0], bez[k][1], bez[k][2]};
      ++hits[3 * i + static_cast<std::size_t>(k)];
    }
  }
  for (std::size_t i = 0; i < c.points.size(); ++i) c.points[i] /= hits[i];
  c.knots.assign(4, breaks.front());
  for (std::size_t i = 1; i < segs; ++i) c.knots.insert(c.knots.end(), 3, breaks[i]);
  c.knots.insert(c.knots.end(), 4, breaks.back());
  c.t0 = breaks.front();
  c.t1 = breaks.back();
  return c;
}

NurbsCurve bspline_126(const Context& ctx, const Params& p) {
  p.require(6, "a rational B-spline curve");
  const std::int64_t k = p.integer(1), m = p.integer(2);
  if (m < 1) p.fault("degree " + std::to_string(m) + " (must be at least 1)");
  if (k < 0) p.fault("negative upper index K = " + std::to_string(k));
  const ResourceLimits& lim = ctx.options.limits;
  ctx.check_limit(p.index(), static_cast<std::uint64_t>(k) + 1, lim.max_control_points,
                  "control points", "max_control_points");
  ctx.check_limit(p.index(), static_cast<std::uint64_t>(m),
                  static_cast<std::uint64_t>(lim.max_degree), "as the degree", "max_degree");
  if (m > k) {
    p.fault("degree " + std::to_string(m) + " is larger than the control net allows (" +
            std::to_string(k + 1) + " control points need degree <= " + std::to_string(k) + ")");
  }
  const std::size_t n = static_cast<std::size_t>(k) + 1, deg = static_cast<std::size_t>(m);
  const std::size_t nk = n + deg + 1;
  ctx.check_limit(p.index(), nk, lim.max_knots, "knots", "max_knots");
  p.require(6 + nk + n + 3 * n + 2, "the B-spline data");
  const bool polynomial = p.integer(5) == 1;
  NurbsCurve c;
  c.degree = static_cast<int>(m);
  c.knots = read_knots(p, 7, nk, "the");
  c.weights = read_weights(p, 7 + nk, n);
  if (polynomial) c.weights.assign(n, 1.0);
  c.points = read_points(p, 7 + nk + n, n);
  c.periodic = p.integer(6) == 1;
  const double lo = c.knots[deg], hi = c.knots[n];
  if (!(hi > lo)) p.fault("the knot vector leaves an empty parameter range");
  double v0 = p.real(7 + nk + 4 * n), v1 = p.real(8 + nk + 4 * n);
  const double slack = 1e-6 * (hi - lo);
  if (!(v1 > v0) || v0 < lo - slack || v1 > hi + slack) {
    // Some writers leave V0 = V1 = 0; the knot range is then what they meant.
    if (v0 == v1) {
      v0 = lo;
      v1 = hi;
    } else {
      p.fault("parameter range [" + std::to_string(v0) + ", " + std::to_string(v1) +
              "] is outside the knot range [" + std::to_string(lo) + ", " + std::to_string(hi) +
              "]");
    }
  }
  c.t0 = std::clamp(v0, lo, hi);
  c.t1 = std::clamp(v1, lo, hi);
  if (!(c.t1 > c.t0)) p.fault("empty parameter range");
  return c;
}

}  // namespace

bool is_curve_type(int type) {
  switch (type) {
    case 100:
    case 102:
    case 104:
    case 106:
    case 110:
    case 112:
    case 126:
      return true;
    default:
      return false;
  }
}

void apply(const Affine& a, NurbsCurve& c) {
  if (a.identity) return;
  for (Vec3d& p : c.points) p = a.apply(p);
}

std::vector<NurbsCurve> convert_curve(const Context& ctx, int index, int depth) {
  ctx.mark(index);
  const Params p(ctx.model, index);
  const DirEntry& e = p.entry();
  std::vector<NurbsCurve> out;
  switch (e.type) {
    case 100:
      out.push_back(arc_100(p));
      break;
    case 104:
      out.push_back(conic_104(p, std::max(ctx.options.trim_tolerance, 1e-9)));
      break;
    case 106:
      out.push_back(copious_106(ctx, p));
      break;
    case 110:
      out.push_back(line_110(p));
      break;
    case 112:
      out.push_back(spline_112(ctx, p));
      break;
    case 126:
      out.push_back(bspline_126(ctx, p));
      break;
    case 102: {
      if (static_cast<std::uint64_t>(depth) >= ctx.options.limits.max_pointer_depth) {
        p.fault("composite curves nested deeper than " +
                std::to_string(ctx.options.limits.max_pointer_depth) +
                " levels (a cycle?) (limit max_pointer_depth)");
      }
      const std::int64_t n = p.integer(1);
      if (n < 1) p.fault("composite curve with " + std::to_string(n) + " members");
      p.require(1 + static_cast<std::uint64_t>(n), "the composite curve members");
      for (std::int64_t k = 0; k < n; ++k) {
        const int member = p.pointer(2 + static_cast<std::size_t>(k));
        if (member < 0) p.fault("null member in a composite curve");
        const int t = ctx.entry(member).type;
        if (t == 116) continue;  // points are allowed as members; they carry no curve
        if (!is_curve_type(t))
          p.fault("composite member DE " + std::to_string(2 * member + 1) + " of type " +
                  std::to_string(t) + " is not a curve");
        std::vector<NurbsCurve> part = convert_curve(ctx, member, depth + 1);
        for (NurbsCurve& c : part) out.push_back(std::move(c));
      }
      if (out.empty()) p.fault("composite curve without curves");
      break;
    }
    default:
      p.fault("type " + std::to_string(e.type) + " is not a supported curve");
  }
  WorkBudget& budget = job_budget();
  for (const NurbsCurve& c : out) budget.curve_units += c.points.size() + kCurveOverhead;
  const std::uint64_t cap = max_curve_units(ctx.options.limits.max_control_points);
  if (budget.curve_units > cap) {
    p.fault("curve data expands past " + std::to_string(cap) +
            " units for one entity (composite curves sharing members?)");
  }
  const Affine a = ctx.transforms.of(index);
  for (NurbsCurve& c : out) {
    apply(a, c);
    for (const Vec3d& q : c.points) {
      if (!is_finite(q)) p.fault("curve coordinates overflow (not finite)");
    }
  }
  return out;
}

NurbsCurve convert_single_curve(const Context& ctx, int index) {
  const std::vector<NurbsCurve> chain = convert_curve(ctx, index);
  NurbsCurve c;
  if (!join_chain(chain, ctx.options.limits.max_control_points, c)) {
    throw EntityFault(index, "the curve is too large to join into one B-spline");
  }
  return c;
}

}  // namespace hm::iges
