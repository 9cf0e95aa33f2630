// Trim-loop sampling and patch areas.
//
// Area accuracy. Untrimmed: on every knot-span cell a tensor Gauss-Legendre rule of order
// max(degree_u, degree_v) + 4 (at least 6) is accepted when the rule two orders lower agrees with
// it to 1e-11 (relative to the cell, or to its share of the patch); otherwise the cell is split in
// four, at most 6 levels. The accepted higher-order value is far more accurate than the test, so
// smooth patches come out near 1e-12 relative (exact to rounding for polynomial area elements).
// Trimmed: the loops are sampled to 1e-7 of the parameter domain (each direction scaled to
// [0, 1]); cells untouched by a loop are integrated as above, and each span cell a loop crosses is
// integrated over the loop polygons clipped to it (Sutherland-Hodgman) with a fan of triangles
// from the cell centre. The error is then that of the sampled polygon: about (2/3) 1e-7 x (loop
// length in the scaled domain) x (mean area element) x (domain area), typically 1e-7 relative.
#include "nurbs/patch.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"
#include "nurbs/basis.h"
#include "nurbs/evaluate_grid.h"
#include "nurbs/gauss_legendre.h"

namespace hm {
namespace {

constexpr double kAreaLoopTolerance = 1e-7;  // chord tolerance in the unit-scaled domain
constexpr int kMaxAdaptiveDepth = 6;
constexpr int kMaxTrimDepth = 4;  // crossed cells: at most this many levels below a span cell

struct Cell {
  double u0, u1, v0, v1;
  double area() const { return (u1 - u0) * (v1 - v0); }
};

// A loop polygon clipped to a cell, with its weight in the region's indicator function.
struct SignedPolygon {
  std::vector<Vec2d> pts;
  double sign = 1;
};

double signed_area(const std::vector<Vec2d>& pts) {
  double a = 0;
  for (std::size_t i = 0, n = pts.size(); i < n; ++i) a += cross(pts[i], pts[(i + 1) % n]);
  return 0.5 * a;
}

bool point_in_polygon(const Vec2d& p, const std::vector<Vec2d>& pts) {
  bool inside = false;
  for (std::size_t i = 0, n = pts.size(), j = n - 1; i < n; j = i++) {
    const Vec2d& a = pts[i];
    const Vec2d& b = pts[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) {
      inside = !inside;
    }
  }
  return inside;
}

// Sutherland-Hodgman against one half-plane: axis 0 clips x, 1 clips y; keep >= c when upper is
// false, <= c otherwise. Intersections get the clip coordinate exactly, so edges along the cell
// boundary are recognisable.
std::vector<Vec2d> clip_half(const std::vector<Vec2d>& in, int axis, double c, bool upper) {
  std::vector<Vec2d> out;
  if (in.empty()) return out;
  out.reserve(in.size() + 4);
  auto coord = [axis](const Vec2d& p) { return axis == 0 ? p.x : p.y; };
  auto inside = [&](const Vec2d& p) { return upper ? coord(p) <= c : coord(p) >= c; };
  auto cut = [&](const Vec2d& p, const Vec2d& q) {
    const double t = (c - coord(p)) / (coord(q) - coord(p));
    return axis == 0 ? Vec2d{c, p.y + t * (q.y - p.y)} : Vec2d{p.x + t * (q.x - p.x), c};
  };
  for (std::size_t i = 0, n = in.size(); i < n; ++i) {
    const Vec2d& p = in[(i + n - 1) % n];
    const Vec2d& q = in[i];
    const bool pin = inside(p);
    const bool qin = inside(q);
    if (pin && qin) {
      out.push_back(q);
    } else if (pin) {
      out.push_back(cut(p, q));
    } else if (qin) {
      out.push_back(cut(p, q));
      out.push_back(q);
    }
  }
  return out;
}

std::vector<Vec2d> clip_to_cell(std::vector<Vec2d> pts, const Cell& c) {
  pts = clip_half(pts, 0, c.u0, false);
  pts = clip_half(pts, 0, c.u1, true);
  pts = clip_half(pts, 1, c.v0, false);
  return clip_half(pts, 1, c.v1, true);
}

// True when some edge of the clipped polygon runs through the cell's interior (not along one of
// its sides).
bool crosses_cell(const std::vector<Vec2d>& pts, const Cell& c) {
  for (std::size_t i = 0, n = pts.size(); i < n; ++i) {
    const Vec2d& a = pts[i];
    const Vec2d& b = pts[(i + 1) % n];
    const bool on_side = (a.x == c.u0 && b.x == c.u0) || (a.x == c.u1 && b.x == c.u1) ||
                         (a.y == c.v0 && b.y == c.v0) || (a.y == c.v1 && b.y == c.v1);
    if (!on_side && !(a == b)) return true;
  }
  return false;
}

// Breaks strictly inside (lo, hi) of a sorted list.
std::pair<std::size_t, std::size_t> inner_breaks(const std::vector<double>& b, double lo,
                                                 double hi) {
  const auto first = std::upper_bound(b.begin(), b.end(), lo);
  const auto last = std::lower_bound(first, b.end(), hi);
  return {static_cast<std::size_t>(first - b.begin()), static_cast<std::size_t>(last - b.begin())};
}

class AreaIntegrator {
 public:
  AreaIntegrator(const NurbsSurface& s, double rel_tol)
      : rel_tol_(rel_tol),
        arrays_(surface_arrays(s)),
        breaks_u_(span_breaks_u(s)),
        breaks_v_(span_breaks_v(s)),
        hi_(gauss_legendre_01(std::clamp(std::max(s.degree_u, s.degree_v) + 4, 6, 24))),
        lo_(gauss_legendre_01(static_cast<int>(hi_.nodes.size()) - 2)),
        edge_(gauss_legendre_01(3)) {
    // Mean area element on a coarse grid: the scale of the absolute error budget.
    const Cell domain{s.u0, s.u1, s.v0, s.v1};
    density_ = gauss(domain, lo_) / domain.area();
  }

