// Neighbour rules over the edge adjacency: area ratio and normal angle of neighbouring panels.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/parallel.h"
#include "quality/quality_steps.h"

namespace hm {
namespace {

constexpr double kHugeRatio = 1e30;

// Angle between two unit normals, degrees; flip: the edge is used twice in one direction, so one
// face's normal is taken reversed (orientation is reported by the topology step instead).
double normal_angle(const Vec3d& a, const Vec3d& b, bool flip) {
  const Vec3d bb = flip ? -b : b;
  return std::atan2(norm(cross(a, bb)), dot(a, bb)) * 180.0 / std::numbers::pi;
}

}  // namespace

std::vector<std::uint8_t> knuckle_mask(const EdgeAdjacency& adj, const FaceQuality& fq,
                                       const QualityOptions& o) {
  std::vector<std::uint8_t> mask(adj.edges.size(), 0);
  for (const std::array<Index, 2>& e : o.knuckle_edges) {
    const Index id = find_edge(adj, e[0], e[1]);
    if (id != kInvalid) mask[id] = 1;
  }
  parallel_for(0, adj.edges.size(), [&](std::size_t e) {
    const MeshEdge& m = adj.edges[e];
    if (m.uses != 2 || mask[e]) return;
    const Index f = m.first_slot / 4, g = adj.opposite_face[m.first_slot];
    const Vec3d &nf = fq.normal[f], &ng = fq.normal[g];
    if (squared_norm(nf) == 0 || squared_norm(ng) == 0) return;
    mask[e] = normal_angle(nf, ng, m.same_direction) > o.knuckle_angle_deg;
  });
  return mask;
}

void measure_neighbours(const SurfaceMesh& mesh, const EdgeAdjacency& adj,
                        const std::vector<std::uint8_t>& knuckle, QualityReport& r) {
  FaceQuality& fq = r.per_face;
  const std::size_t nf = mesh.face_count();
  // 0: no neighbour; -1: no non-knuckle neighbour with a defined normal.
  fq.neighbour_area_ratio.assign(nf, 0.0);
  fq.neighbour_normal_angle.assign(nf, -1.0);
  parallel_for(0, nf, [&](std::size_t f) {
    for (int c = 0; c < 4; ++c) {
      const std::size_t slot = 4 * f + c;
      const Index g = adj.opposite_face[slot];
      if (g == kInvalid) continue;
      const double lo = std::min(fq.area[f], fq.area[g]), hi = std::max(fq.area[f], fq.area[g]);
      const double ratio = lo > hi / kHugeRatio ? hi / lo : kHugeRatio;
      fq.neighbour_area_ratio[f] = std::max(fq.neighbour_area_ratio[f], ratio);
      const Index e = adj.slot_edge[slot];
      if (knuckle[e] || squared_norm(fq.normal[f]) == 0 || squared_norm(fq.normal[g]) == 0)
        continue;
      const double angle = normal_angle(fq.normal[f], fq.normal[g], adj.edges[e].same_direction);
      fq.neighbour_normal_angle[f] = std::max(fq.neighbour_normal_angle[f], angle);
    }
  });
  for (std::size_t f = 0; f < nf; ++f) {
    r.max_area_ratio = std::max(r.max_area_ratio, fq.neighbour_area_ratio[f]);
    r.max_normal_angle_deg = std::max(r.max_normal_angle_deg, fq.neighbour_normal_angle[f]);
  }
  for (std::uint8_t k : knuckle) r.knuckle_edges += k;
}

double area_ratio_pair_share(const EdgeAdjacency& adj, const FaceQuality& fq, double limit) {
  std::size_t pairs = 0, ok = 0;
  for (const MeshEdge& m : adj.edges) {
    if (m.uses != 2) continue;
    const Index f = m.first_slot / 4, g = adj.opposite_face[m.first_slot];
    const double lo = std::min(fq.area[f], fq.area[g]), hi = std::max(fq.area[f], fq.area[g]);
    ++pairs;
    ok += lo > hi / kHugeRatio && hi / lo < limit;
  }
  return pairs ? static_cast<double>(ok) / static_cast<double>(pairs) : 1.0;
}

}  // namespace hm
