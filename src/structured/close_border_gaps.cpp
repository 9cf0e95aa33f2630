// Border gaps, found on the panel mesh's own boundary: an edge between the end nodes of two rows
// whose boundary path on the surface strays from the straight edge by a quarter panel or more.
#include "structured/close_border_gaps.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/adjacency.h"
#include "structured/border_path.h"

namespace hm::structured {
namespace {

// A path straying less than this from the edge (in panels) is no gap.
constexpr double kGapPanels = 0.25;

// Largest metric distance of the points from the segment a-b.
double stray(const std::vector<Vec3d>& pts, const Vec3d& a, const Vec3d& b, const Metric& m) {
  const Vec3d d = b - a;
  const double dd = squared_norm(d);
  double worst = 0;
  for (const Vec3d& p : pts) {
    const double f = dd > 0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
    worst = std::max(worst, m.length(a + d * f, p));
  }
  return worst;
}

}  // namespace

GapCounts close_border_gaps(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                            std::span<const std::uint8_t> row_end, const Metric& metric,
                            SurfaceMesh& mesh, std::vector<NodeSlot>& slots) {
  GapCounts counts;
  const EdgeAdjacency panels = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  const double tol = 0.25 * std::min({metric.size.x, metric.size.y, metric.size.z});
  const std::size_t face_count = mesh.faces.size();
  for (Index e : panels.boundary_edges) {
    const Index slot = panels.edges[e].first_slot;
    const Face& f = mesh.faces[slot / 4];
    const Index u = f[slot % 4], w = f[(slot % 4 + 1) % corner_count(f)];
    if (u >= row_end.size() || w >= row_end.size() || !row_end[u] || !row_end[w]) continue;
    if (slots[u].row == slots[w].row) continue;
    const Vec3d pu = mesh.positions[u], pw = mesh.positions[w];
    const std::vector<Vec3d> best = shortest_border_path(surface, adj, pu, pw, metric, tol);
    if (best.empty()) continue;
    // One end on the centre plane and the other off it, on another plane (the waterline): the
    // boundary turns a corner between them, however little the path strays.
    const bool turns = pu.z != pw.z && (pu.y == 0) != (pw.y == 0);
    if (!turns && stray(best, pu, pw, metric) < kGapPanels) continue;
    if (best.size() < 3) continue;  // nothing between the ends
    std::vector<Vec3d> inner = resample(best, metric);
    if (inner.empty()) {
      // Shorter than a panel but bent: its farthest point alone.
      const Vec3d d = pw - pu;
      double far = -1;
      Vec3d at = best[best.size() / 2];
      for (const Vec3d& p : best) {
        const double f = std::clamp(dot(p - pu, d) / std::max(squared_norm(d), 1e-300), 0.0, 1.0);
        const double h = norm(pu + d * f - p);
        if (h > far) {
          far = h;
          at = p;
        }
      }
      inner.push_back(at);
    }
    // The gap lies across the edge from its face, which runs u -> w: a fan from w, starting with
    // (w, u, q1), runs w -> u.
    std::vector<Index> q;
    for (const Vec3d& p : inner) {
      q.push_back(static_cast<Index>(mesh.positions.size()));
      mesh.positions.push_back(p);
      mesh.vertex_patch.push_back(mesh.vertex_patch[u]);
      mesh.vertex_uv.push_back(mesh.vertex_uv[u]);
      slots.push_back(NodeSlot{});
    }
    mesh.faces.push_back({w, u, q.front(), kInvalid});
    for (std::size_t i = 0; i + 1 < q.size(); ++i)
      mesh.faces.push_back({w, q[i], q[i + 1], kInvalid});
    ++counts.gaps;
  }
  counts.triangles = mesh.faces.size() - face_count;
  return counts;
}

}  // namespace hm::structured