  const std::vector<double>& breaks_u() const { return breaks_u_; }
  const std::vector<double>& breaks_v() const { return breaks_v_; }

  double jacobian(double u, double v) const {
    Vec3d d[3];
    kernel::surface_derivs(arrays_, u, v, 1, d);
    return norm(cross(d[1], d[2]));
  }

  // Tensor Gauss rule on a cell, evaluated as a grid (basis functions computed once per row).
  double gauss(const Cell& c, const GaussRule& rule) const {
    const std::size_t n = rule.nodes.size();
    std::vector<double> us(n), vs(n);
    for (std::size_t i = 0; i < n; ++i) {
      us[i] = c.u0 + (c.u1 - c.u0) * rule.nodes[i];
      vs[i] = c.v0 + (c.v1 - c.v0) * rule.nodes[i];
    }
    kernel::BasisTable bu, bv;
    kernel::basis_table(arrays_.degree_u, arrays_.count_u, arrays_.knots_u, us, 1, bu);
    kernel::basis_table(arrays_.degree_v, arrays_.count_v, arrays_.knots_v, vs, 1, bv);
    std::vector<Vec3d> d(3 * n * n);
    kernel::surface_grid_derivs(arrays_, bu, bv, 1, d);
    double sum = 0;
    for (std::size_t j = 0; j < n; ++j) {
      double row = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t k = 3 * (i + n * j);
        row += rule.weights[i] * norm(cross(d[k + 1], d[k + 2]));
      }
      sum += rule.weights[j] * row;
    }
    return sum * c.area();
  }

  // Adaptive Gauss over a cell inside one knot span: the high-order rule is accepted when the
  // lower-order one agrees with it to rel_tol_ (of the cell's value or of its share of the patch).
  double span_cell(const Cell& c, int depth = 0) const {
    const double hi = gauss(c, hi_);
    const double lo = gauss(c, lo_);
    const double budget = rel_tol_ * std::max(std::abs(hi), density_ * c.area());
    if (depth >= kMaxAdaptiveDepth || std::abs(hi - lo) <= budget) return hi;
    const double um = 0.5 * (c.u0 + c.u1);
    const double vm = 0.5 * (c.v0 + c.v1);
    return span_cell({c.u0, um, c.v0, vm}, depth + 1) + span_cell({um, c.u1, c.v0, vm}, depth + 1) +
           span_cell({c.u0, um, vm, c.v1}, depth + 1) + span_cell({um, c.u1, vm, c.v1}, depth + 1);
  }

