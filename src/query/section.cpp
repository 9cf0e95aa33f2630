// Plane sections: the plane BVH finds the triangles the plane crosses, the crossings are chained
// along shared mesh edges into pieces, every point is refined onto the NURBS, and the pieces are
// joined across patch borders and gaps (section_chain).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>

#include "core/error.h"
#include "core/parallel.h"
#include "query/query_scene.h"
#include "query/section_chain.h"

namespace hm {
namespace {

using Impl = HullQuery::Impl;

// A section point refined farther than this share of its fine edge's length stays on the edge.
constexpr double kMaxRefineShare = 0.25;

// The plane n.x = c in the local frame (n unit), and its model-frame form for refinement.
struct CutPlane {
  Vec3d n;
  double c = 0;
  Vec3d model_point;
};

CutPlane make_plane(const Impl& m, const Plane& plane) {
  const Vec3d n = normalized(plane.normal);
  if (!is_finite(n) || n == Vec3d{} || !is_finite(plane.point)) {
    throw GeometryError("section: the plane needs a finite point and a non-zero normal");
  }
  return {n, dot(n, plane.point - m.centre), plane.point};
}

// Signed distance of a vertex to the plane. Every triangle sharing the vertex computes the same
// value (same inputs, same operations), so they agree on its side; a vertex on the plane counts as
// the positive side (symbolic perturbation), so a triangle crosses iff its corners' sides differ
// and then exactly two of its edges cross.
double side(const Impl& m, const CutPlane& pl, Index v) { return dot(pl.n, m.local[v]) - pl.c; }

// A triangle the plane crosses, with its corners' signed distances (computed once: vertex
// positions are scattered in memory, and reading them is most of a section's search cost).
struct Crossed {
  Index tri;
  std::array<double, 3> side;
};

bool crosses(const Impl& m, const CutPlane& pl, Index t, const std::array<Index, 3>& tri,
             Crossed& out) {
  // A triangle with a repeated corner has no area and would link an edge to itself.
  if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) return false;
  out = {t, {side(m, pl, tri[0]), side(m, pl, tri[1]), side(m, pl, tri[2])}};
  const bool s0 = out.side[0] >= 0;
  return (out.side[1] >= 0) != s0 || (out.side[2] >= 0) != s0;
}

// One crossing edge seen from one crossed triangle: the edge key (sorted vertex pair), the
// triangle, its corner slots, and the segment (crossed triangle) it belongs to.
struct EdgeUse {
  Index lo, hi;
  Index tri;
  int ka, kb;
  Index segment;
  double sa, sb;  // signed distances of corners ka and kb
};

// The crossing edges as nodes and the crossed triangles as links between them.
struct CrossingGraph {
  std::vector<EdgeUse> edges;  // one per node: the use by the lowest triangle
  std::vector<std::array<Index, 2>> segment_nodes;
  std::vector<Index> node_first;  // node n's segments are node_segments[first[n]..first[n+1])
  std::vector<Index> node_segments;
};

// Nodes are numbered in order of first use; crossed is in triangle order, so a node's recorded
// use is by its lowest triangle and the numbering is the same for the BVH and the brute-force
// search. Edge keys go through an open-addressing table (no sort, no allocation per entry).
CrossingGraph build_graph(const Impl& m, std::span<const Crossed> crossed) {
  constexpr std::uint64_t kEmpty = ~std::uint64_t{0};
  int bits = 4;
  while ((std::size_t{1} << bits) < 2 * crossed.size() + 4) ++bits;
  const std::size_t mask = (std::size_t{1} << bits) - 1;
  std::vector<std::uint64_t> keys(mask + 1, kEmpty);
  std::vector<Index> key_node(mask + 1);
  std::vector<Index> degree;
  CrossingGraph g;
  // A crossed triangle has two crossing edges, most of them shared with a neighbour.
  g.edges.reserve(crossed.size() + 2);
  degree.reserve(crossed.size() + 2);
  g.segment_nodes.assign(crossed.size(), {kInvalid, kInvalid});
  for (Index s = 0; s < crossed.size(); ++s) {
    const Crossed& c = crossed[s];
    const auto& tri = m.tri[c.tri];
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3;
      if ((c.side[k] >= 0) == (c.side[k1] >= 0)) continue;
      const Index lo = std::min(tri[k], tri[k1]), hi = std::max(tri[k], tri[k1]);
      const std::uint64_t key = (std::uint64_t{lo} << 32) | hi;
      std::size_t h = (key * 0x9E3779B97F4A7C15ull) >> (64 - bits);
      while (keys[h] != kEmpty && keys[h] != key) h = (h + 1) & mask;
      if (keys[h] == kEmpty) {
        keys[h] = key;
        key_node[h] = static_cast<Index>(g.edges.size());
        g.edges.push_back({lo, hi, c.tri, k, k1, s, c.side[k], c.side[k1]});
        degree.push_back(0);
      }
      const Index node = key_node[h];
      auto& sn = g.segment_nodes[s];
      (sn[0] == kInvalid ? sn[0] : sn[1]) = node;
      ++degree[node];
    }
  }
  // Segments of each node, in segment order (count, scan, scatter).
  g.node_first.assign(g.edges.size() + 1, 0);
  for (std::size_t n = 0; n < degree.size(); ++n) g.node_first[n + 1] = g.node_first[n] + degree[n];
  g.node_segments.resize(g.node_first.back());
  std::vector<Index> fill(g.node_first.begin(), g.node_first.end() - 1);
  for (Index s = 0; s < g.segment_nodes.size(); ++s) {
    for (Index node : g.segment_nodes[s]) {
      if (node != kInvalid) g.node_segments[fill[node]++] = s;
    }
  }
  return g;
}

