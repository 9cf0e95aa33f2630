// NURBS hydrostatics: adaptive Gauss-Legendre quadrature of the wetted-surface integrals (see
// hydrostatic_sums.h) over each patch's parameter domain, cut at the waterplane along Gauss lines.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/bbox.h"
#include "core/parallel.h"
#include "kernels/bspline_basis.h"
#include "nurbs/gauss_legendre.h"
#include "quality/hydrostatic_sums.h"
#include "quality/hydrostatics.h"

namespace hm {
namespace {

using I = SurfaceIntegrals;

struct Cell {
  double u0, u1, v0, v1;
  double area() const { return (u1 - u0) * (v1 - v0); }
};

// A trim-polygon edge in (u, v).
struct Segment {
  Vec2d p, q;
};
using Segments = std::vector<Segment>;

// Length power of each integral (area 0, volume 1, first moments of volume 2, ...), for its scale.
constexpr int kPower[I::kCount] = {0, 1, 2, 2, 2, 0, 1, 1, 2, 2};
constexpr int kRootIterations = 100;

class PatchIntegrator {
 public:
  PatchIntegrator(const Patch& patch, double z0, const NurbsHydrostaticsOptions& o)
      : s_(patch.surface), sign_(patch.reversed ? -1.0 : 1.0), z0_(z0), o_(o) {
    order_ = std::max(std::max(s_.degree_u, s_.degree_v) + 3, 5);
    rule_ = gauss_legendre_01(order_);
    domain_area_ = (s_.u1 - s_.u0) * (s_.v1 - s_.v0);
    set_scales();
    const double tol = o.trim_tol * std::max(s_.u1 - s_.u0, s_.v1 - s_.v0);
    for (const std::vector<Vec2d>& loop : sample_loops_uv(patch, tol))
      for (std::size_t i = 0; i < loop.size(); ++i)
        trims_.push_back({loop[i], loop[(i + 1) % loop.size()]});
    trimmed_ = !trims_.empty();
    positive_weights_ =
        static_cast<int>(s_.weights.size()) == s_.count_u * s_.count_v &&
        static_cast<int>(s_.knots_u.size()) == s_.count_u + s_.degree_u + 1 &&
        static_cast<int>(s_.knots_v.size()) == s_.count_v + s_.degree_v + 1 &&
        std::all_of(s_.weights.begin(), s_.weights.end(), [](double w) { return w > 0; });
  }

  SurfaceIntegrals integrate() const {
    SurfaceIntegrals total;
    const std::vector<double> bu = span_breaks_u(s_), bv = span_breaks_v(s_);
    for (std::size_t j = 0; j + 1 < bv.size(); ++j) {
      for (std::size_t i = 0; i + 1 < bu.size(); ++i) {
        const Cell c{bu[i], bu[i + 1], bv[j], bv[j + 1]};
        // A knot-span cell lies in the convex hull of the control points that act on it (positive
        // weights): wholly above the waterplane it adds nothing, wholly below it needs no search
        // for the waterline on its lines. Either way the sums are the same, bit for bit.
        const Wetness w = wetness(c);
        if (w == Wetness::kDry) continue;
        adapt(c, filter(trims_, c, true), filter(trims_, c, false), 0, w == Wetness::kWet, total);
      }
    }
    return total;
  }

 private:
  void set_scales() {
    BBox3d box;
    for (const Vec3d& p : s_.points) box.add(p);
    const double size = box.diagonal();
    const double reach = size + std::max({std::abs(box.lo.x), std::abs(box.lo.y),
                                          std::abs(box.lo.z), std::abs(box.hi.x),
                                          std::abs(box.hi.y), std::abs(box.hi.z), std::abs(z0_)});
    double net_area = 0;  // the control net's area: a scale, not a result
    for (int j = 0; j + 1 < s_.count_v; ++j)
      for (int i = 0; i + 1 < s_.count_u; ++i)
        net_area += 0.5 * norm(cross(s_.point(i + 1, j + 1) - s_.point(i, j),
                                     s_.point(i, j + 1) - s_.point(i + 1, j)));
    net_area = std::max(net_area, 1e-6 * size * size);
    for (int k = 0; k < I::kCount; ++k) scale_[k] = net_area * std::pow(reach, kPower[k]);
  }

  enum class Wetness { kDry, kWet, kCrossed };

  // Whether the knot-span cell c lies wholly above the waterplane, wholly on or below it, or
  // either side (also whenever a weight is not positive, or the net is not a B-spline net).
  Wetness wetness(const Cell& c) const {
    if (!positive_weights_) return Wetness::kCrossed;
    // The span holding the cell's low corner; points span - degree .. span act on it.
    auto first_point = [](const std::vector<double>& knots, int degree, int count, double t) {
      return kernel::find_span(degree, count, knots.data(), t) - degree;
    };
    const int iu = first_point(s_.knots_u, s_.degree_u, s_.count_u, c.u0);
    const int iv = first_point(s_.knots_v, s_.degree_v, s_.count_v, c.v0);
    if (iu < 0 || iv < 0) return Wetness::kCrossed;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int j = iv; j <= iv + s_.degree_v && j < s_.count_v; ++j) {
      for (int i = iu; i <= iu + s_.degree_u && i < s_.count_u; ++i) {
        lo = std::min(lo, s_.point(i, j).z);
        hi = std::max(hi, s_.point(i, j).z);
      }
    }
    if (lo > z0_) return Wetness::kDry;
    if (hi <= z0_) return Wetness::kWet;
    return Wetness::kCrossed;
  }

