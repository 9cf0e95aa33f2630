// Zipping two node chains into a strip of panels. Both chains are walked together by their
// arc-length fractions: a quad where both advance, a triangle where one must advance alone to
// keep the fractions level (the paper's quads "collapsed to triangular shape" where the rows
// differ in length). A quad that comes out twisted or distorted is split along its shorter
// diagonal.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

double ratio(double p, double q) {
  const double hi = std::max(p, q);
  return hi > 0 ? std::min(p, q) / hi : 0;
}

void push_triangle(Index a, Index b, Index c, std::vector<Face>& faces, ZipCounts& n) {
  if (a == b || b == c || a == c) return;
  faces.push_back({a, b, c, kInvalid});
  ++n.triangles;
}

}  // namespace

double quad_warp(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  const Vec3d n = cross(c - a, d - b);
  const double nn = norm(n);
  const double diag = 0.5 * (norm(c - a) + norm(d - b));
  if (nn == 0 || diag == 0) return 1;
  const Vec3d m = (a + b + c + d) * 0.25;
  const double h = std::abs(dot(n, a - m)) / nn;  // the four corners are equally far
  return h / diag;
}

double min_angle(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d p[3] = {a, b, c};
  double worst = std::numbers::pi;
  for (int i = 0; i < 3; ++i) {
    const Vec3d u = p[(i + 1) % 3] - p[i], w = p[(i + 2) % 3] - p[i];
    const double nu = norm(u), nw = norm(w);
    if (!(nu > 0 && nw > 0)) return 0;
    worst = std::min(worst, std::acos(std::clamp(dot(u, w) / (nu * nw), -1.0, 1.0)));
  }
  return worst;
}

double opposite_ratio(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return std::min(ratio(norm(b - a), norm(c - d)), ratio(norm(d - a), norm(c - b)));
}

ZipCounts zip_chains(std::span<const Index> a, std::span<const double> fa, std::span<const Index> b,
                     std::span<const double> fb, std::span<const Vec3d> positions,
                     const ZipOptions& options, std::vector<Face>& faces) {
  ZipCounts n;
  std::size_t i = 0, k = 0;
  const std::size_t na = a.size(), nb = b.size();
  // Chains that share an end (a cap's boundary path from one end of a row to the other): a
  // triangle whose apex is that end and whose base is the other chain's edge lies along that
  // chain, three of its nodes in a row (a sonar dome's nose a centimetre beyond dtmb5415's first
  // station at a 0.348 m draft: the row's end nodes fanned over its own edges, area ratios of
  // 55 and 42). So both chains leave a shared start together (a chain that left alone would
  // start with a quad of three nodes in a row, or fan), and neither steps onto a shared end
  // while the other has more than its last edge to go.
  const bool shared_start = na > 1 && nb > 1 && a[0] == b[0];
  const bool shared_end = na > 1 && nb > 1 && a[na - 1] == b[nb - 1];
  while (i + 1 < na || k + 1 < nb) {
    // The fraction mismatch each move leaves behind; a quad wins ties.
    const double inf = 1e300;
    double both = i + 1 < na && k + 1 < nb ? std::abs(fa[i + 1] - fb[k + 1]) : inf;
    double only_a = i + 1 < na ? std::abs(fa[i + 1] - fb[k]) : inf;
    double only_b = k + 1 < nb ? std::abs(fa[i] - fb[k + 1]) : inf;
    if (shared_start && i == 0 && k == 0) only_a = only_b = inf;
    if (shared_end) {
      // Onto a's last node while b has two edges or more left, or b's while a has.
      if (i + 2 == na && k + 2 < nb) both = only_a = inf;
      if (k + 2 == nb && i + 2 < na) both = only_b = inf;
    }
    // Chains with as many nodes left on both sides finish in quads: a triangle here would force
    // a second one further on.
    const bool level = na - i == nb - k;
    if (level || (both <= only_a + 1e-12 && both <= only_b + 1e-12)) {
      const Index q0 = a[i], q1 = a[i + 1], q2 = b[k + 1], q3 = b[k];
      if (q0 == q3 || q1 == q2) {
        // A chain end shared by both chains (a cap): the quad is a triangle.
        if (q0 == q3)
          push_triangle(q0, q1, q2, faces, n);
        else
          push_triangle(q0, q1, q3, faces, n);
      } else {
        const Vec3d &p0 = positions[q0], &p1 = positions[q1], &p2 = positions[q2],
                    &p3 = positions[q3];
        if (opposite_ratio(p0, p1, p2, p3) < options.min_opposite_ratio ||
            quad_warp(p0, p1, p2, p3) > options.max_warp) {
          ++n.split;
          if (squared_norm(p2 - p0) <= squared_norm(p3 - p1)) {
            push_triangle(q0, q1, q2, faces, n);
            push_triangle(q0, q2, q3, faces, n);
          } else {
            push_triangle(q0, q1, q3, faces, n);
            push_triangle(q1, q2, q3, faces, n);
          }
        } else {
          faces.push_back({q0, q1, q2, q3});
          ++n.quads;
        }
      }
      ++i;
      ++k;
    } else if (only_a <= only_b) {
      push_triangle(a[i], a[i + 1], b[k], faces, n);
      ++i;
    } else {
      push_triangle(a[i], b[k + 1], b[k], faces, n);
      ++k;
    }
  }
  return n;
}

}  // namespace hm::structured
