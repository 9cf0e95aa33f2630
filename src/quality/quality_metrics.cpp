// Per-face metrics: the kernel's arrays become the report's per-face cell data, then summaries.
#include "kernels/quality_metrics.h"

#include <algorithm>
#include <limits>

#include "quality/quality_steps.h"

namespace hm {
namespace {

std::vector<double> as_double(const std::vector<std::uint8_t>& v) {
  return std::vector<double>(v.begin(), v.end());
}

}  // namespace

void measure_faces(const SurfaceMesh& mesh, const QualityOptions& o, QualityReport& r) {
  kernel::FaceMetricArrays m;
  kernel::face_metrics(mesh.positions, mesh.faces, o.zero_area_rel, m);
  FaceQuality& fq = r.per_face;
  fq.area = std::move(m.area);
  fq.min_angle_deg = std::move(m.min_angle_deg);
  fq.max_angle_deg = std::move(m.max_angle_deg);
  fq.equilateral = std::move(m.equilateral);
  fq.side_ratio = std::move(m.side_ratio);
  fq.warp = std::move(m.warp);
  fq.warp_angle_deg = std::move(m.warp_angle_deg);
  fq.aspect_ratio = std::move(m.aspect_ratio);
  fq.convex = as_double(m.convex);
  fq.zero_area = as_double(m.zero_area);
  fq.is_quad = as_double(m.is_quad);
  fq.centroid = std::move(m.centroid);
  fq.normal = std::move(m.normal);

  r.faces = mesh.face_count();
  r.vertices = mesh.vertex_count();
  double q_sum = 0;
  r.min_equilateral = std::numeric_limits<double>::infinity();
  r.min_triangle_angle_deg = 180;
  for (std::size_t f = 0; f < r.faces; ++f) {
    const bool quad = fq.is_quad[f] != 0;
    r.zero_area += fq.zero_area[f] != 0;
    if (quad) {
      ++r.quads;
      r.max_side_ratio = std::max(r.max_side_ratio, fq.side_ratio[f]);
      r.max_warp = std::max(r.max_warp, fq.warp[f]);
      r.max_warp_angle_deg = std::max(r.max_warp_angle_deg, fq.warp_angle_deg[f]);
      r.non_convex += fq.convex[f] == 0 && fq.zero_area[f] == 0;
    } else {
      ++r.triangles;
      q_sum += fq.equilateral[f];
      r.min_equilateral = std::min(r.min_equilateral, fq.equilateral[f]);
      r.min_triangle_angle_deg = std::min(r.min_triangle_angle_deg, fq.min_angle_deg[f]);
    }
    r.max_aspect_ratio = std::max(r.max_aspect_ratio, fq.aspect_ratio[f]);
  }
  if (r.triangles == 0) {
    r.min_equilateral = 0;
    r.min_triangle_angle_deg = 0;
  } else {
    r.mean_equilateral = q_sum / static_cast<double>(r.triangles);
  }
}

AngleDistribution angle_distribution(std::vector<double> min_angle_deg) {
  AngleDistribution d;
  if (min_angle_deg.empty()) return d;
  const auto n = static_cast<double>(min_angle_deg.size());
  auto share = [&](double limit) {
    return static_cast<double>(std::count_if(min_angle_deg.begin(), min_angle_deg.end(),
                                             [&](double a) { return a >= limit; })) /
           n;
  };
  d.share_20 = share(20);
  d.share_30 = share(30);
  d.share_40 = share(40);
  std::sort(min_angle_deg.begin(), min_angle_deg.end());
  auto percentile = [&](double p) {
    return min_angle_deg[static_cast<std::size_t>(p * (n - 1) + 0.5)];
  };
  d.p05 = percentile(0.05);
  d.p50 = percentile(0.5);
  d.p95 = percentile(0.95);
  return d;
}

RuleShares rule_shares(const FaceQuality& fq, const QualityRules& rules) {
  std::size_t quads = 0, quads_ok = 0, with_nb = 0, area_ok = 0, with_angle = 0, angle_ok = 0,
              tris = 0, tris_ok = 0;
  RuleShares s;
  for (std::size_t f = 0; f < fq.area.size(); ++f) {
    if (fq.is_quad[f] != 0) {
      ++quads;
      quads_ok += fq.side_ratio[f] < rules.max_side_ratio;
      s.max_warp = std::max(s.max_warp, fq.warp[f]);
    } else {
      ++tris;
      tris_ok += fq.min_angle_deg[f] >= rules.min_triangle_angle_deg;
    }
    if (fq.neighbour_area_ratio[f] > 0) {
      ++with_nb;
      area_ok += fq.neighbour_area_ratio[f] < rules.max_area_ratio;
    }
    if (fq.neighbour_normal_angle[f] >= 0) {
      ++with_angle;
      angle_ok += fq.neighbour_normal_angle[f] < rules.max_normal_angle_deg;
    }
  }
  auto share = [](std::size_t ok, std::size_t n) {
    return n ? static_cast<double>(ok) / static_cast<double>(n) : 1.0;
  };
  s.side_ratio = share(quads_ok, quads);
  s.area_ratio = share(area_ok, with_nb);
  s.normal_angle = share(angle_ok, with_angle);
  s.triangle_angle = share(tris_ok, tris);
  return s;
}

}  // namespace hm
