#include "nurbs/hull_shapes.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "kernels/bspline_basis.h"
#include "nurbs/gauss_legendre.h"

namespace hm {
namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------------------
// Quadrature

struct WaterlineIntegrals {
  double area = 0;    // m^2 of surface below the waterline
  double volume = 0;  // m^3: integral of y n_y dA, the half volume enclosed with y = 0
};

// Cells for composite quadrature over [breaks.front(), breaks.back()]: every interval between
// breaks (where the integrand may have a kink) cut into equal cells, about `cells` in all.
std::vector<double> quadrature_cells(const std::vector<double>& breaks, int cells) {
  std::vector<double> out{breaks.front()};
  const double total = breaks.back() - breaks.front();
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double a = breaks[k], b = breaks[k + 1];
    if (!(b > a)) continue;
    const int n = std::max(1, static_cast<int>(std::lround(cells * (b - a) / total)));
    for (int m = 1; m < n; ++m) out.push_back(a + (b - a) * m / n);
    out.push_back(b);
  }
  return out;
}

// Integrates over the part of a surface below z = waterline, for a surface whose z does not
// increase with v (deck to keel). `column(u)` returns a function of (v, order) giving
// SurfaceDerivs on the line of constant u (p only for order 0; p, su, sv for order 1), so that
// work shared along a line is done once; su x sv
// points out of the hull. `breaks_u` and `breaks_v` (sorted, ends included) are where the
// integrand may have kinks (knots, knuckles); no quadrature cell straddles them. Composite Gauss
// (4 points per cell) in u; per u node the waterline crossing is found by bisection and
// [v_wl, v1] is integrated with composite Gauss in v.
// By the divergence theorem with F = (0, y, 0), the half volume is the integral of y n_y over
// the wetted surface (the waterplane, centreplane and transom add nothing).
template <class Column>
WaterlineIntegrals integrate_below(const Column& column, const std::vector<double>& breaks_u,
                                   const std::vector<double>& breaks_v, double waterline,
                                   int cells_u, int cells_v) {
  const GaussRule g = gauss_legendre_01(4);
  const std::vector<double> cu = quadrature_cells(breaks_u, cells_u);
  const double v0 = breaks_v.front(), v1 = breaks_v.back();
  WaterlineIntegrals r;
  for (std::size_t i = 0; i + 1 < cu.size(); ++i) {
    const double hu = cu[i + 1] - cu[i];
    for (std::size_t a = 0; a < g.nodes.size(); ++a) {
      const auto eval = column(cu[i] + hu * g.nodes[a]);
      if (eval(v1, 0).p.z >= waterline) continue;
      std::vector<double> bv = breaks_v;
      if (eval(v0, 0).p.z > waterline) {
        double lo = v0, hi = v1;  // z(lo) > waterline >= z(hi)
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (lo + hi);
          (eval(mid, 0).p.z > waterline ? lo : hi) = mid;
        }
        const double vs = 0.5 * (lo + hi);
        bv.erase(bv.begin(), std::upper_bound(bv.begin(), bv.end(), vs));
        bv.insert(bv.begin(), vs);
      }
      const std::vector<double> cv = quadrature_cells(
          bv, std::max(1, static_cast<int>(std::lround(cells_v * (v1 - bv.front()) / (v1 - v0)))));
      double area = 0, volume = 0;
      for (std::size_t j = 0; j + 1 < cv.size(); ++j) {
        const double hv = cv[j + 1] - cv[j];
        for (std::size_t b = 0; b < g.nodes.size(); ++b) {
          const SurfaceDerivs d = eval(cv[j] + hv * g.nodes[b], 1);
          const Vec3d n = cross(d.su, d.sv);
          area += hv * g.weights[b] * norm(n);
          volume += hv * g.weights[b] * d.p.y * n.y;
        }
      }
      r.area += hu * g.weights[a] * area;
      r.volume += hu * g.weights[a] * volume;
    }
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// B-spline interpolation (for the round-bilge hull)

// Non-zero basis functions N_{span-p..span, p}(t): the kernel's, so the shapes and the patches
// use the same arithmetic.
void basis_functions(const std::vector<double>& knots, int p, int span, double t, double* out) {
  kernel::basis_funs(span, t, p, knots.data(), out);
}

// Clamped knots by averaging of uniform parameters i / (n - 1), and the LU factors of the
// collocation matrix. Solving gives control values whose spline passes through the samples.
struct Interpolator {
  int degree = 3;
  std::vector<double> knots;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;

  Interpolator(int n, int p) : degree(p) {
    std::vector<double> params(n);
    for (int i = 0; i < n; ++i) params[i] = static_cast<double>(i) / (n - 1);
    knots.assign(p + 1, 0.0);
    for (int j = 1; j < n - p; ++j) {
      double sum = 0;
      for (int i = j; i < j + p; ++i) sum += params[i];
      knots.push_back(sum / p);
    }
    knots.insert(knots.end(), p + 1, 1.0);
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
    std::vector<double> basis(p + 1);
    for (int i = 0; i < n; ++i) {
      const double t = params[i];
      int span =
          static_cast<int>(std::upper_bound(knots.begin(), knots.end(), t) - knots.begin()) - 1;
      span = std::clamp(span, p, n - 1);
      basis_functions(knots, p, span, t, basis.data());
      for (int k = 0; k <= p; ++k) m(i, span - p + k) = basis[k];
    }
    lu.compute(m);
  }

  // Each column of `data` is one set of n samples; returns control values, with the end values
  // set to the end samples exactly (a clamped spline passes through its end control points).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& data) const {
    Eigen::MatrixXd c = lu.solve(data);
    c.row(0) = data.row(0);
    c.row(c.rows() - 1) = data.row(data.rows() - 1);
    return c;
  }
};

