#include "mesh/adjacency.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "core/parallel.h"

namespace hm {
namespace {

// One corner's edge: (min vertex, max vertex) packed for sorting, then the slot 4 f + c.
struct EdgeKey {
  std::uint64_t key;
  Index slot;
  bool operator<(const EdgeKey& o) const { return key != o.key ? key < o.key : slot < o.slot; }
};

std::uint64_t pack(Index a, Index b) { return (std::uint64_t{a} << 32) | b; }

// The directed edge (tail, head) of a slot as its face traverses it.
std::array<Index, 2> directed(std::span<const Face> faces, Index slot) {
  const Face& f = faces[slot / 4];
  const int c = static_cast<int>(slot % 4);
  return {f[c], f[(c + 1) % corner_count(f)]};
}

// Keys sorted by (min vertex, max vertex, slot): a counting sort on the min vertex (count ->
// exclusive scan -> scatter in slot order), then an insertion sort inside each vertex's bucket,
// which holds only that vertex's few edges. Linear, and the same for any thread count.
std::vector<EdgeKey> collect_keys(std::span<const Face> faces, std::size_t vertex_count) {
  // Calls f(a, b, slot) for every corner's edge a -> b (callers skip a == b: a collapsed corner
  // has no edge).
  const auto for_each_edge = [&](auto&& f) {
    for (std::size_t fi = 0; fi < faces.size(); ++fi) {
      const Face& face = faces[fi];
      const int n = corner_count(face);
      for (int c = 0; c < n; ++c) {
        const Index a = face[c], b = face[(c + 1) % n];
        f(a, b, static_cast<Index>(4 * fi + c));
      }
    }
  };
  std::vector<Index> count(vertex_count + 1, 0);
  std::size_t total = 0;
  for_each_edge([&](Index a, Index b, Index slot) {
    if (a >= vertex_count || b >= vertex_count) {
      throw GeometryError("face " + std::to_string(slot / 4) + " names vertex " +
                          std::to_string(std::max(a, b)) + " of a mesh with " +
                          std::to_string(vertex_count) + " vertices");
    }
    if (a == b) return;
    ++count[std::min(a, b) + 1];
    ++total;
  });
  for (std::size_t v = 0; v < vertex_count; ++v) count[v + 1] += count[v];
  std::vector<EdgeKey> keys(total);
  std::vector<Index> next(count.begin(), count.end() - 1);
  for_each_edge([&](Index a, Index b, Index slot) {
    if (a == b) return;
    keys[next[std::min(a, b)]++] = {pack(std::min(a, b), std::max(a, b)), slot};
  });
  parallel_for(
      0, vertex_count,
      [&](std::size_t v) {
        // Slots arrive ascending, so sorting by key keeps equal keys in slot order.
        for (Index i = count[v] + 1; i < count[v + 1]; ++i) {
          const EdgeKey k = keys[i];
          Index j = i;
          for (; j > count[v] && k < keys[j - 1]; --j) keys[j] = keys[j - 1];
          keys[j] = k;
        }
      },
      4096);
  return keys;
}

// Chains the directed boundary edges into loops: open chains first (from vertices with no incoming
// boundary edge), then closed loops, each started at its lowest unused edge id. At a vertex with
// several outgoing boundary edges the lowest unused id is taken, so the result is deterministic.
std::vector<BoundaryLoop> chain_boundary(std::span<const Face> faces, const EdgeAdjacency& adj) {
  const std::vector<Index>& be = adj.boundary_edges;
  std::vector<std::array<Index, 2>> dir(be.size());
  std::vector<std::pair<Index, Index>> outgoing(be.size());  // (tail vertex, local index)
  std::vector<std::pair<Index, Index>> incoming(be.size());  // (head vertex, local index)
  for (std::size_t i = 0; i < be.size(); ++i) {
    dir[i] = directed(faces, adj.edges[be[i]].first_slot);
    outgoing[i] = {dir[i][0], static_cast<Index>(i)};
    incoming[i] = {dir[i][1], static_cast<Index>(i)};
  }
  std::sort(outgoing.begin(), outgoing.end());
  std::sort(incoming.begin(), incoming.end());
  auto has_incoming = [&](Index v) {
    auto it = std::lower_bound(incoming.begin(), incoming.end(), std::pair<Index, Index>{v, 0});
    return it != incoming.end() && it->first == v;
  };
  std::vector<bool> used(be.size(), false);
  auto next_from = [&](Index v) -> Index {
    auto it = std::lower_bound(outgoing.begin(), outgoing.end(), std::pair<Index, Index>{v, 0});
    for (; it != outgoing.end() && it->first == v; ++it)
      if (!used[it->second]) return it->second;
    return kInvalid;
  };
  std::vector<BoundaryLoop> loops;
  auto walk = [&](Index start) {
    BoundaryLoop loop;
    const Index first_vertex = dir[start][0];
    Index cur = start;
    while (cur != kInvalid) {
      used[cur] = true;
      loop.vertices.push_back(dir[cur][0]);
      loop.edges.push_back(be[cur]);
      const Index head = dir[cur][1];
      if (head == first_vertex) {
        loop.closed = true;
        break;
      }
      cur = next_from(head);
      if (cur == kInvalid) loop.vertices.push_back(head);
    }
    loops.push_back(std::move(loop));
  };
  for (std::size_t i = 0; i < be.size(); ++i)
    if (!used[i] && !has_incoming(dir[i][0])) walk(static_cast<Index>(i));
  for (std::size_t i = 0; i < be.size(); ++i)
    if (!used[i]) walk(static_cast<Index>(i));
  return loops;
}

}  // namespace

void reverse_in_adjacency(EdgeAdjacency& adj, std::span<const Face> faces,
                          std::span<const std::uint8_t> reversed) {
  if (reversed.size() != faces.size() || adj.slot_edge.size() != 4 * faces.size()) {
    throw GeometryError("reverse_in_adjacency: the adjacency is of another mesh");
  }
  // Corner c of a reversed face is corner 2 - c of the face it was (for c < 3).
  const auto corner = [](std::uint8_t c) -> std::uint8_t { return c < 3 ? 2 - c : c; };
  for (std::size_t s = 0; s < adj.opposite_face.size(); ++s) {
    const Index g = adj.opposite_face[s];
    if (g != kInvalid && reversed[g]) adj.opposite_corner[s] = corner(adj.opposite_corner[s]);
  }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (!reversed[f]) continue;
    if (!is_triangle(faces[f])) {
      throw GeometryError("reverse_in_adjacency: face " + std::to_string(f) + " is not a triangle");
    }
    std::swap(adj.slot_edge[4 * f], adj.slot_edge[4 * f + 2]);
    std::swap(adj.opposite_face[4 * f], adj.opposite_face[4 * f + 2]);
    std::swap(adj.opposite_corner[4 * f], adj.opposite_corner[4 * f + 2]);
  }
  adj.inconsistent_edges.clear();
  for (std::size_t e = 0; e < adj.edges.size(); ++e) {
    MeshEdge& me = adj.edges[e];
    const Index f = me.first_slot / 4;
    if (reversed[f]) me.first_slot = 4 * f + corner(std::uint8_t(me.first_slot % 4));
    if (me.uses != 2) continue;
    const Index s0 = me.first_slot;
    const Index s1 = 4 * adj.opposite_face[s0] + adj.opposite_corner[s0];
    me.same_direction = directed(faces, s0)[0] == directed(faces, s1)[0];
    if (me.same_direction) adj.inconsistent_edges.push_back(Index(e));
  }
  adj.boundary_loops = chain_boundary(faces, adj);
}

