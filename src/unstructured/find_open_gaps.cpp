// Gaps left open: border vertices whose nearest border edge of another patch lies beyond the
// tolerance but within gap_report_edges local border edge lengths. Grouped by patch pair.
#include <algorithm>
#include <limits>
#include <map>

#include "core/parallel.h"
#include "unstructured/merge_border.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {

std::vector<OpenGap> find_open_gaps(const Work& w, const EdgeAdjacency& adj,
                                    const MergeOptions& options) {
  const SurfaceMesh& m = w.mesh;
  const Border b = collect_border(m, adj);
  const std::size_t nb = b.vertices.size();
  std::vector<double> tol(nb);
  for (std::size_t i = 0; i < nb; ++i) tol[i] = vertex_tolerance(options, b.edge_length[i]);
  struct Near {
    PatchId patch = kInvalid;
    double distance = std::numeric_limits<double>::infinity();
  };
  std::vector<Near> near(nb);
  const SegmentGrid grid(m.positions, b.edges);
  parallel_for(0, nb, [&](std::size_t i) {
    const Index v = b.vertices[i];
    const PatchId pv = m.vertex_patch[v];
    grid.for_each_near(m.positions[v], options.gap_report_edges * b.edge_length[i], [&](Index e) {
      const BorderEdge& be = b.edges[e];
      if (be.patch == pv || be.v0 == v || be.v1 == v) return;
      const SegmentPoint sp =
          closest_on_segment(m.positions[v], m.positions[be.v0], m.positions[be.v1]);
      // A nearest point at an edge end is a border running on past a corner (the next patch's
      // deck edge), not a border facing this one across a gap.
      if (sp.t <= 0 || sp.t >= 1) return;
      // Across a gap the vertex lies straight out from the edge, beyond its patch.
      const Vec3d a = m.positions[be.v0], dir = m.positions[be.v1] - a;
      const Vec3d off = m.positions[v] - (a + sp.t * dir);
      const Vec3d in = edge_inward(m, be);
      if (!(dot(off, in) < -0.7 * norm(off))) return;
      const double d = sp.distance;
      if (d < near[i].distance || (d == near[i].distance && be.patch < near[i].patch)) {
        near[i] = {be.patch, d};
      }
    });
  });
  std::map<std::pair<PatchId, PatchId>, OpenGap> gaps;
  for (std::size_t i = 0; i < nb; ++i) {
    const Near& n = near[i];
    if (n.patch == kInvalid || n.distance <= tol[i] ||
        n.distance > options.gap_report_edges * b.edge_length[i]) {
      continue;
    }
    const PatchId pv = m.vertex_patch[b.vertices[i]];
    OpenGap& g = gaps[{std::min(pv, n.patch), std::max(pv, n.patch)}];
    g.patch_a = std::min(pv, n.patch);
    g.patch_b = std::max(pv, n.patch);
    ++g.vertices;
    if (n.distance > g.width) {
      g.width = n.distance;
      g.location = m.positions[b.vertices[i]];
    }
  }
  std::vector<OpenGap> out;
  for (auto& [k, g] : gaps) out.push_back(g);
  std::stable_sort(out.begin(), out.end(),
                   [](const OpenGap& a, const OpenGap& b) { return a.width > b.width; });
  return out;
}

}  // namespace hm::merge