// ---------------------------------------------------------------------------------------------
// Assembling parts

// The flat transom inside the hull's u = u0 edge: lines of constant v from the centreplane
// (y = 0) out to the edge, degree `degree_w` in the new u (centreline to edge). The edge column
// is the hull's own control column, so transom and hull share that border bit for bit.
NurbsSurface transom_from_edge(const NurbsSurface& hull, int degree_w) {
  NurbsSurface t;
  t.degree_u = degree_w;
  t.degree_v = hull.degree_v;
  t.count_u = degree_w + 1;
  t.count_v = hull.count_v;
  t.knots_u.assign(degree_w + 1, 0.0);
  t.knots_u.insert(t.knots_u.end(), degree_w + 1, 1.0);
  t.knots_v = hull.knots_v;
  t.v0 = hull.v0;
  t.v1 = hull.v1;
  for (int j = 0; j < hull.count_v; ++j) {
    const Vec3d e = hull.point(0, j);
    for (int i = 0; i <= degree_w; ++i) {
      // A linear function in Bezier form of any degree has equally spaced coefficients.
      t.points.push_back(i == degree_w ? e : Vec3d{e.x, e.y * i / degree_w, e.z});
      t.weights.push_back(hull.weight(0, j));
    }
  }
  return t;
}

// Joins a (first) and b along u with a knot of full multiplicity at the seam: a's u range maps
// to [0, seam] and b's to [seam, 1]. Both must be clamped, share degrees in u and the v
// parameterization, and a's last column must equal b's first.
NurbsSurface concat_u(const NurbsSurface& a, const NurbsSurface& b, double seam) {
  const int p = a.degree_u;
  NurbsSurface m;
  m.degree_u = p;
  m.degree_v = a.degree_v;
  m.count_u = a.count_u + b.count_u - 1;
  m.count_v = a.count_v;
  m.knots_v = a.knots_v;
  m.v0 = a.v0;
  m.v1 = a.v1;
  const auto map = [](double t, double t0, double t1, double lo, double hi) {
    if (t == t0) return lo;
    if (t == t1) return hi;
    return lo + (hi - lo) * (t - t0) / (t1 - t0);
  };
  for (std::size_t k = 0; k + 1 < a.knots_u.size(); ++k) {
    m.knots_u.push_back(map(a.knots_u[k], a.u0, a.u1, 0.0, seam));
  }
  for (std::size_t k = p + 1; k < b.knots_u.size(); ++k) {
    m.knots_u.push_back(map(b.knots_u[k], b.u0, b.u1, seam, 1.0));
  }
  for (int j = 0; j < m.count_v; ++j) {
    for (int i = 0; i < a.count_u; ++i) {
      m.points.push_back(a.point(i, j));
      m.weights.push_back(a.weight(i, j));
    }
    for (int i = 1; i < b.count_u; ++i) {
      m.points.push_back(b.point(i, j));
      m.weights.push_back(b.weight(i, j));
    }
  }
  return m;
}

