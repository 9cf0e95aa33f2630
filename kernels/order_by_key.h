// The stable order of 64-bit keys: the sort behind Morton orders, weld cells and grid bins.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"

namespace hm {

// new2old such that keys[new2old[i]] ascend, equal keys in ascending index: a pure function of
// the keys, whatever the thread count. A least-significant-digit radix sort, which skips the
// digits no two keys differ in. Throws LimitError above 2^32 - 1 keys (32-bit indices).
std::vector<Index> order_by_key(std::span<const std::uint64_t> keys);

}  // namespace hm
