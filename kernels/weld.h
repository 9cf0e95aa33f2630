// Welding: find the points that lie within a tolerance of each other and join them into
// clusters, data-parallel and deterministic. Points are binned in a uniform grid of cell size
// `tolerance` and sorted by cell; each point searches the 27 cells around it.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm {

struct ClosePair {
  Index a = kInvalid, b = kInvalid;  // a < b
  double distance = 0;
};

// Every pair of points closer than `tolerance` (> 0), sorted by (a, b). Points whose group ids
// are equal are never paired (pass an empty span to pair everything). Throws LimitError when the
// grid would need more than 2^21 cells per axis (tolerance too small for the extent).
std::vector<ClosePair> find_close_pairs(std::span<const Vec3d> points,
                                        std::span<const std::uint32_t> group, double tolerance);

// Clusters from close pairs, joined nearest pair first (ties by index), never putting two points
// of one group into a cluster. Returns rep: rep[i] is the smallest index in i's cluster.
std::vector<Index> weld_clusters(std::size_t point_count, std::span<const ClosePair> pairs,
                                 std::span<const std::uint32_t> group);

}  // namespace hm