  // Trim edges that can cross the lines of cell c: along v (u fixed in [u0, u1]) when along_v,
  // otherwise along u.
  static Segments filter(const Segments& in, const Cell& c, bool along_v) {
    Segments out;
    for (const Segment& s : in) {
      const double a = along_v ? s.p.x : s.p.y, b = along_v ? s.q.x : s.q.y;
      const double lo = along_v ? c.u0 : c.v0, hi = along_v ? c.u1 : c.v1;
      if (std::max(a, b) >= lo && std::min(a, b) <= hi) out.push_back(s);
    }
    return out;
  }

  Vec2d uv(bool along_v, double fixed, double t) const {
    return along_v ? Vec2d{fixed, t} : Vec2d{t, fixed};
  }
  double height(bool along_v, double fixed, double t) const {
    const Vec2d p = uv(along_v, fixed, t);
    return evaluate(s_, p.x, p.y).z - z0_;
  }

  // Wet parameter intervals of the line (z <= z0): sampled sign changes refined by Illinois.
  void wet_intervals(bool along_v, double fixed, double a, double b,
                     std::vector<std::pair<double, double>>& out) const {
    out.clear();
    const int m = 2 * order_ + 1;
    double t_prev = a, g_prev = height(along_v, fixed, a);
    double start = g_prev <= 0 ? a : NAN;
    for (int i = 1; i <= m; ++i) {
      const double t = a + (b - a) * i / m;
      const double g = height(along_v, fixed, t);
      if ((g_prev <= 0) != (g <= 0)) {
        const double r = root(along_v, fixed, t_prev, g_prev, t, g);
        if (g_prev <= 0) {
          out.emplace_back(start, r);
        } else {
          start = r;
        }
      }
      t_prev = t;
      g_prev = g;
    }
    if (g_prev <= 0) out.emplace_back(start, b);
  }

  double root(bool along_v, double fixed, double a, double ga, double b, double gb) const {
    int side = 0;
    for (int it = 0; it < kRootIterations && b - a > 1e-15 * (std::abs(a) + std::abs(b)); ++it) {
      const double t = (a * gb - b * ga) / (gb - ga);
      const double g = height(along_v, fixed, t);
      if (g == 0) return t;
      if ((g <= 0) == (ga <= 0)) {
        a = t;
        ga = g;
        if (side == -1) gb *= 0.5;
        side = -1;
      } else {
        b = t;
        gb = g;
        if (side == 1) ga *= 0.5;
        side = 1;
      }
    }
    return 0.5 * (a + b);
  }

  // Inside the trim loops along the line (even-odd over every loop), intersected with wet.
  void trim_intervals(bool along_v, double fixed, const Segments& segs,
                      std::vector<std::pair<double, double>>& wet) const {
    std::vector<double> cuts;
    for (const Segment& s : segs) {
      const double pa = along_v ? s.p.x : s.p.y, qa = along_v ? s.q.x : s.q.y;
      if ((pa > fixed) == (qa > fixed)) continue;
      const double pb = along_v ? s.p.y : s.p.x, qb = along_v ? s.q.y : s.q.x;
      cuts.push_back(pb + (fixed - pa) * (qb - pb) / (qa - pa));
    }
    std::sort(cuts.begin(), cuts.end());
    std::vector<std::pair<double, double>> out;
    for (std::size_t k = 0; k + 1 < cuts.size(); k += 2)
      for (const auto& [a, b] : wet) {
        const double lo = std::max(a, cuts[k]), hi = std::min(b, cuts[k + 1]);
        if (hi > lo) out.emplace_back(lo, hi);
      }
    wet.swap(out);
  }

  void add_point(double u, double v, double w, SurfaceIntegrals& acc) const {
    const SurfaceDerivs d = evaluate_derivs(s_, u, v, 1);
    const Vec3d n = sign_ * cross(d.su, d.sv);  // n dS / (du dv)
    const Vec3d& p = d.p;
    const double h = p.z - z0_, wn = w * n.z;
    acc.v[I::kArea] += w * norm(n);
    acc.v[I::kVolume] += wn * h;
    acc.v[I::kMx] += wn * p.x * h;
    acc.v[I::kMy] += wn * p.y * h;
    acc.v[I::kMz] += wn * 0.5 * (p.z * p.z - z0_ * z0_);
    acc.v[I::kAwp] -= wn;
    acc.v[I::kSx] -= wn * p.x;
    acc.v[I::kSy] -= wn * p.y;
    acc.v[I::kSxx] -= wn * p.x * p.x;
    acc.v[I::kSyy] -= wn * p.y * p.y;
  }

