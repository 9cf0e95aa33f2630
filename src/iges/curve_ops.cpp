#include "iges/curve_ops.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"

namespace hm::iges {
namespace {

// Homogeneous control point (w x, w y, w z, w).
struct H4 {
  double x = 0, y = 0, z = 0, w = 1;
};

H4 lift(const Vec3d& p, double w) { return {p.x * w, p.y * w, p.z * w, w}; }
H4 mix(const H4& a, const H4& b, double s) {  // (1 - s) a + s b
  return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.z + s * (b.z - a.z),
          a.w + s * (b.w - a.w)};
}

std::vector<H4> lift_all(const NurbsCurve& c) {
  std::vector<H4> h(c.points.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double w = i < c.weights.size() ? c.weights[i] : 1.0;
    h[i] = lift(c.points[i], w);
  }
  return h;
}

void drop_all(const std::vector<H4>& h, NurbsCurve& c) {
  c.points.resize(h.size());
  c.weights.resize(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double w = h[i].w;
    c.weights[i] = w;
    c.points[i] = w != 0 ? Vec3d{h[i].x / w, h[i].y / w, h[i].z / w} : Vec3d{};
  }
}

// Knots are sorted: a binary search keeps this O(log n).
int multiplicity(const std::vector<double>& k, double u) {
  const auto [lo, hi] = std::equal_range(k.begin(), k.end(), u);
  return static_cast<int>(hi - lo);
}

double binomial(int n, int k) {
  double r = 1;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

}  // namespace

void reverse_curve(NurbsCurve& c) {
  std::reverse(c.points.begin(), c.points.end());
  std::reverse(c.weights.begin(), c.weights.end());
  const double a = c.knots.empty() ? 0 : c.knots.front();
  const double b = c.knots.empty() ? 0 : c.knots.back();
  std::reverse(c.knots.begin(), c.knots.end());
  for (double& k : c.knots) k = a + b - k;
  const double t0 = a + b - c.t1, t1 = a + b - c.t0;
  c.t0 = t0;
  c.t1 = t1;
}

void reparametrize(NurbsCurve& c, double a, double b) {
  const double s = (b - a) / (c.t1 - c.t0);
  const double t0 = c.t0, t1 = c.t1;
  // The end of the range maps to b exactly: two curves put on the same range must share their
  // end knots bit for bit (make_compatible matches knots by value).
  for (double& k : c.knots) k = k == t1 ? b : a + (k - t0) * s;
  c.t0 = a;
  c.t1 = b;
}

// Span index i with U[i] <= u < U[i + 1], in [p, n - 1] (n control points).
int find_span(const std::vector<double>& U, int p, int n, double u) {
  if (u >= U[static_cast<std::size_t>(n)]) return n - 1;
  if (u <= U[static_cast<std::size_t>(p)]) return p;
  const int k = static_cast<int>(std::upper_bound(U.begin(), U.end(), u) - U.begin()) - 1;
  return std::clamp(k, p, n - 1);
}

void refine_knots(NurbsCurve& c, const std::vector<double>& x) {
  if (x.empty()) return;
  // A5.4 writes out of bounds for knots outside the domain or out of order: refuse them.
  if (c.degree < 1 || c.knots.size() != c.points.size() + c.degree + 1 ||
      !std::is_sorted(x.begin(), x.end()) || !(x.front() >= c.knots[c.degree]) ||
      !(x.back() <= c.knots[c.points.size()])) {
    throw GeometryError("knot insertion outside the curve's domain");
  }
  // Knot refinement in one pass (Piegl & Tiller, The NURBS Book, A5.4): O((n + r) p).
  const int p = c.degree;
  const int n = c.count();  // control points
  const int r = static_cast<int>(x.size());
  const std::vector<double>& U = c.knots;
  const std::vector<H4> P = lift_all(c);
  std::vector<H4> Q(static_cast<std::size_t>(n + r));
  std::vector<double> Ub(U.size() + x.size());
  const int a = find_span(U, p, n, x.front());
  const int b = find_span(U, p, n, x.back()) + 1;
  auto at = [](auto& v, int i) -> auto& { return v[static_cast<std::size_t>(i)]; };
  for (int j = 0; j <= a - p; ++j) at(Q, j) = at(P, j);
  for (int j = b - 1; j < n; ++j) at(Q, j + r) = at(P, j);
  for (int j = 0; j <= a; ++j) at(Ub, j) = at(U, j);
  for (int j = b + p; j < static_cast<int>(U.size()); ++j) at(Ub, j + r) = at(U, j);
  int i = b + p - 1, k = b + p + r - 1;
  for (int j = r - 1; j >= 0; --j) {
    while (at(x, j) <= at(U, i) && i > a) {
      at(Q, k - p - 1) = at(P, i - p - 1);
      at(Ub, k) = at(U, i);
      --k;
      --i;
    }
    at(Q, k - p - 1) = at(Q, k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alpha = at(Ub, k + l) - at(x, j);
      if (alpha == 0.0) {
        at(Q, ind - 1) = at(Q, ind);
      } else {
        const double den = at(Ub, k + l) - at(U, i - p + l);
        alpha = den != 0 ? alpha / den : 0.0;
        at(Q, ind - 1) = mix(at(Q, ind), at(Q, ind - 1), alpha);
      }
    }
    at(Ub, k) = at(x, j);
    --k;
  }
  c.knots = std::move(Ub);
  drop_all(Q, c);
}

void insert_knot(NurbsCurve& c, double u, int times) {
  if (times > 0) refine_knots(c, std::vector<double>(static_cast<std::size_t>(times), u));
}

void clamp_to_range(NurbsCurve& c) {
  const int p = c.degree;
  std::vector<double> add;
  for (double t : {c.t0, c.t1}) {
    const int have = multiplicity(c.knots, t);
    for (int k = have; k < p; ++k) add.push_back(t);
  }
  refine_knots(c, add);
  const std::vector<double>& U = c.knots;
  // s: last knot equal to t0; e: first knot equal to t1.
  const int s = static_cast<int>(std::upper_bound(U.begin(), U.end(), c.t0) - U.begin()) - 1;
  const int e = static_cast<int>(std::lower_bound(U.begin(), U.end(), c.t1) - U.begin());
  std::vector<double> knots(static_cast<std::size_t>(p + 1), c.t0);
  knots.insert(knots.end(), U.begin() + s + 1, U.begin() + e);
  knots.insert(knots.end(), static_cast<std::size_t>(p + 1), c.t1);
  const int first = s - p, last = e - 1;
  std::vector<Vec3d> pts(c.points.begin() + first, c.points.begin() + last + 1);
  std::vector<double> w(c.weights.begin() + first, c.weights.begin() + last + 1);
  c.knots = std::move(knots);
  c.points = std::move(pts);
  c.weights = std::move(w);
}

bool elevate_degree(NurbsCurve& c, int target, std::uint64_t max_points) {
  const int p = c.degree, t = target - p;
  if (t <= 0) return true;
  // Distinct interior breakpoints.
  std::vector<double> breaks;
  for (std::size_t i = static_cast<std::size_t>(p) + 1;
       i + static_cast<std::size_t>(p) + 1 < c.knots.size(); ++i) {
    if (breaks.empty() || breaks.back() != c.knots[i]) breaks.push_back(c.knots[i]);
  }
  const std::uint64_t segments = breaks.size() + 1;
  if (segments * static_cast<std::uint64_t>(target) + 1 > max_points) return false;
  std::vector<double> add;
  for (double b : breaks) {
    for (int k = multiplicity(c.knots, b); k < p; ++k) add.push_back(b);
  }
  refine_knots(c, add);
  if (c.points.size() != segments * static_cast<std::uint64_t>(p) + 1) return false;
  const std::vector<H4> pts = lift_all(c);
  std::vector<H4> out;
  out.reserve(segments * static_cast<std::uint64_t>(target) + 1);
  for (std::uint64_t sgm = 0; sgm < segments; ++sgm) {
    const H4* q = &pts[sgm * static_cast<std::uint64_t>(p)];
    for (int i = sgm == 0 ? 0 : 1; i <= target; ++i) {
      H4 r{0, 0, 0, 0};
      for (int j = std::max(0, i - t); j <= std::min(p, i); ++j) {
        const double f = binomial(p, j) * binomial(t, i - j) / binomial(target, i);
        r.x += f * q[j].x;
        r.y += f * q[j].y;
        r.z += f * q[j].z;
        r.w += f * q[j].w;
      }
      out.push_back(r);
    }
  }
  std::vector<double> knots(static_cast<std::size_t>(target + 1), c.knots.front());
  for (double b : breaks) knots.insert(knots.end(), static_cast<std::size_t>(target), b);
  knots.insert(knots.end(), static_cast<std::size_t>(target + 1), c.knots.back());
  c.knots = std::move(knots);
  c.degree = target;
  drop_all(out, c);
  return true;
}

bool make_compatible(NurbsCurve& a, NurbsCurve& b, std::uint64_t max_points) {
  const int p = std::max(a.degree, b.degree);
  if (!elevate_degree(a, p, max_points) || !elevate_degree(b, p, max_points)) return false;
  // Union of the interior knots with the larger multiplicity of each value (at most p, so the
  // curve stays continuous). End knots are left alone: both curves are clamped on the same
  // range, and a value a rounding error away from an end must not be inserted as a new knot.
  auto missing = [p](const std::vector<double>& from, const std::vector<double>& into) {
    std::vector<double> out;
    const double lo = into[static_cast<std::size_t>(p)];
    const double hi = into[into.size() - 1 - static_cast<std::size_t>(p)];
    std::size_t i = 0;
    while (i < from.size()) {
      std::size_t j = i;
      while (j < from.size() && from[j] == from[i]) ++j;
      if (from[i] > lo && from[i] < hi) {
        const int want = std::min(static_cast<int>(j - i), p);
        const int need = want - multiplicity(into, from[i]);
        for (int k = 0; k < need; ++k) out.push_back(from[i]);
      }
      i = j;
    }
    return out;
  };
  const std::vector<double> add_to_a = missing(b.knots, a.knots);
  const std::vector<double> add_to_b = missing(a.knots, b.knots);
  if (a.points.size() + add_to_a.size() > max_points ||
      b.points.size() + add_to_b.size() > max_points) {
    return false;
  }
  refine_knots(a, add_to_a);
  refine_knots(b, add_to_b);
  return a.count() == b.count() && a.knots.size() == b.knots.size();
}

bool join_chain(const std::vector<NurbsCurve>& chain, std::uint64_t max_points, NurbsCurve& out) {
  if (chain.empty()) return false;
  int p = 1;
  for (const NurbsCurve& c : chain) p = std::max(p, c.degree);
  out = NurbsCurve{};
  out.degree = p;
  double at = chain.front().t0;
  for (std::size_t k = 0; k < chain.size(); ++k) {
    NurbsCurve c = chain[k];
    clamp_to_range(c);
    if (!elevate_degree(c, p, max_points)) return false;
    const double len = c.t1 - c.t0;
    reparametrize(c, at, at + len);
    if (out.points.size() + c.points.size() > max_points) return false;
    if (k == 0) {
      out = c;
    } else {
      // Scale the new piece's weights so that the shared point has one weight.
      const double s = out.weights.back() / c.weights.front();
      for (double& w : c.weights) w *= s;
      out.points.back() = 0.5 * (out.points.back() + c.points.front());
      out.points.insert(out.points.end(), c.points.begin() + 1, c.points.end());
      out.weights.insert(out.weights.end(), c.weights.begin() + 1, c.weights.end());
      out.knots.resize(out.knots.size() - 1);  // end knot: multiplicity p + 1 -> p
      out.knots.insert(out.knots.end(), c.knots.begin() + p + 1, c.knots.end());
    }
    at += len;
  }
  out.t0 = out.knots.front();
  out.t1 = out.knots.back();
  return true;
}

NurbsCurve rational_arc(const Vec3d& c, const Vec3d& x, const Vec3d& y, double theta0,
                        double theta1) {
  const double sweep = theta1 - theta0;
  const int n =
      std::max(1, static_cast<int>(std::ceil(std::fabs(sweep) / (0.5 * std::numbers::pi) - 1e-9)));
  const double d = sweep / n;
  const double wm = std::cos(0.5 * d);
  NurbsCurve a;
  a.degree = 2;
  a.knots.assign(3, theta0);
  for (int k = 0; k <= n; ++k) {
    const double th = theta0 + k * d;
    if (k > 0) {
      const double mid = th - 0.5 * d;
      a.points.push_back(c + (std::cos(mid) * x + std::sin(mid) * y) / wm);
      a.weights.push_back(wm);
      const double knot = k == n ? theta1 : th;
      a.knots.insert(a.knots.end(), k == n ? 3 : 2, knot);
    }
    const double tk = k == n ? theta1 : th;
    a.points.push_back(c + std::cos(tk) * x + std::sin(tk) * y);
    a.weights.push_back(1.0);
  }
  a.t0 = theta0;
  a.t1 = theta1;
  return a;
}

double control_extent(const NurbsCurve& c) {
  double e = 0;
  for (std::size_t i = 1; i < c.points.size(); ++i)
    e = std::max(e, norm(c.points[i] - c.points[i - 1]));
  return e;
}

}  // namespace hm::iges
