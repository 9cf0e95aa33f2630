#include "iges/convert_surfaces.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "iges/convert_curves.h"
#include "iges/curve_ops.h"

namespace hm::iges {
namespace {

// Parameter range [a0, a1] checked against the knot range [lo, hi]; equal ends mean "all".
void domain(const Params& p, double a0, double a1, double lo, double hi, const char* dir,
            double& out0, double& out1) {
  if (a0 == a1) {
    a0 = lo;
    a1 = hi;
  }
  const double slack = 1e-6 * (hi - lo);
  if (!(a1 > a0) || a0 < lo - slack || a1 > hi + slack) {
    p.fault(std::string("parameter range in ") + dir + " [" + std::to_string(a0) + ", " +
            std::to_string(a1) + "] is empty or outside the knot range [" + std::to_string(lo) +
            ", " + std::to_string(hi) + "]");
  }
  out0 = std::clamp(a0, lo, hi);
  out1 = std::clamp(a1, lo, hi);
}

NurbsSurface bspline_128(const Context& ctx, const Params& p) {
  p.require(9, "a rational B-spline surface");
  const std::int64_t k1 = p.integer(1), k2 = p.integer(2), m1 = p.integer(3), m2 = p.integer(4);
  if (k1 < 0 || k2 < 0)
    p.fault("negative upper index (K1 = " + std::to_string(k1) + ", K2 = " + std::to_string(k2) +
            ")");
  if (m1 < 1 || m2 < 1)
    p.fault("degree below 1 (M1 = " + std::to_string(m1) + ", M2 = " + std::to_string(m2) + ")");
  const ResourceLimits& lim = ctx.options.limits;
  const std::uint64_t n1 = static_cast<std::uint64_t>(k1) + 1,
                      n2 = static_cast<std::uint64_t>(k2) + 1;
  ctx.check_limit(p.index(), std::max(n1, n2), lim.max_control_points,
                  "control points in one direction", "max_control_points");
  ctx.check_limit(p.index(), n1 * n2, lim.max_control_points, "control points",
                  "max_control_points");
  ctx.check_limit(p.index(), static_cast<std::uint64_t>(std::max(m1, m2)),
                  static_cast<std::uint64_t>(lim.max_degree), "as the degree", "max_degree");
  const std::uint64_t a1 = n1 + static_cast<std::uint64_t>(m1) + 1,
                      a2 = n2 + static_cast<std::uint64_t>(m2) + 1;
  ctx.check_limit(p.index(), std::max(a1, a2), lim.max_knots, "knots", "max_knots");
  if (m1 > k1 || m2 > k2) {
    p.fault("degree larger than the control net: degree (" + std::to_string(m1) + ", " +
            std::to_string(m2) + ") with (" + std::to_string(n1) + " x " + std::to_string(n2) +
            ") control points (degree must be at most the count - 1)");
  }
  const std::size_t n = static_cast<std::size_t>(n1 * n2);
  const std::size_t kw = 10 + a1 + a2;  // first weight
  p.require(kw - 1 + n + 3 * n + 4, "the B-spline surface data");
  NurbsSurface s;
  s.count_u = static_cast<int>(n1);
  s.count_v = static_cast<int>(n2);
  s.degree_u = static_cast<int>(m1);
  s.degree_v = static_cast<int>(m2);
  s.knots_u = read_knots(p, 10, a1, "u");
  s.knots_v = read_knots(p, 10 + a1, a2, "v");
  s.weights = read_weights(p, kw, n);
  if (p.integer(7) == 1) s.weights.assign(n, 1.0);  // PROP3: polynomial
  s.points = read_points(p, kw + n, n);
  s.periodic_u = p.integer(8) == 1;
  s.periodic_v = p.integer(9) == 1;
  const std::size_t kd = kw + 4 * n;
  domain(p, p.real(kd), p.real(kd + 1), s.knots_u[static_cast<std::size_t>(m1)], s.knots_u[n1], "u",
         s.u0, s.u1);
  domain(p, p.real(kd + 2), p.real(kd + 3), s.knots_v[static_cast<std::size_t>(m2)], s.knots_v[n2],
         "v", s.v0, s.v1);
  return s;
}

// Surface from two compatible rows of control points (118 ruled, 122 tabulated): v runs from
// row a (v = 0) to row b (v = 1), degree 1.
NurbsSurface ruled_between(const NurbsCurve& a, const NurbsCurve& b) {
  NurbsSurface s;
  s.degree_u = a.degree;
  s.degree_v = 1;
  s.count_u = a.count();
  s.count_v = 2;
  s.knots_u = a.knots;
  s.knots_v = {0, 0, 1, 1};
  s.points = a.points;
  s.points.insert(s.points.end(), b.points.begin(), b.points.end());
  s.weights = a.weights;
  s.weights.insert(s.weights.end(), b.weights.begin(), b.weights.end());
  s.u0 = a.t0;
  s.u1 = a.t1;
  return s;
}

NurbsSurface ruled_118(const Context& ctx, const Params& p, Diagnostics& notes) {
  p.require(3, "a ruled surface");
  const int i1 = p.pointer(1), i2 = p.pointer(2);
  if (i1 < 0 || i2 < 0) p.fault("ruled surface with a null rail curve");
  NurbsCurve a = convert_single_curve(ctx, i1), b = convert_single_curve(ctx, i2);
  for (NurbsCurve* c : {&a, &b}) {
    clamp_to_range(*c);
    reparametrize(*c, 0, 1);
  }
  if (p.integer(3) == 1) reverse_curve(b);
  if (!make_compatible(a, b, ctx.options.limits.max_control_points)) {
    p.fault("rail curves cannot be made compatible (too many control points)");
  }
  const bool straight = a.degree == 1 && a.count() == 2;
  if (p.entry().form == 0 && !straight) {
    notes.add(Severity::kNote, p.entry().de, p.entry().param_line, 118,
              "ruled surface form 0 (equal relative arc length) joined at equal parameter "
              "values; rulings may differ slightly where the rails are not uniformly "
              "parametrised");
  }
  return ruled_between(a, b);
}

NurbsSurface revolution_120(const Context& ctx, const Params& p) {
  p.require(4, "a surface of revolution");
  const int axis_i = p.pointer_to(1, {110}, "axis");
  const int gen_i = p.pointer(2);
  if (axis_i < 0 || gen_i < 0) p.fault("surface of revolution with a null axis or generatrix");
  const std::vector<NurbsCurve> axis = convert_curve(ctx, axis_i);
  const Vec3d a = axis.front().points.front();
  const Vec3d d = normalized(axis.front().points.back() - a);
  if (d == Vec3d{}) p.fault("the axis line has zero length");
  NurbsCurve g = convert_single_curve(ctx, gen_i);
  clamp_to_range(g);
  const double sa = p.real(3), ta = p.real(4);
  if (!(ta > sa) || ta - sa > 2 * std::numbers::pi + 1e-9) {
    p.fault("start and terminate angles (" + std::to_string(sa) + ", " + std::to_string(ta) +
            ") do not give a sweep in (0, 2 pi]");
  }
  const NurbsCurve unit = rational_arc({}, {1, 0, 0}, {0, 1, 0}, sa, ta);
  NurbsSurface s;
  s.degree_u = g.degree;
  s.degree_v = 2;
  s.count_u = g.count();
  s.count_v = unit.count();
  s.knots_u = g.knots;
  s.knots_v = unit.knots;
  s.u0 = g.t0;
  s.u1 = g.t1;
  s.v0 = sa;
  s.v1 = ta;
  s.points.resize(static_cast<std::size_t>(s.count_u) * static_cast<std::size_t>(s.count_v));
  s.weights.resize(s.points.size());
  for (int j = 0; j < s.count_v; ++j) {
    const Vec3d& q = unit.points[static_cast<std::size_t>(j)];
    for (int i = 0; i < s.count_u; ++i) {
      const Vec3d& pt = g.points[static_cast<std::size_t>(i)];
      const Vec3d o = a + dot(pt - a, d) * d;
      const Vec3d x = pt - o, y = cross(d, x);
      const std::size_t k = static_cast<std::size_t>(i + s.count_u * j);
      s.points[k] = o + q.x * x + q.y * y;
      s.weights[k] =
          g.weights[static_cast<std::size_t>(i)] * unit.weights[static_cast<std::size_t>(j)];
    }
  }
  return s;
}

NurbsSurface tabulated_122(const Context& ctx, const Params& p) {
  p.require(4, "a tabulated cylinder");
  const int di = p.pointer(1);
  if (di < 0) p.fault("tabulated cylinder with a null directrix");
  NurbsCurve c = convert_single_curve(ctx, di);
  clamp_to_range(c);
  reparametrize(c, 0, 1);
  const Vec3d shift = Vec3d{p.real(2), p.real(3), p.real(4)} - c.points.front();
  NurbsCurve top = c;
  for (Vec3d& q : top.points) q += shift;
  return ruled_between(c, top);
}

// Orthonormal frame of a plane with unit normal n; e1 along ref when given.
void plane_frame(const Vec3d& n, const Vec3d* ref, Vec3d& e1, Vec3d& e2) {
  Vec3d r;
  if (ref) r = *ref - dot(*ref, n) * n;
  if (!ref || norm(r) < 1e-12) {
    const Vec3d ax = std::fabs(n.x) < 0.6 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
    r = ax - dot(ax, n) * n;
  }
  e1 = normalized(r);
  e2 = cross(n, e1);
}

// Maps curves into the plane's (u, v) = ((x - o).e1, (x - o).e2): exact, the map is affine.
NurbsCurve to_plane_uv(const NurbsCurve& c, const Vec3d& o, const Vec3d& e1, const Vec3d& e2) {
  NurbsCurve uv = c;
  for (Vec3d& q : uv.points) q = {dot(q - o, e1), dot(q - o, e2), 0};
  return uv;
}

NurbsSurface plane_patch(const Params& p, const Vec3d& o, const Vec3d& e1, const Vec3d& e2,
                         const std::vector<NurbsCurve>& uv_curves) {
  double u0 = HUGE_VAL, u1 = -HUGE_VAL, v0 = HUGE_VAL, v1 = -HUGE_VAL;
  for (const NurbsCurve& c : uv_curves) {
    for (const Vec3d& q : c.points) {
      u0 = std::min(u0, q.x);
      u1 = std::max(u1, q.x);
      v0 = std::min(v0, q.y);
      v1 = std::max(v1, q.y);
    }
  }
  if (!(u1 > u0) || !(v1 > v0)) p.fault("the plane's bounding curves enclose no area");
  NurbsSurface s;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = {u0, u0, u1, u1};
  s.knots_v = {v0, v0, v1, v1};
  s.u0 = u0;
  s.u1 = u1;
  s.v0 = v0;
  s.v1 = v1;
  for (double v : {v0, v1}) {
    for (double u : {u0, u1}) s.points.push_back(o + u * e1 + v * e2);
  }
  s.weights.assign(4, 1.0);
  return s;
}

std::optional<ConvertedSurface> plane_108(const Context& ctx, const Params& p,
                                          const PlaneBounds* bounds) {
  p.require(5, "a plane");
  const Vec3d n0{p.real(1), p.real(2), p.real(3)};
  if (!(norm(n0) > 0)) p.fault("plane with a zero normal (A = B = C = 0)");
  const Vec3d n = normalized(n0);
  const Vec3d o = (p.real(4) / norm(n0)) * n;
  Vec3d e1, e2;
  plane_frame(n, nullptr, e1, e2);
  const int form = p.entry().form;
  const int bi = p.pointer(5);
  ConvertedSurface out;
  std::vector<NurbsCurve> uv;
  if (form == 1 && bi >= 0) {
    for (const NurbsCurve& c : convert_curve(ctx, bi)) uv.push_back(to_plane_uv(c, o, e1, e2));
    out.loops.push_back(TrimLoop{uv, true});
  } else if (form == 0 && bounds) {
    for (const NurbsCurve& c : bounds->model_curves) uv.push_back(to_plane_uv(c, o, e1, e2));
  }
  if (uv.empty()) return std::nullopt;  // unbounded plane, or a hole (form -1)
  out.surface = plane_patch(p, o, e1, e2, uv);
  return out;
}

Vec3d read_116_or_123(const Context& ctx, const Params& p, std::size_t k, int type, bool vector) {
  const int i = p.pointer_to(k, {type}, type == 116 ? "location point" : "direction");
  if (i < 0) p.fault("null pointer to the plane's point or direction");
  ctx.mark(i);
  const Params q(ctx.model, i);
  q.require(3, "a point or direction");
  const Vec3d v{q.real(1), q.real(2), q.real(3)};
  const Affine a = ctx.transforms.of(i);
  return vector ? a.apply(v) - a.apply(Vec3d{}) : a.apply(v);
}

std::optional<ConvertedSurface> plane_190(const Context& ctx, const Params& p,
                                          const PlaneBounds* bounds) {
  p.require(2, "a plane surface");
  const Vec3d o = read_116_or_123(ctx, p, 1, 116, false);
  const Vec3d n = normalized(read_116_or_123(ctx, p, 2, 123, true));
  if (n == Vec3d{}) p.fault("plane surface with a zero normal");
  Vec3d ref, e1, e2;
  const bool has_ref = p.entry().form == 1 && p.has(3);
  if (has_ref) ref = read_116_or_123(ctx, p, 3, 123, true);
  plane_frame(n, has_ref ? &ref : nullptr, e1, e2);
  if (!bounds) return std::nullopt;
  std::vector<NurbsCurve> uv = bounds->uv_curves;
  for (const NurbsCurve& c : bounds->model_curves) uv.push_back(to_plane_uv(c, o, e1, e2));
  if (uv.empty()) return std::nullopt;
  ConvertedSurface out;
  out.surface = plane_patch(p, o, e1, e2, uv);
  return out;
}

// Cubic power-basis coefficients c[a] (of s^a, s in [0, h]) to Bezier ordinates.
void power_to_bezier(const double c[4], double h, double b[4]) {
  const double a0 = c[0], a1 = c[1] * h, a2 = c[2] * h * h, a3 = c[3] * h * h * h;
  b[0] = a0;
  b[1] = a0 + a1 / 3;
  b[2] = a0 + 2 * a1 / 3 + a2 / 3;
  b[3] = a0 + a1 + a2 + a3;
}

NurbsSurface spline_114(const Context& ctx, const Params& p) {
  p.require(4, "a parametric spline surface");
  const std::int64_t m = p.integer(3), n = p.integer(4);
  if (m < 1 || n < 1) p.fault("parametric spline surface with no patches");
  const ResourceLimits& lim = ctx.options.limits;
  ctx.check_limit(p.index(), static_cast<std::uint64_t>(std::max(m, n)), lim.max_knots, "segments",
                  "max_knots");
  const std::uint64_t cu = 3 * static_cast<std::uint64_t>(m) + 1,
                      cv = 3 * static_cast<std::uint64_t>(n) + 1;
  ctx.check_limit(p.index(), cu * cv, lim.max_control_points, "control points",
                  "max_control_points");
  const std::size_t M = static_cast<std::size_t>(m), N = static_cast<std::size_t>(n);
  const std::size_t base = 5 + (M + 1) + (N + 1);
  const std::size_t row = 48 * N + 48;  // each u column of patches is followed by 48 spare values
  p.require(base - 1 + (M - 1) * row + 48 * N, "the spline surface coefficients");
  std::vector<double> tu(M + 1), tv(N + 1);
  for (std::size_t i = 0; i <= M; ++i) tu[i] = p.real(5 + i);
  for (std::size_t j = 0; j <= N; ++j) tv[j] = p.real(5 + M + 1 + j);
  for (std::size_t i = 1; i <= M; ++i)
    if (!(tu[i] > tu[i - 1])) p.fault("u break points do not increase");
  for (std::size_t j = 1; j <= N; ++j)
    if (!(tv[j] > tv[j - 1])) p.fault("v break points do not increase");
  NurbsSurface s;
  s.degree_u = s.degree_v = 3;
  s.count_u = static_cast<int>(cu);
  s.count_v = static_cast<int>(cv);
  s.points.assign(cu * cv, Vec3d{});
  s.weights.assign(cu * cv, 1.0);
  std::vector<int> hits(cu * cv, 0);
  for (std::size_t i = 0; i < M; ++i) {
    for (std::size_t j = 0; j < N; ++j) {
      const std::size_t k0 = base + i * row + 48 * j;
      double bez[3][4][4];  // axis, Bezier index in u, in v
      for (int axis = 0; axis < 3; ++axis) {
        // Coefficient of s^a t^b is number a + 4 b of the axis's 16 (A..D, E..H, K..N, P..S).
        double c[4][4], tmp[4][4];
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b)
            c[a][b] = p.real(k0 + 16 * static_cast<std::size_t>(axis) +
                             static_cast<std::size_t>(a + 4 * b));
        for (int b = 0; b < 4; ++b) {
          const double col[4] = {c[0][b], c[1][b], c[2][b], c[3][b]};
          double out[4];
          power_to_bezier(col, tu[i + 1] - tu[i], out);
          for (int a = 0; a < 4; ++a) tmp[a][b] = out[a];
        }
        for (int a = 0; a < 4; ++a) power_to_bezier(tmp[a], tv[j + 1] - tv[j], bez[axis][a]);
      }
      for (int a = 0; a < 4; ++a) {
        for (int b = 0; b < 4; ++b) {
          const std::size_t gi = 3 * i + static_cast<std::size_t>(a),
                            gj = 3 * j + static_cast<std::size_t>(b);
          s.points[gi + cu * gj] += Vec3d{bez[0][a][b], bez[1][a][b], bez[2][a][b]};
          ++hits[gi + cu * gj];
        }
      }
    }
  }
  // Shared patch edges are averaged (they agree when the spline is continuous).
  for (std::size_t k = 0; k < s.points.size(); ++k) s.points[k] /= hits[k];
  auto knots = [](const std::vector<double>& t) {
    std::vector<double> k(4, t.front());
    for (std::size_t i = 1; i + 1 < t.size(); ++i) k.insert(k.end(), 3, t[i]);
    k.insert(k.end(), 4, t.back());
    return k;
  };
  s.knots_u = knots(tu);
  s.knots_v = knots(tv);
  s.u0 = tu.front();
  s.u1 = tu.back();
  s.v0 = tv.front();
  s.v1 = tv.back();
  return s;
}

}  // namespace

