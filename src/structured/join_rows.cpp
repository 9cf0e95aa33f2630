// Joined rows. A row of several curves becomes one chain: its curves in order (lowest first),
// each followed by the surface's boundary path from its upper end to the next curve's lower end,
// resampled at the panel size. A row's joined chain is made once and shared by the strips on
// both sides of it.
#include "structured/join_rows.h"

#include <limits>
#include <map>
#include <optional>

#include "mesh/adjacency.h"
#include "structured/border_path.h"

namespace hm::structured {

std::vector<std::size_t> join_rows(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                                   std::span<const Row> rows, std::span<const RowNodes> nodes,
                                   std::span<const std::vector<Index>> first_vertex,
                                   std::span<const std::size_t> strips, const Metric& metric,
                                   const ZipOptions& zip, SurfaceMesh& mesh,
                                   std::vector<NodeSlot>& slots) {
  std::vector<std::size_t> closed;
  if (strips.empty()) return closed;
  const double tol = 0.25 * std::min({metric.size.x, metric.size.y, metric.size.z});
  std::map<std::size_t, std::optional<std::vector<Index>>> chains;
  auto joined = [&](std::size_t j) -> const std::optional<std::vector<Index>>& {
    auto it = chains.find(j);
    if (it != chains.end()) return it->second;
    std::optional<std::vector<Index>> chain{std::vector<Index>{}};
    const Row& row = rows[j];
    for (std::size_t c = 0; c < row.curves.size() && chain; ++c) {
      const std::size_t n = nodes[j].s[c].size();
      for (std::size_t i = 0; i < n; ++i)
        chain->push_back(first_vertex[j][c] + static_cast<Index>(i));
      if (c + 1 == row.curves.size()) break;
      // The boundary from this curve's upper end to the next one's lower end, the shorter way.
      const Vec3d from = mesh.positions[chain->back()];
      const Vec3d to = mesh.positions[first_vertex[j][c + 1]];
      const std::vector<Vec3d> best = shortest_border_path(surface, adj, from, to, metric, tol);
      if (best.empty()) {
        chain.reset();
        break;
      }
      for (const Vec3d& p : resample(best, metric)) {
        chain->push_back(static_cast<Index>(mesh.positions.size()));
        mesh.positions.push_back(p);
        mesh.vertex_patch.push_back(mesh.vertex_patch[first_vertex[j][c]]);
        mesh.vertex_uv.push_back(mesh.vertex_uv[first_vertex[j][c]]);
        slots.push_back(NodeSlot{});
      }
    }
    return chains.emplace(j, std::move(chain)).first->second;
  };
  for (std::size_t j : strips) {
    if (rows[j].curves.empty() || rows[j + 1].curves.empty()) continue;
    const std::optional<std::vector<Index>> a = joined(j);
    const std::optional<std::vector<Index>> b = joined(j + 1);
    if (!a || !b) continue;
    zip_chains(*a, chain_fractions(*a, mesh, metric), *b, chain_fractions(*b, mesh, metric),
               mesh.positions, zip, mesh.faces);
    closed.push_back(j);
  }
  return closed;
}

}  // namespace hm::structured