// Degree-3 u, degree-1 v ruled surface between rows of control points with the same u knots.
NurbsSurface ruled_rows(const std::vector<std::vector<Vec3d>>& rows,
                        const std::vector<double>& knots_u, const std::vector<double>& knots_v) {
  NurbsSurface s;
  s.degree_u = 3;
  s.degree_v = 1;
  s.count_u = static_cast<int>(rows.front().size());
  s.count_v = static_cast<int>(rows.size());
  s.knots_u = knots_u;
  s.knots_v = knots_v;
  for (const auto& row : rows) s.points.insert(s.points.end(), row.begin(), row.end());
  s.weights.assign(s.points.size(), 1.0);
  return s;
}

HullPart part(std::string name, NurbsSurface s, SideKind u0, SideKind u1, SideKind v0,
              SideKind v1) {
  return HullPart{std::move(name), std::move(s), {u0, u1, v0, v1}};
}

// ---------------------------------------------------------------------------------------------
// Wigley: y = B/2 (1 - (2x'/L)^2)(1 - (z'/T)^2), exactly one biquadratic Bezier patch.

HullShape make_wigley(const HullSpec& spec) {
  const double l = spec.length, b = spec.beam, t = spec.draft;
  if (spec.depth >= 2 * t) {
    throw UsageError("the Wigley formula closes at twice the draft: depth must be below " +
                     std::to_string(2 * t) + " m");
  }
  const double zmax = std::max(spec.depth, t);
  // Bernstein coefficients: x = L u; f(u) = 1 - (2u - 1)^2 = 2 B1(u); z = zmax (1 - v);
  // g(v) = 1 - (z/T - 1)^2, a quadratic in v with g(0) = g(zmax), g(1) = 0.
  const double g0 = 1.0 - (zmax / t - 1.0) * (zmax / t - 1.0);
  const double dg0 = -(2.0 / t - 2.0 * zmax / (t * t)) * zmax;  // dg/dv at v = 0
  const double xs[3] = {0.0, 0.5 * l, l};
  const double fs[3] = {0.0, 2.0, 0.0};
  const double zs[3] = {zmax, 0.5 * zmax, 0.0};
  const double gs[3] = {g0, g0 + 0.5 * dg0, 0.0};
  NurbsSurface s;
  s.degree_u = s.degree_v = 2;
  s.count_u = s.count_v = 3;
  s.knots_u = s.knots_v = {0, 0, 0, 1, 1, 1};
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) s.points.push_back({xs[i], 0.5 * b * fs[i] * gs[j], zs[j]});
  }
  s.weights.assign(9, 1.0);

  HullShape shape;
  shape.parts.push_back(
      part("hull", s, SideKind::kCentre, SideKind::kCentre, SideKind::kFree, SideKind::kCentre));
  shape.merged = shape.parts.front();
  shape.displacement_volume = 4.0 / 9.0 * l * b * t;
  // Wetted area: both sides of sqrt(1 + y_x^2 + y_z^2) over [0, L] x [0, T] (composite Gauss).
  const auto formula = [&](double u) {
    return [&, u](double v, int) {
      const double x = l * u, z = t * (1.0 - v);
      const double xi = 2.0 * x / l - 1.0, zeta = z / t - 1.0;
      SurfaceDerivs d;
      d.p = {x, 0.5 * b * (1 - xi * xi) * (1 - zeta * zeta), z};
      d.su = {l, 0.5 * b * (-4.0 * xi) * (1 - zeta * zeta), 0.0};
      d.sv = {0.0, 0.5 * b * (1 - xi * xi) * (2.0 * zeta), -t};
      return d;
    };
  };
  shape.wetted_area = 2.0 * integrate_below(formula, {0, 1}, {0, 1}, t + 1.0, 64, 16).area;
  return shape;
}

// ---------------------------------------------------------------------------------------------
// Round bilge combatant (DTMB 5415-like): flat of side, round bilge, a nearly flat bottom (4 deg
// deadrise), a bulbous forefoot with a sonar dome reaching 0.03 B below the baseline, a raked
// stem and a flat immersed transom. Each section (s = x / L aft to fore) is a cubic B-spline in
// (y, z) from the deck edge (t = 0) to the keel (t = 1) whose 8 control points are smooth
// functions of s: four on the vertical side line (the last at the bilge), four on the bottom
// line (the first at the bilge). Four collinear control points make a straight span, so the side
// and bottom are exactly plane in the midbody.

