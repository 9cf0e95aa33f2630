// The size field of the coarsening: the panel edge wanted at every point, from the NURBS
// curvature and the user's sources (the formulas are in coarsen_state.h).
#include <algorithm>
#include <cmath>
#include <queue>

#include "core/parallel.h"
#include "nurbs/nurbs_surface.h"
#include "unstructured/coarsen_state.h"

namespace hm::coarsen_detail {
namespace {

double segment_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return norm(p - (a + t * ab));
}

double source_distance(const SizeSource& src, const Vec3d& p) {
  switch (src.kind) {
    case SizeSource::Kind::kPoint:
      return norm(p - src.a);
    case SizeSource::Kind::kLine:
      return segment_distance(p, src.a, src.b);
    case SizeSource::Kind::kBox: {
      Vec3d d;
      for (int i = 0; i < 3; ++i) {
        const double lo = std::min(src.a[i], src.b[i]), hi = std::max(src.a[i], src.b[i]);
        d[i] = std::max({lo - p[i], 0.0, p[i] - hi});
      }
      return norm(d);
    }
  }
  return 0;
}

}  // namespace

double SizeField::curvature_factor(double kappa) const {
  if (w_curvature <= 0) return 1;
  return std::pow(1 + std::min(std::abs(kappa), kappa_max) * curvature_length, -0.5 * w_curvature);
}

double SizeField::source_factor(const Vec3d& x) const {
  if (w_sources <= 0 || sources.empty()) return 1;
  double log_factor = 0;
  for (const SizeSource& src : sources) {
    // Full strength within half the radius, then a smoothstep down to nothing at the radius.
    const double t = std::clamp(2 * source_distance(src, x) / src.radius - 1, 0.0, 1.0);
    const double phi = 1 - t * t * (3 - 2 * t);
    if (phi > 0) log_factor += std::min(1.0, w_sources * phi) * std::log(src.size / h0);
  }
  return std::exp(log_factor);
}

std::vector<double> vertex_curvatures(std::span<const Patch> patches, const SurfaceMesh& fine) {
  std::vector<double> k(fine.vertex_count(), 0.0);
  parallel_for(0, k.size(), [&](std::size_t v) {
    const PatchId p = fine.vertex_patch[v];
    if (p >= patches.size()) return;
    const PrincipalCurvature pc =
        principal_curvature(patches[p].surface, fine.vertex_uv[v].x, fine.vertex_uv[v].y);
    const double kmax = std::max(std::abs(pc.k1), std::abs(pc.k2));
    k[v] = std::isfinite(kmax) ? kmax : 0.0;
  });
  return k;
}

double calibrate_panel_size(const SurfaceMesh& fine, std::span<const double> cfactor,
                            SizeField field, std::size_t panels) {
  // Panels of edge h have area sqrt(3)/4 h^2; with h = h0 c s, the count is
  // sum_f A_f / (sqrt(3)/4 h0^2 c_f^2 s_f^2). The source factor depends on h0 (size / h0), so
  // iterate to a fixed point from the uniform answer.
  const double kEquilateral = std::sqrt(3.0) / 4;
  std::vector<double> area(fine.face_count()), c2(fine.face_count());
  std::vector<Vec3d> centre(fine.face_count());
  parallel_for(0, fine.face_count(), [&](std::size_t f) {
    const Face& fc = fine.faces[f];
    area[f] = face_area(fine.positions, fc);
    centre[f] = face_centroid(fine.positions, fc);
    // The factor falls as curvature grows: the face's is its corners' smallest.
    const double c = std::min({cfactor[fc[0]], cfactor[fc[1]], cfactor[fc[2]]});
    c2[f] = c * c;
  });
  double total = 0;
  for (double a : area) total += a;
  field.h0 =
      std::sqrt(total / (kEquilateral * static_cast<double>(std::max<std::size_t>(panels, 1))));
  // Without sources the factor is 1 everywhere and one pass is the fixed point.
  const int passes = field.w_sources <= 0 || field.sources.empty() ? 1 : 8;
  for (int it = 0; it < passes; ++it) {
    double weighted = 0;  // serial sum in face order: the same bits for any thread count
    for (std::size_t f = 0; f < area.size(); ++f) {
      const double s = field.source_factor(centre[f]);
      weighted += area[f] / (c2[f] * s * s);
    }
    field.h0 = std::sqrt(weighted / (kEquilateral * static_cast<double>(panels)));
  }
  return field.h0;
}

void grade_sizes(const State& s, double slope, std::vector<double>& h) {
  // Dijkstra from the smallest sizes outward: h[u] = min over v (h[v] + slope |uv|), so the
  // wanted edge grows by at most `slope` per metre along the surface.
  using Item = std::pair<double, Index>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (std::size_t v = 0; v < h.size(); ++v) {
    if (s.alive[v]) heap.push({h[v], static_cast<Index>(v)});
  }
  while (!heap.empty()) {
    const auto [hv, v] = heap.top();
    heap.pop();
    if (hv > h[v]) continue;  // stale
    for (Index f : s.vertex_faces[v]) {
      for (Index u : s.faces[f]) {
        const double cand = hv + slope * norm(s.position[u] - s.position[v]);
        if (cand < h[u]) {
          h[u] = cand;
          heap.push({cand, u});
        }
      }
    }
  }
}

}  // namespace hm::coarsen_detail
