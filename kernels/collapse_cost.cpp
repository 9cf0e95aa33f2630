#include "kernels/collapse_cost.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace hm::kernel {
namespace {

const double kSqrt3 = std::sqrt(3.0);

double segment_distance2(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double len2 = dot(ab, ab);
  double t = len2 > 0 ? dot(p - a, ab) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return squared_norm(p - (a + t * ab));
}

}  // namespace

double triangle_shape(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double l2 = squared_norm(b - a) + squared_norm(c - b) + squared_norm(a - c);
  if (!(l2 > 0)) return 0;
  const double area = 0.5 * norm(cross(b - a, c - a));
  return std::min(1.0, 4 * kSqrt3 * area / l2);
}

double equilateral_edge(double area) { return std::sqrt(std::max(0.0, 4 * area / kSqrt3)); }

double area_ratio_quality(std::span<const double> areas) {
  if (areas.empty()) return 1;
  const auto [lo, hi] = std::minmax_element(areas.begin(), areas.end());
  return area_ratio_quality(*lo, *hi);
}

// Ericson's region test (Real-Time Collision Detection, 5.1.5), with the degenerate case
// routed to the edges.
double point_triangle_distance2(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const Vec3d n = cross(ab, ac);
  const double n2 = dot(n, n);
  const double scale = std::max({dot(ab, ab), dot(ac, ac), squared_norm(c - b)});
  if (!(n2 > 1e-24 * scale * scale)) {
    return std::min(
        {segment_distance2(p, a, b), segment_distance2(p, b, c), segment_distance2(p, c, a)});
  }
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return dot(ap, ap);
  const Vec3d bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dot(bp, bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return segment_distance2(p, a, b);
  const Vec3d cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dot(cp, cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return segment_distance2(p, a, c);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return segment_distance2(p, b, c);
  // Inside the face: the distance to the plane.
  const double h = dot(ap, n);
  return h * h / n2;
}

void triangle_shapes(std::span<const Vec3d> corners, std::span<double> shape) {
  parallel_for(0, shape.size(), [&](std::size_t i) {
    shape[i] = triangle_shape(corners[3 * i], corners[3 * i + 1], corners[3 * i + 2]);
  });
}

}  // namespace hm::kernel