  // Any cell: split at the knot breaks inside it, then adaptive Gauss per span cell.
  double untrimmed(const Cell& c) const {
    const auto [bu0, bu1] = inner_breaks(breaks_u_, c.u0, c.u1);
    const auto [bv0, bv1] = inner_breaks(breaks_v_, c.v0, c.v1);
    std::vector<double> us{c.u0}, vs{c.v0};
    us.insert(us.end(), breaks_u_.begin() + bu0, breaks_u_.begin() + bu1);
    vs.insert(vs.end(), breaks_v_.begin() + bv0, breaks_v_.begin() + bv1);
    us.push_back(c.u1);
    vs.push_back(c.v1);
    const std::size_t nu = us.size() - 1;
    const std::size_t cells = nu * (vs.size() - 1);
    std::vector<double> parts(cells);
    parallel_for(
        0, cells,
        [&](std::size_t k) {
          const std::size_t i = k % nu;
          const std::size_t j = k / nu;
          parts[k] = span_cell({us[i], us[i + 1], vs[j], vs[j + 1]});
        },
        16);
    double sum = 0;
    for (const double p : parts) sum += p;
    return sum;
  }

  // Integral of the area element over a closed polygon (winding-number weighted), by a fan of
  // triangles from the cell centre o. Triangle (o, a, b) is P(r, s) = o + r (a + s (b - a)) with
  // Jacobian r cross(a, b), integrated by the high-order rule in r. Across (in s) a long edge
  // gets the same rule, and `lo` receives the sum with the lower-order rule in both directions
  // (the error estimate). A short edge (under 10% of the cell in each direction, as the edges of
  // a finely sampled curve) gets a 3-point rule across, exact to O((|b - a| / cell)^6), and adds
  // the same value to both sums.
  double fan(const std::vector<Vec2d>& pts, const Cell& c, double& lo) const {
    const Vec2d o{0.5 * (c.u0 + c.u1), 0.5 * (c.v0 + c.v1)};
    const double cw = c.u1 - c.u0;
    const double ch = c.v1 - c.v0;
    double hi = 0;
    lo = 0;
    for (std::size_t e = 0, n = pts.size(); e < n; ++e) {
      const Vec2d a = pts[e] - o;
      const Vec2d b = pts[(e + 1) % n] - o;
      const double twice_area = cross(a, b);
      if (twice_area == 0) continue;
      const Vec2d ab = b - a;
      if (std::abs(ab.x) <= 0.1 * cw && std::abs(ab.y) <= 0.1 * ch) {
        const double t = twice_area * triangle(o, a, ab, hi_, edge_);
        hi += t;
        lo += t;
      } else {
        hi += twice_area * triangle(o, a, ab, hi_, hi_);
        lo += twice_area * triangle(o, a, ab, lo_, lo_);
      }
    }
    return hi;
  }

  // The integral over (r, s) in [0, 1]^2 of r J(o + r (a + s ab)).
  double triangle(const Vec2d& o, const Vec2d& a, const Vec2d& ab, const GaussRule& radial,
                  const GaussRule& across) const {
    double tri = 0;
    for (std::size_t i = 0; i < radial.nodes.size(); ++i) {
      const double r = radial.nodes[i];
      double row = 0;
      for (std::size_t j = 0; j < across.nodes.size(); ++j) {
        const Vec2d p = o + r * (a + across.nodes[j] * ab);
        row += across.weights[j] * jacobian(p.x, p.y);
      }
      tri += radial.weights[i] * r * row;
    }
    return tri;
  }