constexpr int kSectionPoints = 8;
const std::vector<double> kSectionKnots = {0, 0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1};
const std::vector<double> kSectionKnotValues = {0, 0.2, 0.4, 0.6, 0.8, 1};

struct RoundBilge {
  double l, b, d, t;

  // Control points of the section at s (kSectionPoints values).
  std::array<Vec3d, kSectionPoints> section(double s) const {
    const double h = 0.5 * b;
    const auto smooth = [](double x) { return x * x * (3.0 - 2.0 * x); };
    double w = 1.0;  // half beam / (B / 2): transom 0.86, parallel midbody, fine entrance
    if (s < 0.4) w = 0.86 + 0.14 * smooth(s / 0.4);
    if (s > 0.6) w = std::max(0.0, 1.0 - (s - 0.6) * (s - 0.6) / 0.16);
    const double half = s >= 1.0 ? 0.0 : h * w;
    const double zb = s < 0.4 ? 0.55 * t * (1 - s / 0.4) * (1 - s / 0.4) : 0.0;  // keel rise aft
    const double a = std::min(0.5 * half, 0.4 * (d - zb));  // bilge corner offset
    // Forefoot: the bottom rises into the stem, so the stem is a curve and not a point.
    const double rise = s > 0.75 ? 0.35 * t * smooth(std::min(1.0, (s - 0.75) / 0.25)) : 0.0;
    // A slight deadrise (4 degrees): z falls strictly towards the keel, so the transom, made of
    // horizontal lines, has no zero-area strip along the bottom.
    const double dead = (half - a) * std::tan(4.0 * kPi / 180.0);
    const double low = zb + a + rise + dead;  // lowest point of the straight side
    const double side = d - low;
    std::array<Vec3d, kSectionPoints> q = {
        Vec3d{0, half, d},
        Vec3d{0, half, low + 2 * side / 3},
        Vec3d{0, half, low + side / 3},
        Vec3d{0, half, low},
        Vec3d{0, half - a, zb + 0.75 * rise + dead},
        Vec3d{0, 2 * (half - a) / 3, zb + 0.5 * rise + 2 * dead / 3},
        Vec3d{0, (half - a) / 3, zb + 0.25 * rise + dead / 3},
        Vec3d{0, 0, zb}};
    // Sonar dome: the forefoot bulges out and down between s = 0.78 and the stem.
    const double beta = s > 0.78 && s < 1.0 ? std::pow(std::sin(kPi * (s - 0.78) / 0.22), 2) : 0.0;
    const double out[kSectionPoints] = {0, 0, 0.3, 0.8, 1.0, 0.7, 0.3, 0};
    const double down[kSectionPoints] = {0, 0, 0, 0.3, 0.8, 1, 1, 1};
    for (int j = 0; j < kSectionPoints; ++j) {
      Vec3d& p = q[j];
      p.y += 0.12 * b * beta * out[j];
      p.z -= 0.03 * b * beta * down[j];
      // Stem: bulb nose forward below the waterline, rake above it.
      const double above = std::max(0.0, p.z - t) / (d - t);
      const double e = 0.05 * l * above * above +
                       0.03 * l * std::exp(-std::pow((p.z - 0.4 * t) / (0.22 * t), 2));
      p.x = l * s + std::pow(s, 6) * e;
    }
    return q;
  }
};

// The point at t in [0, 1] of the section curve with control points q.
Vec3d section_point(const std::array<Vec3d, kSectionPoints>& q, double t) {
  t = std::clamp(t, 0.0, 1.0);
  const int span =
      std::clamp(static_cast<int>(std::upper_bound(kSectionKnots.begin(), kSectionKnots.end(), t) -
                                  kSectionKnots.begin()) -
                     1,
                 3, kSectionPoints - 1);
  double basis[4];
  basis_functions(kSectionKnots, 3, span, t, basis);
  Vec3d p;
  for (int k = 0; k < 4; ++k) p += basis[k] * q[span - 3 + k];
  return p;
}

