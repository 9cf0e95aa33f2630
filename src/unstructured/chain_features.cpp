// Feature graph (CSR by vertex, edges in ascending id), corners, knuckle chains.
#include "unstructured/chain_features.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace hm::detail {
namespace {

// Feature edges around each vertex, ascending edge ids (so every walk below is deterministic).
struct FeatureGraph {
  std::vector<Index> offset;  // vertex_count + 1
  std::vector<Index> edge;    // edge ids, offset[v] .. offset[v + 1]

  std::span<const Index> around(Index v) const {
    return {edge.data() + offset[v], edge.data() + offset[v + 1]};
  }
  Index degree(Index v) const { return offset[v + 1] - offset[v]; }
};

FeatureGraph build_graph(std::size_t vertex_count, const EdgeAdjacency& adjacency,
                         std::span<const std::uint8_t> is_feature) {
  FeatureGraph g;
  g.offset.assign(vertex_count + 1, 0);
  for (std::size_t e = 0; e < adjacency.edges.size(); ++e) {
    if (!is_feature[e]) continue;
    ++g.offset[adjacency.edges[e].v0 + 1];
    ++g.offset[adjacency.edges[e].v1 + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) g.offset[v + 1] += g.offset[v];
  g.edge.resize(g.offset.back());
  std::vector<Index> fill(g.offset.begin(), g.offset.end() - 1);
  for (std::size_t e = 0; e < adjacency.edges.size(); ++e) {
    if (!is_feature[e]) continue;
    g.edge[fill[adjacency.edges[e].v0]++] = static_cast<Index>(e);
    g.edge[fill[adjacency.edges[e].v1]++] = static_cast<Index>(e);
  }
  return g;
}

Index other_end(const MeshEdge& e, Index v) { return e.v0 == v ? e.v1 : e.v0; }

double turn_deg(const Vec3d& a, const Vec3d& b) {
  return std::atan2(norm(cross(a, b)), dot(a, b)) * 180.0 / std::numbers::pi;
}

std::vector<std::uint8_t> find_corners(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                                       const FeatureGraph& g,
                                       std::span<const std::uint8_t> edge_knuckle,
                                       std::span<const BoundaryRun> boundaries) {
  std::vector<std::uint8_t> corner(mesh.vertex_count(), 0);
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const Index v = static_cast<Index>(i);
    const Index d = g.degree(v);
    if (d == 0) continue;
    if (d != 2) {
      corner[v] = 1;
      continue;
    }
    const Index e0 = g.around(v)[0], e1 = g.around(v)[1];
    if (edge_knuckle[e0] != edge_knuckle[e1]) {
      corner[v] = 1;
      continue;
    }
    const Vec3d& p = mesh.positions[v];
    const Vec3d in = p - mesh.positions[other_end(adjacency.edges[e0], v)];
    const Vec3d out = mesh.positions[other_end(adjacency.edges[e1], v)] - p;
    if (turn_deg(in, out) > kCornerTurnDeg) corner[v] = 1;
  }
  for (const BoundaryRun& run : boundaries) {
    if (run.closed || run.vertices.empty()) continue;
    corner[run.vertices.front()] = 1;
    corner[run.vertices.back()] = 1;
  }
  return corner;
}

// Walks knuckle edges from v along `first` until a corner, a dead end or back at the start.
FeatureLine walk(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency, const FeatureGraph& g,
                 std::span<const std::uint8_t> edge_knuckle, std::span<const std::uint8_t> corner,
                 Index v, Index first, std::vector<std::uint8_t>& used) {
  FeatureLine line;
  line.vertices.push_back(v);
  Index e = first;
  while (e != kInvalid) {
    used[e] = 1;
    const Index next = other_end(adjacency.edges[e], v);
    line.length += norm(mesh.positions[next] - mesh.positions[v]);
    v = next;
    if (v == line.vertices.front()) {
      line.closed = true;
      break;
    }
    line.vertices.push_back(v);
    if (corner[v]) break;
    e = kInvalid;
    for (Index k : g.around(v)) {
      if (edge_knuckle[k] && !used[k]) {
        e = k;
        break;
      }
    }
  }
  return line;
}

void orient(FeatureLine& line) {
  std::vector<Index>& v = line.vertices;
  if (!line.closed) {
    if (v.back() < v.front()) std::reverse(v.begin(), v.end());
    return;
  }
  std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
  if (v.size() > 2 && v.back() < v[1]) std::reverse(v.begin() + 1, v.end());
}

}  // namespace

ChainedFeatures chain_features(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                               std::span<const std::uint8_t> edge_knuckle,
                               std::span<const BoundaryRun> boundaries) {
  std::vector<std::uint8_t> is_feature(adjacency.edges.size());
  for (std::size_t e = 0; e < is_feature.size(); ++e) {
    is_feature[e] = edge_knuckle[e] || adjacency.edges[e].uses == 1;
  }
  const FeatureGraph g = build_graph(mesh.vertex_count(), adjacency, is_feature);
  const std::vector<std::uint8_t> corner =
      find_corners(mesh, adjacency, g, edge_knuckle, boundaries);

  ChainedFeatures out;
  std::vector<std::uint8_t> used(adjacency.edges.size(), 0);
  // Open lines from every corner first, then the closed loops that meet no corner.
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
      const Index v = static_cast<Index>(i);
      if (pass == 0 && !corner[v]) continue;
      for (Index e : g.around(v)) {
        if (edge_knuckle[e] && !used[e]) {
          out.knuckles.push_back(walk(mesh, adjacency, g, edge_knuckle, corner, v, e, used));
        }
      }
    }
  }
  for (FeatureLine& line : out.knuckles) orient(line);
  std::sort(
      out.knuckles.begin(), out.knuckles.end(), [](const FeatureLine& a, const FeatureLine& b) {
        return std::pair(a.vertices[0], a.vertices[1]) < std::pair(b.vertices[0], b.vertices[1]);
      });

  out.vertex_feature.assign(mesh.vertex_count(), VertexFeature::kSmooth);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (corner[v]) {
      out.vertex_feature[v] = VertexFeature::kCorner;
      out.corners.push_back(static_cast<Index>(v));
    } else if (g.degree(static_cast<Index>(v)) > 0) {
      out.vertex_feature[v] = VertexFeature::kOnLine;
    }
  }
  return out;
}

}  // namespace hm::detail
