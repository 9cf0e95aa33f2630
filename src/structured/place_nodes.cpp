// Row nodes as mesh vertices: placed on their row curves (linear between section points), then,
// after relocation, back onto the exact NURBS on their station planes.
#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "query/surface_refine.h"
#include "structured/structured_steps.h"

namespace hm::structured {

NodeLayout place_nodes(std::span<const Row> rows, std::span<const RowNodes> nodes,
                       SurfaceMesh& mesh) {
  NodeLayout layout;
  std::vector<NodeSlot>& slots = layout.slots;
  std::vector<std::vector<Index>>& first_vertex = layout.first_vertex;
  first_vertex.resize(rows.size());
  // Row by row, curve by curve, node by node.
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (std::size_t c = 0; c < rows[j].curves.size(); ++c) {
      const RowCurve& curve = rows[j].curves[c];
      first_vertex[j].push_back(static_cast<Index>(mesh.positions.size()));
      for (double s : nodes[j].s[c]) {
        bool on_break = false;
        for (const Breakpoint& b : curve.breaks) on_break = on_break || std::abs(b.s - s) < 1e-12;
        std::size_t k;
        double f;
        curve.locate(s, k, f);
        mesh.positions.push_back(curve.at(s));
        mesh.vertex_patch.push_back(f < 0.5 ? curve.patch[k] : curve.patch[k + 1]);
        mesh.vertex_uv.push_back(curve.patch[k] == curve.patch[k + 1]
                                     ? curve.uv[k] * (1 - f) + curve.uv[k + 1] * f
                                     : (f < 0.5 ? curve.uv[k] : curve.uv[k + 1]));
        slots.push_back({static_cast<Index>(j), static_cast<Index>(c), s,
                         rows[j].border || on_break, on_break});
      }
    }
  }

  return layout;
}

void refine_nodes(std::span<const Patch> patches, std::span<const Row> rows,
                  std::span<const NodeSlot> slots, double tol, const Metric& metric,
                  SurfaceMesh& mesh) {
  std::vector<query::ParamDomain> domains(patches.size());
  parallel_for_each_item(patches.size(), [&](std::size_t p) {
    domains[p] = query::make_domain(patches[p].surface, tol);
  });
  parallel_for(0, slots.size(), [&](std::size_t v) {
    const NodeSlot& n = slots[v];
    // Cap nodes lie on the surface's boundary, breakpoints on a section point, the waterline or a
    // knuckle: refining would only move them off it.
    if (n.row == kInvalid || n.on_break) return;
    const RowCurve& c = rows[n.row].curves[n.curve];
    std::size_t k;
    double f;
    c.locate(n.s, k, f);
    // A segment across a patch border: refined on the nearer point's patch, from its (u, v)
    // alone (the other end's belongs to another surface).
    const bool same = c.patch[k] == c.patch[k + 1];
    const std::size_t near = same || f < 0.5 ? k : k + 1;
    const PatchId p = c.patch[near];
    const query::RefinedPlanePoint r = query::refine_plane_edge(
        patches[p].surface, domains[p], {1, 0, 0}, {rows[n.row].x, 0, 0}, c.uv[near],
        same ? c.uv[k + 1] : c.uv[near], same ? f : 0.0, mesh.positions[v], tol);
    // The curve's z range holds it: the waterplane cut snapped the surface's last vertices onto
    // the plane, and the exact NURBS can cross it a little way off, so a node near the waterline
    // would otherwise rise above it.
    if (r.converged &&
        squared_norm(r.point - mesh.positions[v]) < 1e-4 * metric.size.x * metric.size.x &&
        r.point.z <= c.z_max && r.point.z >= c.z_min) {
      mesh.positions[v] = r.point;
      mesh.vertex_uv[v] = r.uv;
      mesh.vertex_patch[v] = p;
    }
  });
}

}  // namespace hm::structured
