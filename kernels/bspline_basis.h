// B-spline basis functions on raw knot arrays (Piegl & Tiller, The NURBS Book, A2.1-A2.3).
// Written once: surfaces, curves and the batched kernel all call these, so a point evaluated one
// at a time and the same point evaluated in a batch go through identical arithmetic.
#pragma once

#include <algorithm>
#include <cmath>

namespace hm::kernel {

// Largest degree the basis routines accept (their scratch arrays live on the stack). Equal to the
// default ResourceLimits::max_degree; validate_surface/validate_curve reject anything larger.
inline constexpr int kMaxDegree = 40;
// Highest derivative order the surface kernel computes.
inline constexpr int kMaxOrder = 2;

// Clamps t into the valid parameter range [knots[degree], knots[count]] of a B-spline with
// `count` control points. NaN passes through (and evaluates to NaN, never loops).
inline double clamp_param(int degree, int count, const double* knots, double t) {
  const double lo = knots[degree];
  const double hi = knots[count];
  return t < lo ? lo : (t > hi ? hi : t);
}

// A knot span narrower than this fraction of the knots' scale holds nothing a double resolves:
// the derivatives evaluated in it are rounding noise divided by its width. Such spans come from
// knot arithmetic (a sub-patch cut 1.1e-16 before an existing knot leaves a span that wide after
// its clamped start: property seed 4877), in CAD files as in our generator. 1e-12 is ten thousand
// ulps, far below any knot spacing a modeller means.
inline constexpr double kEmptySpan = 1e-12;

// Span index s in [degree, count - 1] with knots[s] <= t < knots[s + 1] and a span that is not
// empty (wider than kEmptySpan of the knots' scale). In an empty span, t is evaluated on the
// nearest span to its right (the polynomial there extends over the empty width continuously),
// or, at the upper end, on the last one that is not empty, so domain ends evaluate from the
// inside. Repeated interior knots (knuckles) give the span on the right of the knot.
inline int find_span(int degree, int count, const double* knots, double t) {
  const double lo = knots[degree];
  const double hi = knots[count];
  const double width = kEmptySpan * std::max(hi - lo, std::max(std::abs(lo), std::abs(hi)));
  const auto empty = [&](int s) { return !(knots[s + 1] - knots[s] > width); };
  const double* first = knots + degree + 1;
  const double* last = knots + count;
  int s = static_cast<int>(std::upper_bound(first, last, t) - knots) - 1;
  if (!empty(s)) return s;
  for (int r = s + 1; r < count; ++r)
    if (!empty(r)) return r;
  while (s > degree && empty(s)) --s;
  return s;
}

namespace detail {

// Scratch arrays sized for degrees up to Cap - 1: small ones for the common low degrees keep the
// stack frame small, the large ones serve up to kMaxDegree. Same arithmetic in both. Fixed >= 0
// is the degree known at compile time (the loops unroll; the operations and their order are the
// same, so the results are bit-identical to the run-time degree's); FixedN likewise for the
// derivative order.
template <int Cap, int Fixed = -1>
void basis_funs(int span, double t, int run_degree, const double* knots, double* out) {
  const int degree = Fixed >= 0 ? Fixed : run_degree;
  double left[Cap];
  double right[Cap];
  out[0] = 1.0;
  for (int j = 1; j <= degree; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double temp = out[r] / (right[r + 1] + left[j - r]);
      out[r] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    out[j] = saved;
  }
}

template <int Cap, int Fixed = -1, int FixedN = -1>
void ders_basis_funs(int span, double t, int degree, int run_n, const double* knots, double* ders) {
  const int p = Fixed >= 0 ? Fixed : degree;
  const int n = FixedN >= 0 ? FixedN : run_n;
  const int w = p + 1;
  // ndu(j, r) = ndu[j * w + r]: upper triangle basis values, lower triangle knot differences.
  double ndu[Cap * Cap];
  double left[Cap];
  double right[Cap];
  double a[2][Cap];
  ndu[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j * w + r] = right[r + 1] + left[j - r];
      const double temp = ndu[r * w + j - 1] / ndu[j * w + r];
      ndu[r * w + j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j * w + j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[j] = ndu[j * w + p];
  for (int k = p + 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * w + j] = 0.0;
  }
  const int nk = std::min(n, p);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0;
    int s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= nk; ++k) {
      double d = 0.0;
      const int rk = r - k;
      const int pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[(pk + 1) * w + rk];
        d = a[s2][0] * ndu[rk * w + pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[(pk + 1) * w + rk + j];
        d += a[s2][j] * ndu[(rk + j) * w + pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[(pk + 1) * w + r];
        d += a[s2][k] * ndu[r * w + pk];
      }
      ders[k * w + r] = d;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int k = 1; k <= nk; ++k) {
    for (int j = 0; j <= p; ++j) ders[k * w + j] *= factor;
    factor *= p - k;
  }
}

inline constexpr int kSmallCap = 8;
// Cubic: nearly every hull patch (ship_449's 449 are all bicubic), and the surface kernel's
// hottest evaluations. It gets its own compiled copy of the routines.
inline constexpr int kCommonDegree = 3;

}  // namespace detail

// The degree + 1 non-zero basis functions at t in span `span` (A2.2); out[0..degree].
inline void basis_funs(int span, double t, int degree, const double* knots, double* out) {
  if (degree == detail::kCommonDegree) {
    detail::basis_funs<detail::kCommonDegree + 1, detail::kCommonDegree>(span, t, degree, knots,
                                                                         out);
  } else if (degree < detail::kSmallCap) {
    detail::basis_funs<detail::kSmallCap>(span, t, degree, knots, out);
  } else {
    detail::basis_funs<kMaxDegree + 1>(span, t, degree, knots, out);
  }
}

// Basis functions and their derivatives up to order n (A2.3). ders is (n + 1) x (degree + 1),
// row k holding the k-th derivatives: ders[k * (degree + 1) + j]. Row 0 is bit-identical to
// basis_funs (same operations in the same order). Derivatives above the degree are zero.
inline void ders_basis_funs(int span, double t, int degree, int n, const double* knots,
                            double* ders) {
  if (n == 0) {
    basis_funs(span, t, degree, knots, ders);
  } else if (degree == detail::kCommonDegree) {
    constexpr int kCap = detail::kCommonDegree + 1;
    constexpr int kP = detail::kCommonDegree;
    if (n == 1) {
      detail::ders_basis_funs<kCap, kP, 1>(span, t, degree, n, knots, ders);
    } else if (n == 2) {
      detail::ders_basis_funs<kCap, kP, 2>(span, t, degree, n, knots, ders);
    } else {
      detail::ders_basis_funs<kCap, kP>(span, t, degree, n, knots, ders);
    }
  } else if (degree < detail::kSmallCap) {
    detail::ders_basis_funs<detail::kSmallCap>(span, t, degree, n, knots, ders);
  } else {
    detail::ders_basis_funs<kMaxDegree + 1>(span, t, degree, n, knots, ders);
  }
}

}  // namespace hm::kernel