bool is_surface_type(int type) {
  switch (type) {
    case 108:
    case 114:
    case 118:
    case 120:
    case 122:
    case 128:
    case 190:
      return true;
    default:
      return false;
  }
}

void apply(const Affine& a, NurbsSurface& s) {
  if (a.identity) return;
  for (Vec3d& p : s.points) p = a.apply(p);
}

std::optional<ConvertedSurface> convert_surface(const Context& ctx, int index,
                                                const PlaneBounds* bounds, Diagnostics& notes) {
  ctx.mark(index);
  const Params p(ctx.model, index);
  std::optional<ConvertedSurface> out;
  switch (p.entry().type) {
    case 128:
      out = ConvertedSurface{bspline_128(ctx, p), {}};
      break;
    case 118:
      out = ConvertedSurface{ruled_118(ctx, p, notes), {}};
      break;
    case 120:
      out = ConvertedSurface{revolution_120(ctx, p), {}};
      break;
    case 122:
      out = ConvertedSurface{tabulated_122(ctx, p), {}};
      break;
    case 114:
      out = ConvertedSurface{spline_114(ctx, p), {}};
      break;
    case 108:
      out = plane_108(ctx, p, bounds);
      break;
    case 190:
      out = plane_190(ctx, p, bounds);
      break;
    default:
      p.fault("type " + std::to_string(p.entry().type) + " is not a supported surface");
  }
  if (!out) return out;
  apply(ctx.transforms.of(index), out->surface);
  for (const Vec3d& q : out->surface.points) {
    if (!is_finite(q)) p.fault("control point coordinates overflow after the transformation");
  }
  return out;
}

