#include "kernels/weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"
#include "kernels/order_by_key.h"

namespace hm {
namespace {

using Cell = std::array<std::int64_t, 3>;

std::uint64_t cell_key(const Cell& c) {
  // 21 bits per axis after the range check below, so keys never collide.
  return std::uint64_t(c[0]) | std::uint64_t(c[1]) << 21 | std::uint64_t(c[2]) << 42;
}

}  // namespace

std::vector<ClosePair> find_close_pairs(std::span<const Vec3d> points,
                                        std::span<const std::uint32_t> group, double tolerance) {
  if (!(tolerance > 0)) throw InternalError("find_close_pairs: tolerance must be positive");
  const std::size_t n = points.size();
  if (n < 2) return {};
  BBox3d box;
  for (const Vec3d& p : points) box.add(p);
  const Vec3d e = box.extent();
  const double cells = std::max({e.x, e.y, e.z}) / tolerance + 3;
  if (!(cells < double(1 << 21))) {
    throw LimitError("weld tolerance " + std::to_string(tolerance) +
                     " m is too small for a model of extent " +
                     std::to_string(std::max({e.x, e.y, e.z})) + " m");
  }
  const auto cell_of = [&](const Vec3d& p) {
    // +1 keeps every neighbour cell index non-negative.
    return Cell{std::int64_t((p.x - box.lo.x) / tolerance) + 1,
                std::int64_t((p.y - box.lo.y) / tolerance) + 1,
                std::int64_t((p.z - box.lo.z) / tolerance) + 1};
  };

  // Sort point indices by cell key (ties by index).
  std::vector<std::uint64_t> key(n);
  parallel_for(
      0, n, [&](std::size_t i) { key[i] = cell_key(cell_of(points[i])); }, 1024);
  const std::vector<Index> order = order_by_key(key);
  std::vector<std::uint64_t> sorted_key(n);
  for (std::size_t i = 0; i < n; ++i) sorted_key[i] = key[order[i]];

  // Partners of each point with a larger index, in the 9 rows of cells around it (x - 1 .. x + 1
  // at y + dy, z + dz; consecutive keys). Points are walked in key order: a row's first key is
  // the point's key plus a constant (keys are linear in the cell, every component in range), so
  // each row's cursor only moves forward. Chunks of the key order run in parallel, each starting
  // its cursors by binary search; each fills its own list, and the lists joined are sorted by
  // (a, b), an order of the pairs alone, so that the result does not depend on the chunks.
  constexpr std::size_t kChunk = 1024;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::vector<ClosePair>> chunk_pairs(chunks);
  parallel_for_each_item(chunks, [&](std::size_t c) {
    std::vector<ClosePair>& out = chunk_pairs[c];
    std::array<std::size_t, 9> cursor{};
    const std::size_t first = c * kChunk, last = std::min(n, (c + 1) * kChunk);
    for (std::size_t s = first; s < last; ++s) {
      const Index i = order[s];
      const Cell cell = cell_of(points[i]);
      int row = 0;
      for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy, ++row) {
          const std::uint64_t k0 = cell_key({cell[0] - 1, cell[1] + dy, cell[2] + dz});
          const std::uint64_t k1 = cell_key({cell[0] + 1, cell[1] + dy, cell[2] + dz});
          std::size_t& t0 = cursor[row];
          if (s == first) {
            t0 = std::size_t(std::lower_bound(sorted_key.begin(), sorted_key.end(), k0) -
                             sorted_key.begin());
          } else {
            while (t0 < n && sorted_key[t0] < k0) ++t0;
          }
          for (std::size_t t = t0; t < n && sorted_key[t] <= k1; ++t) {
            const Index j = order[t];
            if (j <= i) continue;
            if (!group.empty() && group[i] == group[j]) continue;
            const double d = norm(points[j] - points[i]);
            if (d < tolerance) out.push_back({i, j, d});
          }
        }
      }
    }
  });
  std::size_t total = 0;
  for (const auto& cp : chunk_pairs) total += cp.size();
  std::vector<ClosePair> pairs;
  pairs.reserve(total);
  for (const auto& cp : chunk_pairs) pairs.insert(pairs.end(), cp.begin(), cp.end());
  std::sort(pairs.begin(), pairs.end(), [](const ClosePair& x, const ClosePair& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  return pairs;
}

std::vector<Index> weld_clusters(std::size_t point_count, std::span<const ClosePair> pairs,
                                 std::span<const std::uint32_t> group) {
  std::vector<Index> parent(point_count);
  std::iota(parent.begin(), parent.end(), Index{0});
  const auto find = [&](Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  // Members of each cluster, a circular list through next_member. A cluster never holds two
  // points of one group, so its groups are its members' groups, each once; clusters are small (a
  // few patches meet at a point), and the lists cost no allocation.
  std::vector<Index> next_member(point_count);
  std::iota(next_member.begin(), next_member.end(), Index{0});
  const auto share_a_group = [&](Index ra, Index rb) {
    for (Index x = ra;;) {
      for (Index y = rb;;) {
        if (group[x] == group[y]) return true;
        if ((y = next_member[y]) == rb) break;
      }
      if ((x = next_member[x]) == ra) return false;
    }
  };
  std::vector<Index> by_distance(pairs.size());
  std::iota(by_distance.begin(), by_distance.end(), Index{0});
  std::sort(by_distance.begin(), by_distance.end(), [&](Index x, Index y) {
    const ClosePair &p = pairs[x], &q = pairs[y];
    if (p.distance != q.distance) return p.distance < q.distance;
    return p.a != q.a ? p.a < q.a : p.b < q.b;
  });
  for (Index k : by_distance) {
    Index ra = find(pairs[k].a), rb = find(pairs[k].b);
    if (ra == rb) continue;
    if (!group.empty() && share_a_group(ra, rb)) continue;
    if (rb < ra) std::swap(ra, rb);
    parent[rb] = ra;                              // the smaller index is the root
    std::swap(next_member[ra], next_member[rb]);  // one circle of both
  }
  std::vector<Index> rep(point_count);
  for (std::size_t i = 0; i < point_count; ++i) rep[i] = find(Index(i));
  return rep;
}

}  // namespace hm
