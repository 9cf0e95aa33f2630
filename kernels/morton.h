// Morton (Z-order) codes and the locality order they give. Used to reorder meshes before
// building adjacency or search structures, and to bin points for welding.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/bbox.h"
#include "core/types.h"
#include "core/vec.h"

namespace hm {

// 63-bit codes: each coordinate quantized to 21 bits over `box` (points outside are clamped) and
// the bits interleaved x, y, z from the lowest. codes.size() must equal points.size().
void morton_codes(std::span<const Vec3d> points, const BBox3d& box, std::span<std::uint64_t> codes);

// The permutation new2old that sorts points by Morton code over their own bounding box, ties by
// index (so it is a pure function of the input, whatever the thread count).
std::vector<Index> morton_order(std::span<const Vec3d> points);

}  // namespace hm