// Walks the graph into chains of nodes: from every node that is not a simple pass-through
// (a mesh boundary or a non-manifold edge) first, then around the remaining rings.
std::vector<std::pair<std::vector<Index>, bool>> chain_nodes(const CrossingGraph& g) {
  std::vector<std::pair<std::vector<Index>, bool>> chains;
  std::vector<bool> used(g.segment_nodes.size(), false);
  auto degree = [&](Index n) { return g.node_first[n + 1] - g.node_first[n]; };
  auto walk = [&](Index start, Index seg) {
    std::vector<Index> nodes{start};
    Index node = start;
    while (true) {
      used[seg] = true;
      const auto& sn = g.segment_nodes[seg];
      node = sn[0] == node ? sn[1] : sn[0];
      nodes.push_back(node);
      if (degree(node) != 2) break;
      Index next = kInvalid;
      for (Index i = g.node_first[node]; i < g.node_first[node + 1]; ++i) {
        if (!used[g.node_segments[i]]) next = g.node_segments[i];
      }
      if (next == kInvalid) break;
      seg = next;
    }
    const bool closed = nodes.size() > 2 && nodes.back() == start;
    if (closed) nodes.pop_back();
    chains.emplace_back(std::move(nodes), closed);
  };
  for (Index n = 0; n < g.edges.size(); ++n) {
    if (degree(n) == 2) continue;
    for (Index i = g.node_first[n]; i < g.node_first[n + 1]; ++i) {
      if (!used[g.node_segments[i]]) walk(n, g.node_segments[i]);
    }
  }
  for (Index s = 0; s < g.segment_nodes.size(); ++s) {
    if (!used[s]) walk(g.segment_nodes[s][0], s);
  }
  return chains;
}

// The crossing on one edge, refined onto the patch of the lowest triangle using that edge (or
// left on the edge when refine is false).
SectionPoint refine_node(const Impl& m, const CutPlane& pl, const EdgeUse& e, bool refine) {
  const auto& tri = m.tri[e.tri];
  const Index va = tri[e.ka], vb = tri[e.kb];
  const double f = e.sa / (e.sa - e.sb);
  const Vec3d estimate = m.to_model(m.local[va] + f * (m.local[vb] - m.local[va]));
  const PatchId p = m.tri_patch[e.tri];
  const auto& uv = m.tri_uv[e.tri];
  const SectionPoint on_edge{estimate, p, m.domains[p].map(uv[e.ka] + f * (uv[e.kb] - uv[e.ka]))};
  if (!refine) return on_edge;
  const query::RefinedPlanePoint r =
      query::refine_plane_edge(m.patches[p].surface, m.domains[p], pl.n, pl.model_point, uv[e.ka],
                               uv[e.kb], f, estimate, m.accept_tolerance());
  // A refinement moves the crossing by the chord error, a small part of the edge. A merged
  // triangle that a repair stretched across a patch border carries one patch's (u, v) at a
  // corner that lies on another, and its crossings would refine towards that patch's border, far
  // away: they stay on the edge.
  if (squared_norm(r.point - estimate) >
      kMaxRefineShare * kMaxRefineShare * squared_norm(m.local[vb] - m.local[va])) {
    return on_edge;
  }
  return {r.point, p, r.uv};
}

