// Bridging rows that start apart: collect the curve pairs whose starts lie on and off the
// centre plane -> find the boundary between them inside the strip -> keep it where it is a fair
// share of the curve from the centre plane -> lay its nodes.
#include "structured/bridge_starts.h"

#include <algorithm>
#include <cmath>

#include "structured/border_path.h"

namespace hm::structured {
namespace {

// Starts closer than this across the strip (panels, the x offset left out) are one start.
constexpr double kApartPanels = 2.0;
// A bridge is laid only where it is at least this share of the curve from the centre plane: a
// zip by arc-length fractions absorbs a smaller offset with a few triangles, as the strips
// by npl_round_bilge's immersed transom do (a bridge of 4 panels against 18 there thinned
// their panels and crossed nothing before), while ship_449_patches' crossed at 7-16 panels
// against 18-29.
constexpr double kBridgeShare = 1.0 / 3.0;

}  // namespace

std::vector<std::vector<StartBridge>> bridge_starts(
    const SurfaceMesh& surface, const EdgeAdjacency& adj, std::span<const Row> rows,
    std::span<const std::vector<Index>> first_vertex, const Metric& metric, double centre,
    SurfaceMesh& mesh, std::vector<NodeSlot>& slots) {
  std::vector<std::vector<StartBridge>> out(rows.empty() ? 0 : rows.size() - 1);
  const double tol = 0.25 * std::min({metric.size.x, metric.size.y, metric.size.z});
  const double margin = kSlabMargin * metric.size.x;
  for (std::size_t j = 0; j < out.size(); ++j) {
    const Row& a = rows[j];
    const Row& b = rows[j + 1];
    if (a.curves.size() != b.curves.size()) continue;  // join_rows reads those strips
    for (std::size_t c = 0; c < a.curves.size(); ++c) {
      const Vec3d pa = a.curves[c].points.front(), pb = b.curves[c].points.front();
      const bool a_on = std::abs(pa.y) <= centre, b_on = std::abs(pb.y) <= centre;
      if (a_on == b_on || metric.length(pa, Vec3d{pa.x, pb.y, pb.z}) <= kApartPanels) continue;
      const Vec3d from = a_on ? pa : pb, to = a_on ? pb : pa;
      const std::vector<Vec3d> path =
          shortest_border_path(surface, adj, from, to, metric, tol, a.x - margin, b.x + margin);
      if (path.empty()) continue;
      double along = 0;
      for (std::size_t i = 1; i < path.size(); ++i) along += metric.length(path[i - 1], path[i]);
      if (along < kBridgeShare * (a_on ? a : b).curves[c].length()) continue;
      StartBridge br;
      br.curve = c;
      br.forward = a_on;
      const Index first = first_vertex[a_on ? j : j + 1][c];
      br.nodes.push_back(first);
      br.at.push_back(0);
      for (const Vec3d& p : resample(path, metric)) {
        br.at.push_back(br.at.back() + metric.length(mesh.positions[br.nodes.back()], p));
        mesh.positions.push_back(p);
        mesh.vertex_patch.push_back(mesh.vertex_patch[first]);
        mesh.vertex_uv.push_back(mesh.vertex_uv[first]);
        NodeSlot slot;
        slot.bridge = true;
        slots.push_back(slot);
        br.nodes.push_back(static_cast<Index>(mesh.positions.size() - 1));
      }
      br.length = br.at.back() + metric.length(mesh.positions[br.nodes.back()], to);
      out[j].push_back(std::move(br));
    }
  }
  return out;
}

}  // namespace hm::structured
