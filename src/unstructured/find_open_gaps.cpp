// Gaps left open: border vertices whose nearest border edge of another patch lies beyond the
// tolerance but within gap_report_edges local border edge lengths. Grouped by patch pair.
#include <algorithm>
#include <limits>
#include <map>

#include "core/parallel.h"
#include "unstructured/merge_border.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

constexpr double kEndT = 1e-9;             // an edge parameter this close to an end is at the end
constexpr double kStraightCosine = 0.866;  // cos 30 degrees

// Border edges at each vertex (indices into Border::edges), as offsets into one array.
struct VertexEdges {
  VertexEdges(const Border& b, std::size_t vertex_count) : first(vertex_count + 1, 0) {
    for (const BorderEdge& e : b.edges) ++first[e.v0 + 1], ++first[e.v1 + 1];
    for (std::size_t v = 0; v < vertex_count; ++v) first[v + 1] += first[v];
    edges.resize(first.back());
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (std::size_t e = 0; e < b.edges.size(); ++e) {
      edges[next[b.edges[e].v0]++] = Index(e);
      edges[next[b.edges[e].v1]++] = Index(e);
    }
  }
  std::vector<std::size_t> first;
  std::vector<Index> edges;
};

// Parameter of p's foot on the line through a and b (0 at a, 1 at b; not clamped).
double along(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d d = b - a;
  const double dd = dot(d, d);
  return dd > 0 ? dot(p - a, d) / dd : 0.0;
}

// Whether the border runs straight on through `end` past edge `from`: another border edge there
// leaves it within 30 degrees of straight on. A foot at such an end is a foot on a smooth border;
// at a corner it is not (a low deck edge meeting the end of a raised side, or a border vertex
// beside a gap's end).
bool straight_through(const SurfaceMesh& m, const Border& b, const VertexEdges& at, Index end,
                      Index from) {
  const BorderEdge& fe = b.edges[from];
  const Vec3d back = m.positions[fe.v0 == end ? fe.v1 : fe.v0] - m.positions[end];
  for (std::size_t i = at.first[end]; i < at.first[end + 1]; ++i) {
    const Index e = at.edges[i];
    if (e == from) continue;
    const BorderEdge& be = b.edges[e];
    const Vec3d on = m.positions[be.v0 == end ? be.v1 : be.v0] - m.positions[end];
    if (dot(on, back) < -kStraightCosine * norm(on) * norm(back)) return true;
  }
  return false;
}

}  // namespace

std::vector<OpenGapVertex> find_open_gap_vertices(const Work& w, const EdgeAdjacency& adj,
                                                  const MergeOptions& options, double reach) {
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
  const VertexEdges at(b, m.vertex_count());
  parallel_for(0, nb, [&](std::size_t i) {
    const Index v = b.vertices[i];
    const PatchId pv = m.vertex_patch[v];
    grid.for_each_within(
        m.positions[v], std::max(reach, options.gap_report_edges * b.edge_length[i]), [&](Index e) {
          const BorderEdge& be = b.edges[e];
          if (be.patch == pv || be.v0 == v || be.v1 == v) return;
          if (!grid.may_be_within(e, m.positions[v], near[i].distance)) return;
          // A vertex beside an edge's end (beyond it, or a rounding error from it) faces that edge
          // across a gap only where the border runs straight on through that end; at a corner it
          // is a border running on past it (the next patch's deck edge, or a low deck edge meeting
          // the end of a raised side). Beyond the end, it faces the next edge or nothing.
          const double t = along(m.positions[v], m.positions[be.v0], m.positions[be.v1]);
          if (t < -kEndT || t > 1 + kEndT) return;
          if ((t <= kEndT || t >= 1 - kEndT) &&
              !straight_through(m, b, at, t < 0.5 ? be.v0 : be.v1, e)) {
            return;
          }
          const SegmentPoint sp =
              closest_on_segment(m.positions[v], m.positions[be.v0], m.positions[be.v1]);
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
  std::vector<OpenGapVertex> out;
  for (std::size_t i = 0; i < nb; ++i) {
    const Near& n = near[i];
    if (n.patch == kInvalid || n.distance <= tol[i] ||
        n.distance > std::max(reach, options.gap_report_edges * b.edge_length[i])) {
      continue;
    }
    out.push_back({b.vertices[i], n.patch, n.distance});
  }
  return out;
}

std::vector<OpenGap> find_open_gaps(const Work& w, const EdgeAdjacency& adj,
                                    const MergeOptions& options) {
  const SurfaceMesh& m = w.mesh;
  std::map<std::pair<PatchId, PatchId>, OpenGap> gaps;
  for (const OpenGapVertex& o : find_open_gap_vertices(w, adj, options)) {
    const PatchId pv = m.vertex_patch[o.vertex];
    OpenGap& g = gaps[{std::min(pv, o.across), std::max(pv, o.across)}];
    g.patch_a = std::min(pv, o.across);
    g.patch_b = std::max(pv, o.across);
    ++g.vertices;
    if (o.width > g.width) {
      g.width = o.width;
      g.location = m.positions[o.vertex];
    }
  }
  std::vector<OpenGap> out;
  for (auto& [k, g] : gaps) out.push_back(g);
  std::stable_sort(out.begin(), out.end(),
                   [](const OpenGap& a, const OpenGap& b) { return a.width > b.width; });
  return out;
}

}  // namespace hm::merge