  // Trimmed integral over a cell: `polys` are the loops clipped to the cell, `w` the indicator
  // weight already known to cover the whole cell, `span_depth` the levels below a span cell.
  double trimmed(const Cell& c, std::vector<SignedPolygon> polys, double w, int span_depth) const {
    std::vector<SignedPolygon> crossing;
    for (auto& p : polys) {
      if (p.pts.size() < 3) continue;
      if (crosses_cell(p.pts, c)) {
        crossing.push_back(std::move(p));
      } else {
        w += p.sign * std::round(signed_area(p.pts) / c.area());
      }
    }
    if (crossing.empty()) return w == 0 ? 0.0 : w * untrimmed(c);

    std::vector<Cell> kids;
    const auto [bu0, bu1] = inner_breaks(breaks_u_, c.u0, c.u1);
    const auto [bv0, bv1] = inner_breaks(breaks_v_, c.v0, c.v1);
    if (bu1 > bu0 || bv1 > bv0) {
      // Split at the middle knot break of the direction with more breaks.
      if (bu1 - bu0 >= bv1 - bv0) {
        const double b = breaks_u_[(bu0 + bu1) / 2];
        kids = {{c.u0, b, c.v0, c.v1}, {b, c.u1, c.v0, c.v1}};
      } else {
        const double b = breaks_v_[(bv0 + bv1) / 2];
        kids = {{c.u0, c.u1, c.v0, b}, {c.u0, c.u1, b, c.v1}};
      }
    } else {
      // A leaf inside one span when the fan rules of two orders agree; otherwise split in four.
      double hi = 0;
      double lo = 0;
      for (const auto& p : crossing) {
        double lo_p;
        hi += p.sign * fan(p.pts, c, lo_p);
        lo += p.sign * lo_p;
      }
      const double budget = rel_tol_ * std::max(std::abs(hi), density_ * c.area());
      if (span_depth >= kMaxTrimDepth || std::abs(hi - lo) <= budget) {
        return (w == 0 ? 0.0 : w * span_cell(c)) + hi;
      }
      const double um = 0.5 * (c.u0 + c.u1);
      const double vm = 0.5 * (c.v0 + c.v1);
      kids = {
          {c.u0, um, c.v0, vm}, {um, c.u1, c.v0, vm}, {c.u0, um, vm, c.v1}, {um, c.u1, vm, c.v1}};
      ++span_depth;
    }
    double sum = 0;
    for (const Cell& k : kids) {
      std::vector<SignedPolygon> clipped;
      for (const auto& p : crossing) {
        SignedPolygon q{clip_to_cell(p.pts, k), p.sign};
        if (q.pts.size() >= 3) clipped.push_back(std::move(q));
      }
      sum += trimmed(k, std::move(clipped), w, span_depth);
    }
    return sum;
  }

 private:
  double rel_tol_;
  kernel::SurfaceArrays arrays_;
  std::vector<double> breaks_u_;
  std::vector<double> breaks_v_;
  GaussRule hi_;
  GaussRule lo_;
  GaussRule edge_;
  double density_ = 0;
};

// The loop as a polygon: its curves sampled and chained, joint duplicates dropped. `scale_u`,
// `scale_v` map the curves into the space where the chord tolerance applies.
std::vector<Vec2d> sample_loop(const TrimLoop& loop, double tol, double origin_u, double origin_v,
                               double scale_u, double scale_v) {
  std::vector<Vec2d> poly;
  for (const NurbsCurve& curve : loop.curves_uv) {
    NurbsCurve scaled = curve;
    for (Vec3d& p : scaled.points) {
      p = {(p.x - origin_u) * scale_u, (p.y - origin_v) * scale_v, 0.0};
    }
    const std::vector<Vec3d> pts = sample_curve(scaled, tol);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Vec2d q{pts[i].x / scale_u + origin_u, pts[i].y / scale_v + origin_v};
      if (i == 0 && !poly.empty()) {
        const Vec2d d = q - poly.back();
        if (norm(Vec2d{d.x * scale_u, d.y * scale_v}) <= tol) continue;
      }
      poly.push_back(q);
    }
  }
  if (poly.size() > 1) {
    const Vec2d d = poly.back() - poly.front();
    if (norm(Vec2d{d.x * scale_u, d.y * scale_v}) <= tol) poly.pop_back();
  }
  return poly;
}

}  // namespace

const char* to_string(Wrapping w) {
  switch (w) {
    case Wrapping::kPlain:
      return "plain";
    case Wrapping::kBounded:
      return "bounded";
    case Wrapping::kTrimmed:
      return "trimmed";
    case Wrapping::kFace:
      return "face";
    case Wrapping::kGenerated:
      return "generated";
  }
  return "unknown";
}