// The crossed triangles in triangle order, found by the BVH or by a loop over all triangles.
std::vector<Crossed> find_crossed(const Impl& m, const CutPlane& pl, bool brute_force) {
  std::vector<Crossed> crossed;
  Crossed c;
  if (brute_force) {
    for (Index t = 0; t < m.tri.size(); ++t) {
      if (crosses(m, pl, t, m.tri[t], c)) crossed.push_back(c);
    }
  } else {
    std::vector<query::PlaneBvh::SlotRange> leaves;
    leaves.reserve(256);
    m.plane_bvh.query_plane(pl.n, pl.c, leaves);
    std::size_t boxed = 0;
    for (const auto& leaf : leaves) boxed += leaf.count;
    crossed.reserve(boxed);
    for (const auto& leaf : leaves) {
      for (Index slot = leaf.first; slot < leaf.first + leaf.count; ++slot) {
        if (crosses(m, pl, m.plane_bvh.prim(slot), m.plane_bvh.corners(slot), c)) {
          crossed.push_back(c);
        }
      }
    }
    // Triangle order, as the brute-force loop meets them: both give the same section.
    std::sort(crossed.begin(), crossed.end(),
              [](const Crossed& a, const Crossed& b) { return a.tri < b.tri; });
  }
  return crossed;
}

Section cut(const Impl& m, const Plane& plane, const SectionOptions& options, bool brute_force) {
  const CutPlane pl = make_plane(m, plane);
  const std::vector<Crossed> crossed = find_crossed(m, pl, brute_force);
  if (crossed.empty()) return Section{};

  const CrossingGraph g = build_graph(m, crossed);
  std::vector<SectionPoint> points(g.edges.size());
  auto place = [&](std::size_t i) { points[i] = refine_node(m, pl, g.edges[i], options.refine); };
  if (options.refine) {
    parallel_for(0, g.edges.size(), place);
  } else {
    for (std::size_t i = 0; i < g.edges.size(); ++i) place(i);  // too little work for tasks
  }

  // Repeats within 1e-10 L are one point reached from several edges (a plane through a vertex).
  const double repeat_tol = 1e-10 * m.length;
  std::vector<SectionPolyline> pieces;
  for (const auto& [nodes, closed] : chain_nodes(g)) {
    SectionPolyline line;
    line.closed = closed;
    line.points.reserve(nodes.size());
    for (Index n : nodes) line.points.push_back(points[n]);
    query::drop_repeated_points(line, repeat_tol);
    if (line.points.size() < 2) continue;
    if (line.closed && line.points.size() < 3) line.closed = false;
    pieces.push_back(std::move(line));
  }
  return query::assemble_section(std::move(pieces), pl.n, options.join_tolerance * m.length);
}

std::vector<Index> faces_crossed_by(const Impl& m, const Plane& plane, bool brute_force) {
  const std::vector<Crossed> crossed = find_crossed(m, make_plane(m, plane), brute_force);
  std::vector<Index> faces(crossed.size());
  for (std::size_t i = 0; i < crossed.size(); ++i) faces[i] = m.tri_face[crossed[i].tri];
  return faces;
}

}  // namespace

std::vector<Index> HullQuery::crossed_faces(const Plane& plane) const {
  return faces_crossed_by(*impl_, plane, false);
}

std::vector<Index> HullQuery::crossed_faces_brute_force(const Plane& plane) const {
  return faces_crossed_by(*impl_, plane, true);
}

Section HullQuery::section(const Plane& plane, const SectionOptions& options) const {
  return cut(*impl_, plane, options, false);
}

Section HullQuery::section_brute_force(const Plane& plane, const SectionOptions& options) const {
  return cut(*impl_, plane, options, true);
}

std::vector<Section> HullQuery::sections(std::span<const Plane> planes,
                                         const SectionOptions& options) const {
  std::vector<Section> out(planes.size());
  parallel_for_each_item(planes.size(),
                         [&](std::size_t i) { out[i] = cut(*impl_, planes[i], options, false); });
  return out;
}

}  // namespace hm
