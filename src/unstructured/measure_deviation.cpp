#include "unstructured/measure_deviation.h"

#include <vector>

#include "core/parallel.h"
#include "mesh/adjacency.h"

namespace hm {

DeviationMeasure measure_deviation(const HullQuery& hull, const SurfaceMesh& panels) {
  // Every centroid, then every edge's midpoint once (an edge shared by two panels is one sample).
  const std::size_t nf = panels.face_count();
  const EdgeAdjacency adj = build_edge_adjacency(panels.faces, panels.vertex_count());
  std::vector<Vec3d> sample(nf + adj.edges.size());
  parallel_for(
      0, nf, [&](std::size_t f) { sample[f] = face_centroid(panels.positions, panels.faces[f]); });
  parallel_for(0, adj.edges.size(), [&](std::size_t e) {
    sample[nf + e] = 0.5 * (panels.positions[adj.edges[e].v0] + panels.positions[adj.edges[e].v1]);
  });
  std::vector<ClosestPoint> cp(sample.size());
  hull.closest_points(sample, cp);
  DeviationMeasure m;
  double sum = 0;
  for (std::size_t i = 0; i < cp.size(); ++i) {
    if (!cp[i].valid()) continue;
    ++m.samples;
    sum += cp[i].distance;
    if (cp[i].distance > m.max) {
      m.max = cp[i].distance;
      m.where = sample[i];
    }
  }
  m.mean = m.samples ? sum / static_cast<double>(m.samples) : 0.0;
  return m;
}

}  // namespace hm
