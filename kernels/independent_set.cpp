#include "kernels/independent_set.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <functional>
#include <numeric>

#include "core/parallel.h"

namespace hm::kernel {
namespace {

// Each item is a few atomic operations: below this many, one thread is faster than waking more.
constexpr std::size_t kSerialBelow = 4096;

}  // namespace

std::uint64_t priority_key(double priority, Index index) {
  // Non-negative floats order like their bit patterns; the low 32 bits break ties toward the
  // smaller index.
  const float p = static_cast<float>(std::isfinite(priority) && priority > 0 ? priority : 0.0);
  const std::uint64_t bits = std::bit_cast<std::uint32_t>(p);
  return (bits << 32) | (~std::uint64_t{index} & 0xffffffffu);
}

std::vector<Index> select_independent(std::span<const std::uint64_t> keys,
                                      std::span<const Index> offsets, std::span<const Index> region,
                                      std::vector<std::uint64_t>& marks) {
  const std::size_t n = keys.size();
  // Every candidate raises the mark of its vertices to its key (atomic max: the final marks do
  // not depend on the order the writes happen in).
  parallel_for(
      0, n,
      [&](std::size_t i) {
        for (Index k = offsets[i]; k < offsets[i + 1]; ++k) {
          std::atomic_ref<std::uint64_t> m(marks[region[k]]);
          std::uint64_t cur = m.load(std::memory_order_relaxed);
          while (cur < keys[i] &&
                 !m.compare_exchange_weak(cur, keys[i], std::memory_order_relaxed)) {
          }
        }
      },
      256, kSerialBelow);
  std::vector<std::uint8_t> won(n, 0);
  parallel_for(
      0, n,
      [&](std::size_t i) {
        bool all = true;
        for (Index k = offsets[i]; k < offsets[i + 1] && all; ++k) {
          all = std::atomic_ref<std::uint64_t>(marks[region[k]]).load(std::memory_order_relaxed) ==
                keys[i];
        }
        won[i] = all;
      },
      256, kSerialBelow);
  // Clear only what was written; concurrent stores of the same zero are benign under atomic_ref.
  parallel_for(
      0, n,
      [&](std::size_t i) {
        for (Index k = offsets[i]; k < offsets[i + 1]; ++k) {
          std::atomic_ref<std::uint64_t>(marks[region[k]]).store(0, std::memory_order_relaxed);
        }
      },
      256, kSerialBelow);
  std::vector<Index> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (won[i]) out.push_back(static_cast<Index>(i));
  }
  return out;
}

std::vector<Index> select_greedy(std::span<const std::uint64_t> keys,
                                 std::span<const Index> offsets, std::span<const Index> region,
                                 std::vector<std::uint8_t>& held) {
  std::vector<Index> order(keys.size());
  std::iota(order.begin(), order.end(), Index{0});
  // Callers that rank their batch first pass it in order already.
  if (!std::is_sorted(keys.begin(), keys.end(), std::greater<>())) {
    std::sort(order.begin(), order.end(), [&](Index a, Index b) { return keys[a] > keys[b]; });
  }
  std::vector<Index> out;
  for (Index i : order) {
    bool free = true;
    for (Index k = offsets[i]; k < offsets[i + 1] && free; ++k) free = !held[region[k]];
    if (!free) continue;
    for (Index k = offsets[i]; k < offsets[i + 1]; ++k) held[region[k]] = 1;
    out.push_back(i);
  }
  for (Index i : out) {
    for (Index k = offsets[i]; k < offsets[i + 1]; ++k) held[region[k]] = 0;
  }
  return out;
}

std::vector<Index> select_greedy_apart(std::span<const std::uint64_t> keys,
                                       std::span<const Index> centres,
                                       std::span<const Index> offsets,
                                       std::span<const Index> region,
                                       std::vector<std::uint8_t>& held) {
  // held: 2 at a kept centre, 1 at a neighbour of one (either side of an edge may list it).
  constexpr std::uint8_t kKept = 2, kNear = 1;
  std::vector<Index> order(keys.size());
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return keys[a] > keys[b]; });
  std::vector<Index> out;
  for (Index i : order) {
    bool free = held[centres[i]] == 0;
    for (Index k = offsets[i]; k < offsets[i + 1] && free; ++k) free = held[region[k]] != kKept;
    if (!free) continue;
    held[centres[i]] = kKept;
    for (Index k = offsets[i]; k < offsets[i + 1]; ++k) {
      if (region[k] != centres[i]) held[region[k]] = kNear;
    }
    out.push_back(i);
  }
  for (Index i : out) {
    held[centres[i]] = 0;
    for (Index k = offsets[i]; k < offsets[i + 1]; ++k) held[region[k]] = 0;
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace hm::kernel
