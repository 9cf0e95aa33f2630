#include "tessellate/chord_error.h"

#include <algorithm>

#include "core/parallel.h"

namespace hm {

double point_triangle_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  // Closest point by Voronoi regions of the triangle (Ericson, Real-Time Collision
  // Detection 5.1.5).
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return norm(ap);
  const Vec3d bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return norm(bp);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double den = d1 - d3;
    return norm(p - (a + ab * (den > 0 ? d1 / den : 0.0)));
  }
  const Vec3d cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return norm(cp);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double den = d2 - d6;
    return norm(p - (a + ac * (den > 0 ? d2 / den : 0.0)));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double den = (d4 - d3) + (d5 - d6);
    return norm(p - (b + (c - b) * (den > 0 ? (d4 - d3) / den : 0.0)));
  }
  const double den = va + vb + vc;
  if (!(den > 0)) {
    // Degenerate (collinear) triangle: the nearest of its three edges.
    auto seg = [&](const Vec3d& x, const Vec3d& y) {
      const Vec3d xy = y - x;
      const double l2 = dot(xy, xy);
      const double t = l2 > 0 ? std::clamp(dot(p - x, xy) / l2, 0.0, 1.0) : 0.0;
      return norm(p - (x + xy * t));
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
  }
  const double v = vb / den, w = vc / den;
  return norm(p - (a + ab * v + ac * w));
}

double triangle_chord_error(const NurbsSurface& s, const Vec3d& a, const Vec3d& b, const Vec3d& c,
                            const TriUv& w, const CollapsedSides& cs, ChordSampling sampling) {
  const Vec2d samples[4] = {cs.edge_middle(w[0], w[1]), cs.edge_middle(w[1], w[2]),
                            cs.edge_middle(w[2], w[0]), cs.centroid(w)};
  double e = 0;
  if (sampling == ChordSampling::kFromTriangle) {
    const Vec3d points[4] = {0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), (a + b + c) * (1.0 / 3)};
    for (int k = 0; k < 4; ++k) {
      const SurfaceProjection p = closest_point(s, points[k], samples[k].x, samples[k].y);
      e = std::max(e, p.distance);
    }
    return e;
  }
  for (const Vec2d& q : samples)
    e = std::max(e, point_triangle_distance(evaluate(s, q.x, q.y), a, b, c));
  return e;
}

std::vector<double> measure_chord_error(const NurbsSurface& s, const PatchMesh& m,
                                        const CollapsedSides& cs, ChordSampling sampling) {
  std::vector<double> err(m.tri_count(), 0.0);
  parallel_for(0, m.tri_count(), [&](std::size_t t) {
    const Tri& v = m.tris[t];
    err[t] =
        triangle_chord_error(s, m.xyz[v[0]], m.xyz[v[1]], m.xyz[v[2]], m.tri_uv[t], cs, sampling);
  });
  return err;
}

}  // namespace hm