std::vector<Index> boundary_slots(std::span<const Face> faces, std::size_t vertex_count) {
  const std::vector<EdgeKey> keys = collect_keys(faces, vertex_count);
  std::vector<Index> out;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j].key == keys[i].key) ++j;
    if (j == i + 1) out.push_back(keys[i].slot);
    i = j;
  }
  return out;
}

EdgeAdjacency build_edge_adjacency(std::span<const Face> faces, std::size_t vertex_count) {
  const std::vector<EdgeKey> keys = collect_keys(faces, vertex_count);
  EdgeAdjacency adj;
  adj.slot_edge.assign(faces.size() * 4, kInvalid);
  adj.opposite_face.assign(faces.size() * 4, kInvalid);
  adj.opposite_corner.assign(faces.size() * 4, 0xff);
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j].key == keys[i].key) ++j;
    MeshEdge e;
    e.v0 = static_cast<Index>(keys[i].key >> 32);
    e.v1 = static_cast<Index>(keys[i].key & 0xffffffffu);
    e.first_slot = keys[i].slot;
    e.uses = static_cast<Index>(j - i);
    const Index id = static_cast<Index>(adj.edges.size());
    for (std::size_t k = i; k < j; ++k) adj.slot_edge[keys[k].slot] = id;
    if (e.uses == 1) {
      adj.boundary_edges.push_back(id);
    } else if (e.uses == 2) {
      const Index s0 = keys[i].slot, s1 = keys[i + 1].slot;
      e.same_direction = directed(faces, s0)[0] == directed(faces, s1)[0];
      if (e.same_direction) adj.inconsistent_edges.push_back(id);
      adj.opposite_face[s0] = s1 / 4;
      adj.opposite_corner[s0] = static_cast<std::uint8_t>(s1 % 4);
      adj.opposite_face[s1] = s0 / 4;
      adj.opposite_corner[s1] = static_cast<std::uint8_t>(s0 % 4);
    } else {
      adj.nonmanifold_edges.push_back(id);
    }
    adj.edges.push_back(e);
    i = j;
  }
  adj.boundary_loops = chain_boundary(faces, adj);
  return adj;
}

Index find_edge(const EdgeAdjacency& adj, Index a, Index b) {
  const std::pair key{std::min(a, b), std::max(a, b)};
  const auto it = std::lower_bound(adj.edges.begin(), adj.edges.end(), key,
                                   [](const MeshEdge& m, const std::pair<Index, Index>& k) {
                                     return std::pair{m.v0, m.v1} < k;
                                   });
  if (it == adj.edges.end() || it->v0 != key.first || it->v1 != key.second) return kInvalid;
  return static_cast<Index>(it - adj.edges.begin());
}

}  // namespace hm
