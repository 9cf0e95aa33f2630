#include "nurbs/knot_ops.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace hm {
namespace {

void check_sizes_u(const NurbsSurface& s) {
  const std::size_t n = static_cast<std::size_t>(s.count_u) * static_cast<std::size_t>(s.count_v);
  if (s.degree_u < 1 || s.degree_v < 1 || s.count_u <= s.degree_u || s.count_v <= s.degree_v ||
      s.knots_u.size() != static_cast<std::size_t>(s.count_u + s.degree_u + 1) ||
      s.knots_v.size() != static_cast<std::size_t>(s.count_v + s.degree_v + 1) ||
      s.points.size() != n || s.weights.size() != n) {
    throw GeometryError("knot operation on a malformed surface (degree " +
                        std::to_string(s.degree_u) + "x" + std::to_string(s.degree_v) + ", net " +
                        std::to_string(s.count_u) + "x" + std::to_string(s.count_v) + ")");
  }
}

// One Boehm insertion of t in u. Column i of the new net is a blend of old columns i - 1 and i;
// columns with blend factor 0 or 1 are copied so that untouched rows stay bit-identical.
NurbsSurface insert_once_u(const NurbsSurface& s, double t) {
  const int p = s.degree_u;
  const int n = s.count_u;
  const std::vector<double>& knots = s.knots_u;
  const int k = std::min<int>(
      static_cast<int>(std::upper_bound(knots.begin(), knots.end(), t) - knots.begin()) - 1, n - 1);
  NurbsSurface r = s;
  r.count_u = n + 1;
  r.knots_u.insert(r.knots_u.begin() + k + 1, t);
  r.points.assign(static_cast<std::size_t>(n + 1) * s.count_v, Vec3d{});
  r.weights.assign(r.points.size(), 0.0);
  for (int j = 0; j < s.count_v; ++j) {
    const std::size_t in = static_cast<std::size_t>(n) * j;
    const std::size_t out = static_cast<std::size_t>(n + 1) * j;
    for (int i = 0; i <= n; ++i) {
      int src = i;  // copy from this old column unless blended
      if (i > k) src = i - 1;
      if (i >= k - p + 1 && i <= k) {
        const double alpha = (t - knots[i]) / (knots[i + p] - knots[i]);
        if (alpha <= 0.0) {
          src = i - 1;
        } else if (alpha < 1.0) {
          const double wa = alpha * s.weights[in + i];
          const double wb = (1.0 - alpha) * s.weights[in + i - 1];
          const double w = wa + wb;
          r.weights[out + i] = w;
          r.points[out + i] = (wa * s.points[in + i] + wb * s.points[in + i - 1]) / w;
          continue;
        }
      }
      r.points[out + i] = s.points[in + src];
      r.weights[out + i] = s.weights[in + src];
    }
  }
  return r;
}

void check_inside_u(const NurbsSurface& s, double t) {
  const double lo = s.knots_u[s.degree_u];
  const double hi = s.knots_u[s.count_u];
  if (!(t > lo && t < hi)) {
    throw GeometryError("knot " + std::to_string(t) + " is not strictly inside the knot range [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
}

NurbsSurface insert_u(const NurbsSurface& s, double t, int times) {
  check_sizes_u(s);
  check_inside_u(s, t);
  if (knot_multiplicity(s.knots_u, t) + times > s.degree_u + 1) {
    throw GeometryError("knot insertion beyond multiplicity degree + 1");
  }
  NurbsSurface r = s;
  for (int m = 0; m < times; ++m) r = insert_once_u(r, t);
  return r;
}

// Brings each break to multiplicity >= degree, then slices the pieces (see split_u in the header).
std::vector<NurbsSurface> split_pieces_u(const NurbsSurface& s, const std::vector<double>& breaks) {
  check_sizes_u(s);
  if (breaks.size() < 2) throw GeometryError("split needs at least two break values");
  for (std::size_t k = 1; k < breaks.size(); ++k) {
    if (!(breaks[k] > breaks[k - 1])) throw GeometryError("split breaks must increase strictly");
  }
  const int p = s.degree_u;
  NurbsSurface r = s;
  for (double t : breaks) {
    const int mult = knot_multiplicity(r.knots_u, t);
    if (mult >= p) continue;
    check_inside_u(r, t);  // an unclamped end cannot be cut here
    for (int m = mult; m < p; ++m) r = insert_once_u(r, t);
  }
  const std::vector<double>& knots = r.knots_u;
  std::vector<NurbsSurface> pieces;
  pieces.reserve(breaks.size() - 1);
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double a = breaks[k];
    const double b = breaks[k + 1];
    const int a_last =
        static_cast<int>(std::upper_bound(knots.begin(), knots.end(), a) - knots.begin()) - 1;
    const int b_first =
        static_cast<int>(std::lower_bound(knots.begin(), knots.end(), b) - knots.begin());
    const int first = a_last - p;
    const int last = b_first - 1;
    if (first < 0 || last >= r.count_u || last - first < p) {
      throw GeometryError("split range outside the knot range of the surface");
    }
    NurbsSurface q;
    q.degree_u = p;
    q.degree_v = r.degree_v;
    q.count_u = last - first + 1;
    q.count_v = r.count_v;
    q.knots_u.assign(p + 1, a);
    q.knots_u.insert(q.knots_u.end(), knots.begin() + a_last + 1, knots.begin() + b_first);
    q.knots_u.insert(q.knots_u.end(), p + 1, b);
    q.knots_v = r.knots_v;
    q.points.reserve(static_cast<std::size_t>(q.count_u) * q.count_v);
    q.weights.reserve(q.points.capacity());
    for (int j = 0; j < r.count_v; ++j) {
      const std::size_t row = static_cast<std::size_t>(r.count_u) * j;
      q.points.insert(q.points.end(), r.points.begin() + row + first,
                      r.points.begin() + row + last + 1);
      q.weights.insert(q.weights.end(), r.weights.begin() + row + first,
                       r.weights.begin() + row + last + 1);
    }
    q.periodic_u = false;
    q.periodic_v = r.periodic_v;
    q.u0 = a;
    q.u1 = b;
    q.v0 = r.v0;
    q.v1 = r.v1;
    pieces.push_back(std::move(q));
  }
  return pieces;
}

}  // namespace

int knot_multiplicity(const std::vector<double>& knots, double t) {
  const auto range = std::equal_range(knots.begin(), knots.end(), t);
  return static_cast<int>(range.second - range.first);
}

NurbsSurface transpose_uv(const NurbsSurface& s) {
  NurbsSurface r;
  r.degree_u = s.degree_v;
  r.degree_v = s.degree_u;
  r.count_u = s.count_v;
  r.count_v = s.count_u;
  r.knots_u = s.knots_v;
  r.knots_v = s.knots_u;
  r.periodic_u = s.periodic_v;
  r.periodic_v = s.periodic_u;
  r.u0 = s.v0;
  r.u1 = s.v1;
  r.v0 = s.u0;
  r.v1 = s.u1;
  r.points.resize(s.points.size());
  r.weights.resize(s.weights.size());
  for (int j = 0; j < s.count_v; ++j) {
    for (int i = 0; i < s.count_u; ++i) {
      const std::size_t from =
          static_cast<std::size_t>(i) + static_cast<std::size_t>(s.count_u) * j;
      const std::size_t to = static_cast<std::size_t>(j) + static_cast<std::size_t>(s.count_v) * i;
      if (from < s.points.size()) r.points[to] = s.points[from];
      if (from < s.weights.size()) r.weights[to] = s.weights[from];
    }
  }
  return r;
}

NurbsSurface insert_knot_u(const NurbsSurface& s, double t, int times) {
  return insert_u(s, t, times);
}

NurbsSurface insert_knot_v(const NurbsSurface& s, double t, int times) {
  return transpose_uv(insert_u(transpose_uv(s), t, times));
}

std::vector<NurbsSurface> split_u(const NurbsSurface& s, const std::vector<double>& breaks) {
  return split_pieces_u(s, breaks);
}

std::vector<NurbsSurface> split_v(const NurbsSurface& s, const std::vector<double>& breaks) {
  std::vector<NurbsSurface> pieces = split_pieces_u(transpose_uv(s), breaks);
  for (NurbsSurface& q : pieces) q = transpose_uv(q);
  return pieces;
}

NurbsSurface extract_subsurface(const NurbsSurface& s, double ua, double ub, double va, double vb) {
  if (!(ua >= s.u0 && ub <= s.u1 && va >= s.v0 && vb <= s.v1)) {
    throw GeometryError("sub-surface range outside the domain of the surface");
  }
  NurbsSurface r = split_u(s, {ua, ub}).front();
  return split_v(r, {va, vb}).front();
}

NurbsSurface reverse_u(const NurbsSurface& s) {
  check_sizes_u(s);
  NurbsSurface r = s;
  const std::size_t m = s.knots_u.size();
  for (std::size_t k = 0; k < m; ++k) {
    const double t = s.knots_u[m - 1 - k];
    // Mirror about the domain; the domain ends map onto each other exactly.
    r.knots_u[k] = t == s.u0 ? s.u1 : (t == s.u1 ? s.u0 : s.u0 + (s.u1 - t));
  }
  const int n = s.count_u;
  for (int j = 0; j < s.count_v; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::size_t row = static_cast<std::size_t>(n) * j;
      r.points[row + i] = s.points[row + (n - 1 - i)];
      r.weights[row + i] = s.weights[row + (n - 1 - i)];
    }
  }
  return r;
}

NurbsSurface reverse_v(const NurbsSurface& s) { return transpose_uv(reverse_u(transpose_uv(s))); }

}  // namespace hm