std::size_t own_parameter_count(const Params& p) {
  try {
    switch (p.entry().type) {
      case 128: {
        const std::int64_t k1 = p.integer(1), k2 = p.integer(2), m1 = p.integer(3),
                           m2 = p.integer(4);
        if (k1 < 0 || k2 < 0 || m1 < 0 || m2 < 0 || k1 > (1 << 30) || k2 > (1 << 30)) return 0;
        return static_cast<std::size_t>(9 + (k1 + m1 + 2) + (k2 + m2 + 2) +
                                        4 * (k1 + 1) * (k2 + 1) + 4);
      }
      case 118:
      case 120:
      case 122:
        return 4;
      case 108:
        return 9;
      case 190:
        return p.entry().form == 1 ? 3 : 2;
      case 143:
      case 510: {
        const std::int64_t n = p.integer(p.entry().type == 143 ? 3 : 2);
        return n < 0 || n > (1 << 30) ? 0 : static_cast<std::size_t>(3 + n);
      }
      case 144: {
        const std::int64_t n2 = p.integer(3);
        return n2 < 0 || n2 > (1 << 30) ? 0 : static_cast<std::size_t>(4 + n2);
      }
      case 402: {
        const std::int64_t n = p.integer(1);
        return n < 0 || n > (1 << 30) ? 0 : static_cast<std::size_t>(1 + n);
      }
      default:
        return 0;
    }
  } catch (const EntityFault&) {
    return 0;
  }
}

}  // namespace hm::iges
