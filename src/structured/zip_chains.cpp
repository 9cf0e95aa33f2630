// Zipping two node chains into a strip of panels. Both chains are walked together by their
// arc-length fractions: a quad where both advance, a triangle where one must advance alone to
// keep the fractions level (the paper's quads "collapsed to triangular shape" where the rows
// differ in length). A quad that comes out twisted or distorted is split along its shorter
// diagonal.
#include <algorithm>
#include <cmath>

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

double opposite_ratio(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  return std::min(ratio(norm(b - a), norm(c - d)), ratio(norm(d - a), norm(c - b)));
}

ZipCounts zip_chains(std::span<const Index> a, std::span<const double> fa, std::span<const Index> b,
                     std::span<const double> fb, std::span<const Vec3d> positions,
                     const ZipOptions& options, std::vector<Face>& faces) {
  ZipCounts n;
  std::size_t i = 0, k = 0;
  const std::size_t na = a.size(), nb = b.size();
  while (i + 1 < na || k + 1 < nb) {
    // The fraction mismatch each move leaves behind; a quad wins ties.
    const double inf = 1e300;
    const double both = i + 1 < na && k + 1 < nb ? std::abs(fa[i + 1] - fb[k + 1]) : inf;
    const double only_a = i + 1 < na ? std::abs(fa[i + 1] - fb[k]) : inf;
    const double only_b = k + 1 < nb ? std::abs(fa[i] - fb[k + 1]) : inf;
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
