#include "unstructured/merge_border.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"
#include "kernels/order_by_key.h"
#include "mesh/adjacency.h"

namespace hm::merge {

namespace {

Border border_of_slots(const SurfaceMesh& mesh, std::span<const Index> slots) {
  Border b;
  b.edges.reserve(slots.size());
  std::vector<double> sum(mesh.vertex_count(), 0.0);
  std::vector<std::uint32_t> count(mesh.vertex_count(), 0);
  for (const Index slot : slots) {
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

}  // namespace

Border collect_border(const SurfaceMesh& mesh) {
  return border_of_slots(mesh, boundary_slots(mesh.faces, mesh.vertex_count()));
}

Border collect_border(const SurfaceMesh& mesh, const EdgeAdjacency& adj) {
  std::vector<Index> slots(adj.boundary_edges.size());
  for (std::size_t i = 0; i < slots.size(); ++i)
    slots[i] = adj.edges[adj.boundary_edges[i]].first_slot;
  return border_of_slots(mesh, slots);
}

SegmentGrid::SegmentGrid(std::span<const Vec3d> positions, std::span<const BorderEdge> edges,
                         double min_cell, double median_edges) {
  if (edges.empty()) return;
  BBox3d box;
  std::vector<double> length(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Vec3d &a = positions[edges[i].v0], &b = positions[edges[i].v1];
    box.add(a);
    box.add(b);
    length[i] = norm(b - a);
  }
  std::vector<double> sorted = length;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2),
                   sorted.end());
  const Vec3d e = box.extent();
  const double most = std::max({e.x, e.y, e.z});
  size_ = std::max({median_edges * sorted[sorted.size() / 2], min_cell, 1e-12 * (1 + most)});
  // At most 2^20 cells along an axis keeps the keys in range for any input.
  size_ = std::max(size_, most / double(1 << 20));
  // The exact distance is off by a few ulps of the coordinates; the margin is 1e-9 of them.
  double scale = 1;
  for (int a = 0; a < 3; ++a) scale = std::max({scale, std::abs(box.lo[a]), std::abs(box.hi[a])});
  const double margin = 1e-9 * scale;
  ball_centre_.resize(edges.size());
  ball_radius_.resize(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Vec3d &a = positions[edges[i].v0], &b = positions[edges[i].v1];
    ball_centre_[i] = 0.5 * (a + b);
    ball_radius_[i] = 0.5 * length[i] * (1 + 1e-9) + margin;
  }
  lo_ = box.lo;
  for (int a = 0; a < 3; ++a) dims_[a] = std::int64_t(e[a] / size_) + 1;
  // (cell, edge) entries, made in edge order and put in cell order stably: by cell, then edge.
  std::vector<std::uint64_t> entry_key;
  std::vector<Index> entry_edge;
  entry_key.reserve(edges.size() * 4);
  entry_edge.reserve(edges.size() * 4);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Vec3d &a = positions[edges[i].v0], &b = positions[edges[i].v1];
    std::int64_t lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = cell(std::min(a[k], b[k]), k);
      hi[k] = cell(std::max(a[k], b[k]), k);
    }
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
          entry_key.push_back(key(x, y, z));
          entry_edge.push_back(Index(i));
        }
      }
    }
  }
  const std::vector<Index> entry_new2old = order_by_key(entry_key);
  keys_.resize(entry_key.size());
  order_.resize(entry_key.size());
  for (std::size_t i = 0; i < entry_key.size(); ++i) {
    keys_[i] = entry_key[entry_new2old[i]];
    order_[i] = entry_edge[entry_new2old[i]];
  }
  entry_centre_.resize(order_.size());
  entry_radius_.resize(order_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) {
    entry_centre_[i] = ball_centre_[order_[i]];
    entry_radius_[i] = ball_radius_[order_[i]];
  }
  // Occupied cells in an open-addressing table (load under 1/2): a query looks at 27 or more
  // cells, most of them empty, and a binary search over every entry cost more than the
  // distances.
  std::size_t cells = 0;
  for (std::size_t i = 0; i < keys_.size(); ++i) cells += i == 0 || keys_[i] != keys_[i - 1];
  std::size_t slots = 16;
  while (slots < 2 * cells) slots *= 2;
  slot_key_.assign(slots, kEmptySlot);
  slot_first_.assign(slots, 0);
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    if (i > 0 && keys_[i] == keys_[i - 1]) continue;
    std::size_t h = slot_of(keys_[i]);
    while (slot_key_[h] != kEmptySlot) h = (h + 1) & (slots - 1);
    slot_key_[h] = keys_[i];
    slot_first_[h] = i;
  }
}

std::size_t SegmentGrid::slot_of(std::uint64_t k) const {
  // Fibonacci hashing: cell keys of neighbouring cells differ in their low bits.
  return std::size_t((k * 0x9E3779B97F4A7C15ull) >> 32) & (slot_key_.size() - 1);
}

std::int64_t SegmentGrid::cell(double v, int axis) const {
  const double c = std::floor((v - lo_[axis]) / size_);
  if (!(c >= 0)) return c < 0 ? -1 : 0;  // NaN lands in cell 0
  return std::min<std::int64_t>(std::int64_t(c), dims_[axis]);
}

std::size_t SegmentGrid::first(std::uint64_t k) const {
  for (std::size_t h = slot_of(k);; h = (h + 1) & (slot_key_.size() - 1)) {
    if (slot_key_[h] == k) return slot_first_[h];
    if (slot_key_[h] == kEmptySlot) return order_.size();
  }
}

std::vector<Vec3d> vertex_inward(const SurfaceMesh& m, const Border& b,
                                 std::span<const Index> local) {
  std::vector<Vec3d> in(b.vertices.size(), Vec3d{});
  for (const BorderEdge& e : b.edges) {
    const Vec3d d = edge_inward(m, e);
    in[local[e.v0]] += d;
    in[local[e.v1]] += d;
  }
  for (Vec3d& d : in) {
    const double n = norm(d);
    d = n > 0 ? d / n : Vec3d{};
  }
  return in;
}

Index edge_apex(const SurfaceMesh& m, const BorderEdge& e) {
  const Face& f = m.faces[e.face];
  Index apex = f[0];
  for (int c = 0; c < 3; ++c) {
    if (f[c] != e.v0 && f[c] != e.v1) apex = f[c];
  }
  return apex;
}

Vec3d edge_inward(const SurfaceMesh& m, const BorderEdge& e) {
  const Index apex = edge_apex(m, e);
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