std::vector<std::vector<Vec2d>> sample_loops_uv(const Patch& p, double tol_uv) {
  std::vector<std::vector<Vec2d>> out;
  out.reserve(p.loops.size());
  for (const TrimLoop& loop : p.loops) out.push_back(sample_loop(loop, tol_uv, 0, 0, 1, 1));
  return out;
}

double patch_area(const Patch& p, double rel_tol) {
  if (!(rel_tol > 0) || !(rel_tol < 1))
    throw InternalError("patch area: the tolerance must lie in (0, 1)");
  const NurbsSurface& s = p.surface;
  const AreaIntegrator integrator(s, rel_tol);
  const Cell domain{s.u0, s.u1, s.v0, s.v1};
  if (p.loops.empty()) return integrator.untrimmed(domain);

  // Loops sampled in the domain scaled to the unit square, so one tolerance serves both directions.
  // A polygon within t of its loop misses about t times the loop's length of the unit square:
  // well under rel_tol of a patch that fills a fair share of its domain.
  const double loop_tol = std::max(kAreaLoopTolerance, 0.1 * rel_tol);
  const double su = 1.0 / (s.u1 - s.u0);
  const double sv = 1.0 / (s.v1 - s.v0);
  std::vector<std::vector<Vec2d>> loops;
  bool has_outer = false;
  for (const TrimLoop& loop : p.loops) {
    loops.push_back(sample_loop(loop, loop_tol, s.u0, s.v0, su, sv));
    has_outer = has_outer || loop.outer;
  }
  // Holes without an outer loop: the domain boundary is the outer loop.
  if (!has_outer) loops.push_back({{s.u0, s.v0}, {s.u1, s.v0}, {s.u1, s.v1}, {s.u0, s.v1}});

  // Indicator of the region = sum of sign * winding number, the sign alternating with the
  // nesting depth (even-odd rule) and correcting each loop's orientation.
  std::vector<SignedPolygon> polys;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (loops[l].size() < 3) continue;
    const double area = signed_area(loops[l]);
    if (area == 0) continue;
    int depth = 0;
    for (std::size_t k = 0; k < loops.size(); ++k) {
      if (k != l && loops[k].size() >= 3 && point_in_polygon(loops[l][0], loops[k])) ++depth;
    }
    const double sign = (depth % 2 == 0 ? 1.0 : -1.0) * (area > 0 ? 1.0 : -1.0);
    SignedPolygon q{clip_to_cell(loops[l], domain), sign};
    if (q.pts.size() >= 3) polys.push_back(std::move(q));
  }
  return integrator.trimmed(domain, std::move(polys), 0.0, 0);
}

PatchExtent patch_extent(const Patch& p) {
  const NurbsSurface& s = p.surface;
  // Fewer samples per span on huge nets, so the cost stays bounded (at most ~4k per direction).
  auto params = [](const std::vector<double>& breaks) {
    const std::size_t spans = breaks.size() - 1;
    if (spans > 4096) return uniform_params(breaks.front(), breaks.back(), 4097);
    const int per_span = spans > 1024 ? 1 : 4;
    std::vector<double> t;
    for (std::size_t k = 0; k < spans; ++k)
      for (int i = 0; i < per_span; ++i)
        t.push_back(breaks[k] + (breaks[k + 1] - breaks[k]) * i / double(per_span));
    t.push_back(breaks.back());
    return t;
  };
  const std::vector<double> us = params(span_breaks_u(s)), vs = params(span_breaks_v(s));
  const std::vector<Vec3d> q = evaluate_grid(s, us, vs).positions;
  PatchExtent out;
  for (const Vec3d& x : q) out.box.add(x);
  const std::size_t nu = us.size();
  for (std::size_t j = 0; j + 1 < vs.size(); ++j) {
    for (std::size_t i = 0; i + 1 < nu; ++i) {
      const Vec3d& a = q[i + nu * j];
      const Vec3d& b = q[i + 1 + nu * j];
      const Vec3d& c = q[i + 1 + nu * (j + 1)];
      const Vec3d& d = q[i + nu * (j + 1)];
      out.grid_area += 0.5 * (norm(cross(b - a, c - a)) + norm(cross(c - a, d - a)));
    }
  }
  return out;
}

}  // namespace hm
