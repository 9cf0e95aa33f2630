#include "kernels/weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"

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
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), Index{0});
  parallel_sort(order.begin(), order.end(),
                [&](Index a, Index b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
  std::vector<std::uint64_t> sorted_key(n);
  for (std::size_t i = 0; i < n; ++i) sorted_key[i] = key[order[i]];

  // Partners of point i with a larger index, in ascending order, passed to emit. The three cells
  // x - 1, x, x + 1 of a row are consecutive keys, so each of the 9 rows is one range.
  const auto for_partners = [&](std::size_t i, auto&& emit) {
    const Cell c = cell_of(points[i]);
    std::vector<Index> found;
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        const std::uint64_t k0 = cell_key({c[0] - 1, c[1] + dy, c[2] + dz});
        const std::uint64_t k1 = cell_key({c[0] + 1, c[1] + dy, c[2] + dz});
        auto it = std::lower_bound(sorted_key.begin(), sorted_key.end(), k0);
        for (; it != sorted_key.end() && *it <= k1; ++it) {
          const Index j = order[std::size_t(it - sorted_key.begin())];
          if (j <= i) continue;
          if (!group.empty() && group[i] == group[j]) continue;
          if (norm(points[j] - points[i]) < tolerance) found.push_back(j);
        }
      }
    }
    std::sort(found.begin(), found.end());
    for (Index j : found) emit(j);
  };

  // Evaluate in parallel, commit in a fixed order: blocks of kBlock points (a size that does not
  // depend on the thread count) each fill their own list, joined in block order. The cell search
  // runs once per point. (Most points have no partner, so the small vector above rarely
  // allocates.)
  constexpr std::size_t kBlock = 256;
  const std::size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::vector<ClosePair>> block_pairs(blocks);
  parallel_for_each_item(blocks, [&](std::size_t b) {
    std::vector<ClosePair>& out = block_pairs[b];
    for (std::size_t i = b * kBlock; i < std::min(n, (b + 1) * kBlock); ++i) {
      for_partners(i, [&](Index j) { out.push_back({Index(i), j, norm(points[j] - points[i])}); });
    }
  });
  std::size_t total = 0;
  for (const auto& bp : block_pairs) total += bp.size();
  std::vector<ClosePair> pairs;
  pairs.reserve(total);
  for (const auto& bp : block_pairs) pairs.insert(pairs.end(), bp.begin(), bp.end());
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
  // Groups present in each cluster, kept at the root (sorted, small: a few patches meet at a
  // point).
  std::vector<std::vector<std::uint32_t>> groups;
  if (!group.empty()) {
    groups.resize(point_count);
    for (std::size_t i = 0; i < point_count; ++i) groups[i] = {group[i]};
  }
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
    if (!group.empty()) {
      std::vector<std::uint32_t>&ga = groups[ra], &gb = groups[rb];
      std::vector<std::uint32_t> both;
      std::set_intersection(ga.begin(), ga.end(), gb.begin(), gb.end(), std::back_inserter(both));
      if (!both.empty()) continue;
      std::vector<std::uint32_t> merged;
      std::set_union(ga.begin(), ga.end(), gb.begin(), gb.end(), std::back_inserter(merged));
      if (rb < ra) std::swap(ra, rb);
      groups[ra] = std::move(merged);
      groups[rb].clear();
    } else if (rb < ra) {
      std::swap(ra, rb);
    }
    parent[rb] = ra;  // the smaller index is the root
  }
  std::vector<Index> rep(point_count);
  for (std::size_t i = 0; i < point_count; ++i) rep[i] = find(Index(i));
  return rep;
}

}  // namespace hm
