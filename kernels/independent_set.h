// Independent-set selection for batched, parallel mesh operations (edge collapses, vertex moves):
// of candidates that each touch a region of vertices, keep a set of which no two share a vertex.
// Two rules: local maxima (a candidate wins every vertex of its region; parallel, but in a dense
// batch only a few percent win) and greedy in key order (serial, maximal: many more per batch).
// For single-vertex moves, select_greedy_apart keeps vertices no two of which are neighbours.
// Deterministic: keys are distinct (pack the priority above the candidate index).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"

namespace hm::kernel {

// Key of a candidate: larger wins. `priority` >= 0 (a quality in [0, 1], say); ties go to the
// smaller index. Equal (priority, index) pairs give equal keys.
std::uint64_t priority_key(double priority, Index index);
// The index a key was made from.
inline Index key_index(std::uint64_t key) { return static_cast<Index>(~key & 0xffffffffu); }

// Candidate i touches vertices region[offsets[i] .. offsets[i + 1]) (each < vertex_count; a
// vertex may repeat within one region). Returns the candidates that hold the largest key at
// every vertex of their region, ascending. `marks` is scratch of vertex_count zeros, returned
// zeroed (pass the same vector every round to avoid clearing it).
std::vector<Index> select_independent(std::span<const std::uint64_t> keys,
                                      std::span<const Index> offsets, std::span<const Index> region,
                                      std::vector<std::uint64_t>& marks);

// Greedy: candidates in descending key order, each kept when no kept one shares a vertex with
// it. The result is maximal (every candidate left out shares a vertex with a kept one of larger
// key) and is returned in descending key order. `held` is scratch of vertex_count zeros, returned
// zeroed.
std::vector<Index> select_greedy(std::span<const std::uint64_t> keys,
                                 std::span<const Index> offsets, std::span<const Index> region,
                                 std::vector<std::uint8_t>& held);

// Greedy over vertices, for moves that write one vertex and read its neighbours: candidate i is
// vertex centres[i], with neighbours region[offsets[i] .. offsets[i + 1]) (repeats and the centre
// itself allowed). In descending key order a candidate is kept when it is not a neighbour of a
// kept one and no kept one is its neighbour, so no two kept vertices are adjacent (they may share
// a neighbour: about four times as many per round as select_greedy on the same rings). Maximal.
// Returned ascending. `held` is scratch of vertex_count zeros, returned zeroed.
std::vector<Index> select_greedy_apart(std::span<const std::uint64_t> keys,
                                       std::span<const Index> centres,
                                       std::span<const Index> offsets,
                                       std::span<const Index> region,
                                       std::vector<std::uint8_t>& held);

}  // namespace hm::kernel
