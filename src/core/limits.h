// Resource limits for untrusted input. Every declared size is checked against these before any
// allocation, so a small hostile file cannot make hullmesh allocate gigabytes or run for minutes.
#pragma once

#include <cstdint>

namespace hm {

struct ResourceLimits {
  std::uint64_t max_file_bytes = 2ull << 30;         // 2 GiB
  std::uint64_t max_entities = 5'000'000;            // directory entries
  std::uint64_t max_params_per_entity = 20'000'000;  // parameters of one entity
  std::uint64_t max_control_points = 4'000'000;      // per patch or curve
  int max_degree = 40;                               // per parameter direction
  std::uint64_t max_knots = 4'000'000;               // per direction
  std::uint64_t max_pointer_depth = 64;              // chains of 124 / nested trims
  std::uint64_t max_triangles = 50'000'000;          // total triangles of one mesh
  int max_refine_depth = 12;                         // adaptive refinement levels
};

}  // namespace hm