  // Gauss lines across the cell in the direction z varies most (so the waterline crosses them).
  // wet: the cell lies wholly on or below the waterplane (every line is wet end to end).
  SurfaceIntegrals estimate(const Cell& c, const Segments& seg_u, const Segments& seg_v,
                            bool wet) const {
    const SurfaceDerivs d = evaluate_derivs(s_, 0.5 * (c.u0 + c.u1), 0.5 * (c.v0 + c.v1), 1);
    const bool along_v = std::abs(d.sv.z) * (c.v1 - c.v0) >= std::abs(d.su.z) * (c.u1 - c.u0);
    const double f0 = along_v ? c.u0 : c.v0, f1 = along_v ? c.u1 : c.v1;
    const double a = along_v ? c.v0 : c.u0, b = along_v ? c.v1 : c.u1;
    SurfaceIntegrals acc;
    std::vector<std::pair<double, double>> iv;
    for (int k = 0; k < order_; ++k) {
      const double fixed = f0 + (f1 - f0) * rule_.nodes[k];
      const double wf = (f1 - f0) * rule_.weights[k];
      if (wet) {
        iv.assign(1, {a, b});
      } else {
        wet_intervals(along_v, fixed, a, b, iv);
      }
      if (trimmed_) trim_intervals(along_v, fixed, along_v ? seg_u : seg_v, iv);
      for (const auto& [lo, hi] : iv) {
        for (int i = 0; i < order_; ++i) {
          const Vec2d p = uv(along_v, fixed, lo + (hi - lo) * rule_.nodes[i]);
          add_point(p.x, p.y, wf * (hi - lo) * rule_.weights[i], acc);
        }
      }
    }
    return acc;
  }

  void adapt(const Cell& c, const Segments& seg_u, const Segments& seg_v, int depth, bool wet,
             SurfaceIntegrals& total) const {
    adapt_with(c, seg_u, seg_v, depth, wet, estimate(c, seg_u, seg_v, wet), total);
  }

  void adapt_with(const Cell& c, const Segments& seg_u, const Segments& seg_v, int depth, bool wet,
                  const SurfaceIntegrals& whole, SurfaceIntegrals& total) const {
    const double um = 0.5 * (c.u0 + c.u1), vm = 0.5 * (c.v0 + c.v1);
    const Cell kids[4] = {
        {c.u0, um, c.v0, vm}, {um, c.u1, c.v0, vm}, {c.u0, um, vm, c.v1}, {um, c.u1, vm, c.v1}};
    Segments ku[4], kv[4];
    SurfaceIntegrals parts[4], sum;
    for (int k = 0; k < 4; ++k) {
      ku[k] = filter(seg_u, kids[k], true);
      kv[k] = filter(seg_v, kids[k], false);
      parts[k] = estimate(kids[k], ku[k], kv[k], wet);
      sum += parts[k];
    }
    // A cell a trim edge crosses cannot beat the sampled trim polygon: accept at its accuracy.
    const bool crossed = trimmed_ && (!seg_u.empty() || !seg_v.empty());
    const double rel = crossed ? std::max(o_.rel_tol, 10 * o_.trim_tol) : o_.rel_tol;
    const double share = c.area() / domain_area_;
    bool ok = depth >= o_.max_depth;
    if (!ok) {
      ok = true;
      for (int k = 0; k < I::kCount && ok; ++k)
        ok = std::abs(whole.v[k] - sum.v[k]) <= rel * scale_[k] * share;
    }
    if (ok) {
      total += sum;
      return;
    }
    for (int k = 0; k < 4; ++k) adapt_with(kids[k], ku[k], kv[k], depth + 1, wet, parts[k], total);
  }

  const NurbsSurface& s_;
  double sign_;
  double z0_;
  NurbsHydrostaticsOptions o_;
  int order_ = 5;
  GaussRule rule_;
  double domain_area_ = 1;
  double scale_[I::kCount] = {};
  Segments trims_;
  bool trimmed_ = false;
  bool positive_weights_ = false;  // a well-formed net with every weight positive
};

}  // namespace

Hydrostatics hydrostatics_nurbs(std::span<const Patch> patches, const FloatingPosition& position,
                                const NurbsHydrostaticsOptions& options) {
  std::vector<SurfaceIntegrals> per_patch(patches.size());
  parallel_for_each_item(patches.size(), [&](std::size_t i) {
    validate_surface(patches[i].surface);
    per_patch[i] = PatchIntegrator(patches[i], position.waterline_z, options).integrate();
  });
  SurfaceIntegrals sum;
  for (const SurfaceIntegrals& s : per_patch) sum += s;
  // The waterplane figures are the flux integrals (exact section implicitly, see the header).
  WaterplaneMoments w;
  w.area = sum.v[I::kAwp];
  w.sx = sum.v[I::kSx];
  w.sy = sum.v[I::kSy];
  w.sxx = sum.v[I::kSxx];
  w.syy = sum.v[I::kSyy];
  return finish_hydrostatics(sum, w, position.half_hull);
}

}  // namespace hm
