// Independent-set selection for batched, parallel mesh operations (edge collapses, vertex moves):
// of candidates that each touch a region of vertices, keep those that win every vertex of their
// region, so no two kept candidates share a vertex. Deterministic: the winner at a vertex is the
// largest key, and keys are distinct (pack the priority above the candidate index).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"

namespace hm::kernel {

// Key of a candidate: larger wins. `priority` >= 0 (a quality in [0, 1], say); ties go to the
// smaller index. Equal (priority, index) pairs give equal keys.
std::uint64_t priority_key(double priority, Index index);

// Candidate i touches vertices region[offsets[i] .. offsets[i + 1]) (each < vertex_count; a
// vertex may repeat within one region). Returns the candidates that hold the largest key at
// every vertex of their region, ascending. `marks` is scratch of vertex_count zeros, returned
// zeroed (pass the same vector every round to avoid clearing it).
std::vector<Index> select_independent(std::span<const std::uint64_t> keys,
                                      std::span<const Index> offsets, std::span<const Index> region,
                                      std::vector<std::uint64_t>& marks);

}  // namespace hm::kernel