// Cubic interpolation along u of the section control points sampled at s_i = i / (ns - 1): the
// surface passes through every sampled section exactly.
NurbsSurface interpolate_sections(const RoundBilge& rb, int ns) {
  const Interpolator iu(ns, 3);
  Eigen::MatrixXd data(ns, 3 * kSectionPoints);
  for (int i = 0; i < ns; ++i) {
    const auto q = rb.section(static_cast<double>(i) / (ns - 1));
    for (int j = 0; j < kSectionPoints; ++j) {
      for (int c = 0; c < 3; ++c) data(i, 3 * j + c) = q[j][c];
    }
  }
  const Eigen::MatrixXd c = iu.solve(data);
  NurbsSurface s;
  s.degree_u = 3;
  s.degree_v = 3;
  s.count_u = ns;
  s.count_v = kSectionPoints;
  s.knots_u = iu.knots;
  s.knots_v = kSectionKnots;
  for (int j = 0; j < kSectionPoints; ++j) {
    for (int i = 0; i < ns; ++i) {
      // The keel row stays on the centreplane exactly.
      const double y = j + 1 == kSectionPoints ? 0.0 : c(i, 3 * j + 1);
      s.points.push_back({c(i, 3 * j), y, c(i, 3 * j + 2)});
    }
  }
  s.weights.assign(s.points.size(), 1.0);
  return s;
}

HullShape make_round_bilge(const HullSpec& spec) {
  if (spec.beam > 4.0 * spec.depth) {
    // Beyond this the bilge and bottom rise would leave no straight side.
    throw UsageError("round-bilge hull: the beam must be at most 4 times the depth");
  }
  const RoundBilge rb{spec.length, spec.beam, spec.depth, spec.draft};
  const NurbsSurface hull = interpolate_sections(rb, 61);
  HullShape shape;
  shape.parts.push_back(
      part("hull", hull, SideKind::kShared, SideKind::kCentre, SideKind::kFree, SideKind::kCentre));
  shape.parts.push_back(part("transom", transom_from_edge(hull, 1), SideKind::kCentre,
                             SideKind::kShared, SideKind::kFree, SideKind::kDegenerate));
  shape.merged = part("hull", concat_u(transom_from_edge(hull, 3), hull, 0.125), SideKind::kCentre,
                      SideKind::kCentre, SideKind::kFree, SideKind::kCentre);
  shape.knuckles.push_back({0, true, 0.0});

  // The shape's derivatives by central differences: in s between neighbouring sections, in t
  // along one section.
  constexpr double kStep = 1e-6;
  const auto hull_column = [&](double s) {
    return [&, lo = rb.section(s - kStep), mid = rb.section(s), hi = rb.section(s + kStep)](
               double t, int order) {
      SurfaceDerivs d;
      d.p = section_point(mid, t);
      if (order == 0) return d;
      d.su = (section_point(hi, t) - section_point(lo, t)) / (2 * kStep);
      d.sv = (section_point(mid, t + kStep) - section_point(mid, t - kStep)) / (2 * kStep);
      return d;
    };
  };
  const auto transom_column = [&](double w) {
    return [&, w, q = rb.section(0.0)](double t, int) {
      const Vec3d e = section_point(q, t);
      const Vec3d de = (section_point(q, t + kStep) - section_point(q, t - kStep)) / (2 * kStep);
      SurfaceDerivs d;
      d.p = {e.x, w * e.y, e.z};
      d.su = {0.0, e.y, 0.0};
      d.sv = {de.x, w * de.y, de.z};
      return d;
    };
  };
  // Where the shape's functions of s change formula, and the section's knots.
  const std::vector<double> kinks_s = {0, 0.4, 0.6, 0.75, 0.78, 1};
  const WaterlineIntegrals h =
      integrate_below(hull_column, kinks_s, kSectionKnotValues, spec.draft, 96, 20);
  const WaterlineIntegrals tr =
      integrate_below(transom_column, {0, 1}, kSectionKnotValues, spec.draft, 16, 20);
  shape.displacement_volume = 2.0 * (h.volume + tr.volume);
  shape.wetted_area = 2.0 * (h.area + tr.area);
  return shape;
}

// ---------------------------------------------------------------------------------------------
// Hard chine planing hull: sheer, chine and keel lines are cubic B-splines with one knot vector;
// side and bottom are ruled between them (so they meet at the chine knuckle exactly); the stem
// is raked (the sheer ends forward of the chine); a flat transom closes the stern at x = 0.

