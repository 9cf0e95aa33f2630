#include "unstructured/merge_border.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/bbox.h"
#include "core/error.h"
#include "mesh/adjacency.h"

namespace hm::merge {

Border collect_border(const SurfaceMesh& mesh) {
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  Border b;
  b.edges.reserve(adj.boundary_edges.size());
  std::vector<double> sum(mesh.vertex_count(), 0.0);
  std::vector<std::uint32_t> count(mesh.vertex_count(), 0);
  for (Index e : adj.boundary_edges) {
    const Index slot = adj.edges[e].first_slot;
    const Face& f = mesh.faces[slot / 4];
    const int c = int(slot % 4);
    const BorderEdge be{f[c], f[(c + 1) % corner_count(f)], slot / 4, mesh.face_patch[slot / 4]};
    b.edges.push_back(be);
    const double len = norm(mesh.positions[be.v1] - mesh.positions[be.v0]);
    for (Index v : {be.v0, be.v1}) {
      sum[v] += len;
      ++count[v];
    }
  }
  for (std::size_t v = 0; v < count.size(); ++v) {
    if (count[v] == 0) continue;
    b.vertices.push_back(Index(v));
    b.edge_length.push_back(sum[v] / count[v]);
  }
  return b;
}

SegmentGrid::SegmentGrid(std::span<const Vec3d> positions, std::span<const BorderEdge> edges,
                         double reach) {
  if (edges.empty()) return;
  BBox3d box;
  double longest = 0;
  std::vector<Vec3d> mid(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Vec3d &a = positions[edges[i].v0], &b = positions[edges[i].v1];
    mid[i] = 0.5 * (a + b);
    box.add(mid[i]);
    longest = std::max(longest, norm(b - a));
  }
  // A point within reach of an edge is within (half its length + reach) of its midpoint.
  size_ = std::max(0.5 * longest + reach, 1e-12 * (1 + box.diagonal()));
  // Bound the cell count (a few very long edges would otherwise make a huge sparse grid moot;
  // cells are only keys, so the bound protects the key range, not memory).
  const Vec3d e = box.extent();
  const double most = std::max({e.x, e.y, e.z});
  if (most / size_ > 1e6) size_ = most / 1e6;
  lo_ = box.lo;
  for (int a = 0; a < 3; ++a) dims_[a] = std::int64_t(e[a] / size_) + 1;
  std::vector<std::pair<std::uint64_t, Index>> items(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    items[i] = {key(cell(mid[i].x, 0), cell(mid[i].y, 1), cell(mid[i].z, 2)), Index(i)};
  }
  std::sort(items.begin(), items.end());
  keys_.resize(items.size());
  order_.resize(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    keys_[i] = items[i].first;
    order_[i] = items[i].second;
  }
}

std::int64_t SegmentGrid::cell(double v, int axis) const {
  const double c = std::floor((v - lo_[axis]) / size_);
  if (!(c >= 0)) return c < 0 ? std::max<std::int64_t>(std::int64_t(c), -2) : -2;
  return std::min<std::int64_t>(std::int64_t(c), dims_[axis] + 1);
}

std::size_t SegmentGrid::first(std::uint64_t k) const {
  return std::size_t(std::lower_bound(keys_.begin(), keys_.end(), k) - keys_.begin());
}

Vec3d edge_inward(const SurfaceMesh& m, const BorderEdge& e) {
  const Face& f = m.faces[e.face];
  Index apex = f[0];
  for (int c = 0; c < 3; ++c) {
    if (f[c] != e.v0 && f[c] != e.v1) apex = f[c];
  }
  const Vec3d a = m.positions[e.v0], d = m.positions[e.v1] - a;
  Vec3d in = m.positions[apex] - a;
  const double dd = dot(d, d);
  if (dd > 0) in -= (dot(in, d) / dd) * d;
  const double n = norm(in);
  return n > 0 ? in / n : Vec3d{};
}

SegmentPoint closest_on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double len2 = dot(ab, ab);
  double t = len2 > 0 ? dot(p - a, ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return {t, norm(p - (a + t * ab))};
}

}  // namespace hm::merge
