#include "kernels/evaluate_nurbs.h"

#include <algorithm>
#include <vector>

namespace hm::kernel {
namespace {

// The quotient rule on the homogeneous derivatives a[k][l] = (A(k, l), w(k, l)) for k + l <=
// Order: out[0] = S, then Su, Sv, then Suu, Suv, Svv.
template <int Order>
[[gnu::always_inline]] inline void finish(const double (&a)[Order + 1][Order + 1][4], Vec3d* out) {
  // Multiplying by 1 / w instead of dividing: fewer divisions on the hot path.
  const double inv_w = 1.0 / a[0][0][3];
  auto xyz = [&](int k, int l) { return Vec3d{a[k][l][0], a[k][l][1], a[k][l][2]}; };
  const Vec3d p = xyz(0, 0) * inv_w;
  out[0] = p;
  if constexpr (Order >= 1) {
    const double wu1 = a[1][0][3];
    const double wv1 = a[0][1][3];
    const Vec3d su = (xyz(1, 0) - wu1 * p) * inv_w;
    const Vec3d sv = (xyz(0, 1) - wv1 * p) * inv_w;
    out[1] = su;
    out[2] = sv;
    if constexpr (Order >= 2) {
      out[3] = (xyz(2, 0) - 2.0 * wu1 * su - a[2][0][3] * p) * inv_w;
      out[4] = (xyz(1, 1) - wu1 * sv - wv1 * su - a[1][1][3] * p) * inv_w;
      out[5] = (xyz(0, 2) - 2.0 * wv1 * sv - a[0][2][3] * p) * inv_w;
    }
  }
}

// One row of the net contracted with the u basis: t[k] = sum_i N_i^(k)(u) (w P, w)_i for k <=
// Order, i from the first control point of the span. t is the caller's local array (so that the
// compiler keeps it in registers: a pointer into memory might alias the weights).
template <int Order, int FixedU = -1>
[[gnu::always_inline]] inline void contract_row(int pu_run, const Vec3d* pts, const double* wts,
                                                const double* nu, double (&t)[Order + 1][4]) {
  const int pu = FixedU >= 0 ? FixedU : pu_run;
  const int wu = pu + 1;
  for (int i = 0; i <= pu; ++i) {
    const double w = wts[i];
    const double pw[4] = {pts[i].x * w, pts[i].y * w, pts[i].z * w, w};
    for (int k = 0; k <= Order; ++k) {
      const double b = nu[k * wu + i];
      for (int c = 0; c < 4; ++c) t[k][c] += b * pw[c];
    }
  }
}

// Adds row j's contraction, weighted by the v basis, to a[k][l] for k + l <= Order.
template <int Order, int FixedV = -1>
[[gnu::always_inline]] inline void add_row(int pv_run, int j, const double* nv,
                                           const double (&t)[Order + 1][4],
                                           double (&a)[Order + 1][Order + 1][4]) {
  const int wv = (FixedV >= 0 ? FixedV : pv_run) + 1;
  for (int l = 0; l <= Order; ++l) {
    const double b = nv[l * wv + j];
    for (int k = 0; k + l <= Order; ++k) {
      for (int c = 0; c < 4; ++c) a[k][l][c] += b * t[k][c];
    }
  }
}

// Sums the homogeneous derivatives A(k, l) = sum_ij N_i^(k)(u) N_j^(l)(v) (w P, w)_ij for
// k + l <= Order, then applies the quotient rule. nu and nv point at a ders_basis_funs block of at
// least Order + 1 rows. The summation order is fixed (rows of the net j outside, u inside) and is
// the same for every Order, so positions do not depend on how many derivatives were asked for.
// FixedU / FixedV >= 0 are the degrees known at compile time (same operations in the same
// order: bit-identical to the run-time degrees, with the loops unrolled).
template <int Order, int FixedU = -1, int FixedV = -1>
void combine_order(const SurfaceArrays& s, int span_u, const double* nu, int span_v,
                   const double* nv, Vec3d* out) {
  const int pu = FixedU >= 0 ? FixedU : s.degree_u;
  const int pv = FixedV >= 0 ? FixedV : s.degree_v;
  double a[Order + 1][Order + 1][4] = {};
  const std::size_t count_u = static_cast<std::size_t>(s.count_u);
  const Vec3d* net = s.points.data() + (span_u - pu);
  const double* net_w = s.weights.data() + (span_u - pu);
  for (int j = 0; j <= pv; ++j) {
    const std::size_t row = count_u * static_cast<std::size_t>(span_v - pv + j);
    double t[Order + 1][4] = {};
    contract_row<Order, FixedU>(pu, net + row, net_w + row, nu, t);
    add_row<Order, FixedV>(pv, j, nv, t, a);
  }
  finish<Order>(a, out);
}

// combine_order over a whole grid: each u parameter's contraction with the net rows of a v
// span is computed once and serves every v parameter in that span (the same sums in the same
// order as combine_order, so the same bits). rows: scratch.
template <int Order, int FixedU = -1, int FixedV = -1>
void grid_order(const SurfaceArrays& s, const BasisTable& bu, const BasisTable& bv,
                std::vector<double>& rows, Vec3d* out) {
  const int pu = FixedU >= 0 ? FixedU : s.degree_u;
  const int pv = FixedV >= 0 ? FixedV : s.degree_v;
  using Row = double[Order + 1][4];
  constexpr std::size_t kOut = Order == 0 ? 1 : (Order == 1 ? 3 : 6);
  const std::size_t block_u = static_cast<std::size_t>(bu.order + 1) * (bu.degree + 1);
  const std::size_t block_v = static_cast<std::size_t>(bv.order + 1) * (bv.degree + 1);
  const std::size_t nu = bu.spans.size();
  const std::size_t count_u = static_cast<std::size_t>(s.count_u);
  rows.resize(static_cast<std::size_t>(pv + 1) * nu * sizeof(Row) / sizeof(double));
  Row* row_of = reinterpret_cast<Row*>(rows.data());  // [j * nu + i]
  int rows_span = -1;
  for (std::size_t jv = 0; jv < bv.spans.size(); ++jv) {
    const int span_v = bv.spans[jv];
    if (span_v != rows_span) {
      for (int j = 0; j <= pv; ++j) {
        const std::size_t row = count_u * static_cast<std::size_t>(span_v - pv + j);
        for (std::size_t i = 0; i < nu; ++i) {
          const std::size_t first = row + static_cast<std::size_t>(bu.spans[i] - pu);
          Row t = {};
          contract_row<Order, FixedU>(pu, s.points.data() + first, s.weights.data() + first,
                                      &bu.values[block_u * i], t);
          std::copy(&t[0][0], &t[0][0] + sizeof(Row) / sizeof(double),
                    &row_of[static_cast<std::size_t>(j) * nu + i][0][0]);
        }
      }
      rows_span = span_v;
    }
    const double* nvj = &bv.values[block_v * jv];
    for (std::size_t i = 0; i < nu; ++i) {
      double a[Order + 1][Order + 1][4] = {};
      for (int j = 0; j <= pv; ++j) {
        add_row<Order, FixedV>(pv, j, nvj, row_of[static_cast<std::size_t>(j) * nu + i], a);
      }
      finish<Order>(a, &out[(i + nu * jv) * kOut]);
    }
  }
}

void combine(const SurfaceArrays& s, int span_u, const double* nu, int span_v, const double* nv,
             int order, Vec3d* out) {
  constexpr int kCubic = detail::kCommonDegree;
  if (s.degree_u == kCubic && s.degree_v == kCubic) {
    switch (order) {
      case 0:
        combine_order<0, kCubic, kCubic>(s, span_u, nu, span_v, nv, out);
        return;
      case 1:
        combine_order<1, kCubic, kCubic>(s, span_u, nu, span_v, nv, out);
        return;
      default:
        combine_order<2, kCubic, kCubic>(s, span_u, nu, span_v, nv, out);
        return;
    }
  }
  switch (order) {
    case 0:
      combine_order<0>(s, span_u, nu, span_v, nv, out);
      break;
    case 1:
      combine_order<1>(s, span_u, nu, span_v, nv, out);
      break;
    default:
      combine_order<2>(s, span_u, nu, span_v, nv, out);
      break;
  }
}

// Span and basis block of one direction at one parameter (clamped into the knot range).
int direction_basis(int degree, int count, const double* knots, double t, int order, double* ders) {
  t = clamp_param(degree, count, knots, t);
  const int span = find_span(degree, count, knots, t);
  ders_basis_funs(span, t, degree, order, knots, ders);
  return span;
}

// The unit normal from Su and Sv, or false when normal_degenerate (one cross product, shared).
bool unit_normal(const Vec3d& su, const Vec3d& sv, double du, double dv, Vec3d& n) {
  const Vec3d c = cross(su, sv);
  const double len = norm(c);
  const double edges = norm(su) * du + norm(sv) * dv;
  if (!(len * du * dv > kDegenerateRatio * edges * edges)) return false;
  n = c * (1.0 / len);
  return true;
}

}  // namespace

void surface_derivs(const SurfaceArrays& s, double u, double v, int order, Vec3d* out) {
  order = std::clamp(order, 0, kMaxOrder);
  double nu[(kMaxOrder + 1) * (kMaxDegree + 1)];
  double nv[(kMaxOrder + 1) * (kMaxDegree + 1)];
  const int span_u = direction_basis(s.degree_u, s.count_u, s.knots_u.data(), u, order, nu);
  const int span_v = direction_basis(s.degree_v, s.count_v, s.knots_v.data(), v, order, nv);
  combine(s, span_u, nu, span_v, nv, order, out);
}

Vec3d surface_point(const SurfaceArrays& s, double u, double v) {
  Vec3d p;
  surface_derivs(s, u, v, 0, &p);
  return p;
}

bool normal_degenerate(const Vec3d& su, const Vec3d& sv, double du, double dv, double ratio) {
  const double len = norm(cross(su, sv));
  const double edges = norm(su) * du + norm(sv) * dv;
  return !(len * du * dv > ratio * edges * edges);
}

bool regular_param(const SurfaceArrays& s, double& u, double& v, double ratio) {
  static constexpr double kSteps[] = {0.0, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 0.5, 1.0};
  const double du = s.u1 - s.u0;
  const double dv = s.v1 - s.v0;
  const double cu = 0.5 * (s.u0 + s.u1);
  const double cv = 0.5 * (s.v0 + s.v1);
  const double u_in = std::clamp(u, std::min(s.u0, s.u1), std::max(s.u0, s.u1));
  const double v_in = std::clamp(v, std::min(s.v0, s.v1), std::max(s.v0, s.v1));
  for (const double f : kSteps) {
    const double ut = u_in + f * (cu - u_in);
    const double vt = v_in + f * (cv - v_in);
    Vec3d d[3];
    surface_derivs(s, ut, vt, 1, d);
    if (!normal_degenerate(d[1], d[2], du, dv, ratio)) {
      u = ut;
      v = vt;
      return true;
    }
  }
  u = u_in;
  v = v_in;
  return false;
}

Vec3d surface_normal(const SurfaceArrays& s, double u, double v) {
  const double du = s.u1 - s.u0;
  const double dv = s.v1 - s.v0;
  Vec3d d[3];
  Vec3d n;
  surface_derivs(s, u, v, 1, d);
  if (unit_normal(d[1], d[2], du, dv, n)) return n;
  if (!regular_param(s, u, v)) return Vec3d{};
  surface_derivs(s, u, v, 1, d);
  return unit_normal(d[1], d[2], du, dv, n) ? n : Vec3d{};
}

void basis_table(int degree, int count, std::span<const double> knots,
                 std::span<const double> params, int order, BasisTable& out) {
  order = std::clamp(order, 0, kMaxOrder);
  const std::size_t block = static_cast<std::size_t>(order + 1) * (degree + 1);
  out.degree = degree;
  out.order = order;
  out.spans.resize(params.size());
  out.values.resize(block * params.size());
  for (std::size_t i = 0; i < params.size(); ++i) {
    out.spans[i] =
        direction_basis(degree, count, knots.data(), params[i], order, &out.values[block * i]);
  }
}

void surface_grid_rows(const SurfaceArrays& s, std::span<const double> us,
                       std::span<const double> vs, const BasisTable& bu, const BasisTable& bv,
                       std::size_t row_begin, std::size_t row_end, std::span<Vec3d> positions,
                       std::span<Vec3d> normals) {
  const bool with_normals = !normals.empty();
  const int order = with_normals ? 1 : 0;
  const std::size_t block_u = static_cast<std::size_t>(bu.order + 1) * (bu.degree + 1);
  const std::size_t block_v = static_cast<std::size_t>(bv.order + 1) * (bv.degree + 1);
  const double du = s.u1 - s.u0;
  const double dv = s.v1 - s.v0;
  const std::size_t nu = us.size();
  for (std::size_t j = row_begin; j < row_end; ++j) {
    const double* bvj = &bv.values[block_v * j];
    for (std::size_t i = 0; i < nu; ++i) {
      Vec3d d[3];
      combine(s, bu.spans[i], &bu.values[block_u * i], bv.spans[j], bvj, order, d);
      const std::size_t k = i + nu * j;
      positions[k] = d[0];
      if (with_normals && !unit_normal(d[1], d[2], du, dv, normals[k])) {
        normals[k] = surface_normal(s, us[i], vs[j]);
      }
    }
  }
}

void surface_grid_derivs(const SurfaceArrays& s, const BasisTable& bu, const BasisTable& bv,
                         int order, std::span<Vec3d> out) {
  order = std::clamp(order, 0, std::min(bu.order, bv.order));
  thread_local std::vector<double> rows;
  constexpr int kCubic = detail::kCommonDegree;
  const bool cubic = s.degree_u == kCubic && s.degree_v == kCubic;
  switch (order) {
    case 0:
      cubic ? grid_order<0, kCubic, kCubic>(s, bu, bv, rows, out.data())
            : grid_order<0>(s, bu, bv, rows, out.data());
      return;
    case 1:
      cubic ? grid_order<1, kCubic, kCubic>(s, bu, bv, rows, out.data())
            : grid_order<1>(s, bu, bv, rows, out.data());
      return;
    default:
      cubic ? grid_order<2, kCubic, kCubic>(s, bu, bv, rows, out.data())
            : grid_order<2>(s, bu, bv, rows, out.data());
      return;
  }
}

void surface_points(const SurfaceArrays& s, std::span<const Vec2d> uv, std::size_t begin,
                    std::size_t end, std::span<Vec3d> positions, std::span<Vec3d> normals) {
  const bool with_normals = !normals.empty();
  const double du = s.u1 - s.u0;
  const double dv = s.v1 - s.v0;
  for (std::size_t k = begin; k < end; ++k) {
    Vec3d d[3];
    surface_derivs(s, uv[k].x, uv[k].y, with_normals ? 1 : 0, d);
    positions[k] = d[0];
    if (with_normals && !unit_normal(d[1], d[2], du, dv, normals[k])) {
      normals[k] = surface_normal(s, uv[k].x, uv[k].y);
    }
  }
}

void curve_derivs(int degree, std::span<const double> knots, std::span<const Vec3d> points,
                  std::span<const double> weights, double t, int order, Vec3d* out) {
  order = std::clamp(order, 0, 1);
  const int count = static_cast<int>(points.size());
  double n[2 * (kMaxDegree + 1)];
  const int span = direction_basis(degree, count, knots.data(), t, order, n);
  const int w = degree + 1;
  double a[2][4] = {};
  for (int i = 0; i <= degree; ++i) {
    const int idx = span - degree + i;
    const double wt = weights[idx];
    const double pw[4] = {points[idx].x * wt, points[idx].y * wt, points[idx].z * wt, wt};
    for (int k = 0; k <= order; ++k) {
      for (int c = 0; c < 4; ++c) a[k][c] += n[k * w + i] * pw[c];
    }
  }
  const Vec3d c = Vec3d{a[0][0], a[0][1], a[0][2]} / a[0][3];
  out[0] = c;
  if (order < 1) return;
  out[1] = (Vec3d{a[1][0], a[1][1], a[1][2]} - a[1][3] * c) / a[0][3];
}

}  // namespace hm::kernel