HullShape make_chine(const HullSpec& spec) {
  const double l = spec.length, h = 0.5 * spec.beam, d = spec.depth;
  const double deadrise = std::tan(14.0 * kPi / 180.0);               // bottom slope aft
  const double hc = 0.9 * h;                                          // chine half beam
  const double zc = hc * deadrise;                                    // chine height aft
  const double zs = std::max(0.55 * d, std::min(1.5 * zc, 0.9 * d));  // chine meets the stem here
  if (zc >= 0.5 * d) {
    const double max_beam = 2.0 * 0.5 * d / (0.9 * deadrise);
    throw UsageError(
        "chine hull: the beam is too wide for the depth (the bottom would reach half "
        "the depth); use a beam below " +
        std::to_string(max_beam) + " m");
  }
  const std::vector<double> xs_sheer = {0, 0.17, 0.33, 0.5, 0.67, 0.83, 1.0};
  const std::vector<double> xs_low = {0, 0.17, 0.33, 0.5, 0.67, 0.8, 0.9};
  const std::vector<double> ys_sheer = {0.92, 0.97, 1.0, 1.0, 0.9, 0.55, 0.0};
  const std::vector<double> ys_chine = {0.95, 1.0, 1.0, 0.97, 0.85, 0.45, 0.0};
  const std::vector<double> zs_chine = {
      zc, zc, 1.05 * zc, 1.3 * zc, 1.8 * zc, std::max(1.8 * zc, 0.8 * zs), zs};
  const std::vector<double> zs_keel = {0, 0, 0, 0, 0.05 * zs, 0.35 * zs, zs};
  std::vector<Vec3d> sheer, chine, keel;
  for (int i = 0; i < 7; ++i) {
    sheer.push_back({l * xs_sheer[i], h * ys_sheer[i], d});
    chine.push_back({l * xs_low[i], hc * ys_chine[i], zs_chine[i]});
    keel.push_back({l * xs_low[i], 0.0, zs_keel[i]});
  }
  const std::vector<double> ku = {0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1};
  const NurbsSurface side = ruled_rows({sheer, chine}, ku, {0, 0, 1, 1});
  const NurbsSurface bottom = ruled_rows({chine, keel}, ku, {0, 0, 1, 1});
  // Side over bottom in one surface: v in [0, 0.5] is the side, [0.5, 1] the bottom; the knot
  // 0.5 has full multiplicity (degree 1), so the chine is a knuckle inside the surface.
  const NurbsSurface both = ruled_rows({sheer, chine, keel}, ku, {0, 0, 0.5, 1, 1});

  HullShape shape;
  shape.parts.push_back(
      part("side", side, SideKind::kShared, SideKind::kCentre, SideKind::kFree, SideKind::kShared));
  shape.parts.push_back(part("bottom", bottom, SideKind::kShared, SideKind::kDegenerate,
                             SideKind::kShared, SideKind::kCentre));
  shape.parts.push_back(part("transom", transom_from_edge(both, 1), SideKind::kCentre,
                             SideKind::kShared, SideKind::kFree, SideKind::kDegenerate));
  shape.merged = part("hull", concat_u(transom_from_edge(both, 3), both, 0.125), SideKind::kCentre,
                      SideKind::kCentre, SideKind::kFree, SideKind::kCentre);
  shape.knuckles = {{0, false, 1.0}, {0, true, 0.0}, {1, true, 0.0}};

  WaterlineIntegrals sum;
  for (const HullPart& p : shape.parts) {
    const NurbsSurface& s = p.surface;
    const auto column = [&](double u) {
      return [&, u](double v, int order) { return evaluate_derivs(s, u, v, order); };
    };
    const WaterlineIntegrals w =
        integrate_below(column, span_breaks_u(s), span_breaks_v(s), spec.draft, 96, 16);
    sum.area += w.area;
    sum.volume += w.volume;
  }
  shape.displacement_volume = 2.0 * sum.volume;
  shape.wetted_area = 2.0 * sum.area;
  return shape;
}

}  // namespace

HullShape make_hull_shape(const HullSpec& spec) {
  switch (spec.kind) {
    case HullKind::kWigley:
      return make_wigley(spec);
    case HullKind::kRoundBilge:
      return make_round_bilge(spec);
    case HullKind::kChine:
      return make_chine(spec);
  }
  throw UsageError("unknown hull kind");
}

}  // namespace hm
