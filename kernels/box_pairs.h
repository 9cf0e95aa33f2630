// Broad phase: the pairs of axis-aligned boxes that overlap, data-parallel and deterministic.
// Boxes are binned in a uniform grid (cell edge: the median box extent) and sorted by cell; each
// pair is tested once, in the cell that holds the low corner of the two boxes' intersection.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm {

// Every pair (a, b), a < b, of boxes [lo[i], hi[i]] that overlap or touch and for which
// keep(a, b) holds, sorted. keep runs on several threads at once and must only read shared
// state. Boxes with a NaN corner or lo > hi on an axis pair with nothing. Throws LimitError
// when the grid would hold more than max_entries (box, cell) entries, counted before any
// allocation; the cell edge is first widened (up to 8 times) to stay under it.
std::vector<std::array<Index, 2>> overlapping_box_pairs(
    std::span<const Vec3d> lo, std::span<const Vec3d> hi,
    const std::function<bool(Index, Index)>& keep, std::size_t max_entries = 0);

}  // namespace hm
