#include "kernels/order_by_key.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "core/parallel.h"

namespace hm {
namespace {

// 11-bit digits: six passes cover 64 bits, and a chunk's counts (16 KiB) stay in L1.
constexpr int kDigitBits = 11;
constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
constexpr std::uint64_t kDigitMask = kBuckets - 1;
// Below this many keys a comparison sort of (key, index) is cheaper than the bucket counts.
constexpr std::size_t kRadixFrom = 1024;
// Chunks of at least this many keys count and scatter in parallel. The order does not depend on
// the chunking: each chunk's keys go to the slots the scan gave its digit, in chunk order.
constexpr std::size_t kChunkKeys = 131072;
constexpr std::size_t kMaxChunks = 64;

struct Item {
  std::uint64_t key;
  Index index;
};

}  // namespace

std::vector<Index> order_by_key(std::span<const std::uint64_t> keys) {
  const std::size_t n = keys.size();
  if (n > std::size_t{kInvalid}) {
    throw LimitError("cannot order " + std::to_string(n) + " keys with 32-bit indices");
  }
  std::vector<Item> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = {keys[i], Index(i)};
  std::vector<Index> new2old(n);
  if (n < kRadixFrom) {
    std::sort(a.begin(), a.end(), [](const Item& x, const Item& y) {
      return x.key != y.key ? x.key < y.key : x.index < y.index;
    });
    for (std::size_t i = 0; i < n; ++i) new2old[i] = a[i].index;
    return new2old;
  }
  // Bits in which some key differs from the first: digits without any are already sorted.
  std::uint64_t differ = 0;
  for (std::size_t i = 0; i < n; ++i) differ |= keys[i] ^ keys[0];

  const std::size_t chunks = std::clamp<std::size_t>(n / kChunkKeys, 1, kMaxChunks);
  const auto chunk_begin = [&](std::size_t c) { return c * n / chunks; };
  std::vector<std::uint32_t> offset(chunks * kBuckets);  // [chunk][digit]
  std::vector<Item> b(n);
  for (int shift = 0; shift < 64; shift += kDigitBits) {
    if (((differ >> shift) & kDigitMask) == 0) continue;
    // count -> exclusive scan (digit-major, chunk-minor) -> scatter: each chunk writes its own
    // slots, and equal digits keep their order, so every pass is stable.
    parallel_for(
        0, chunks,
        [&](std::size_t c) {
          std::uint32_t* count = &offset[c * kBuckets];
          std::fill(count, count + kBuckets, 0u);
          for (std::size_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
            ++count[(a[i].key >> shift) & kDigitMask];
          }
        },
        1, 2);
    std::uint32_t running = 0;
    for (std::size_t d = 0; d < kBuckets; ++d) {
      for (std::size_t c = 0; c < chunks; ++c) {
        const std::uint32_t k = offset[c * kBuckets + d];
        offset[c * kBuckets + d] = running;
        running += k;
      }
    }
    parallel_for(
        0, chunks,
        [&](std::size_t c) {
          std::uint32_t* next = &offset[c * kBuckets];
          for (std::size_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
            b[next[(a[i].key >> shift) & kDigitMask]++] = a[i];
          }
        },
        1, 2);
    a.swap(b);
  }
  for (std::size_t i = 0; i < n; ++i) new2old[i] = a[i].index;
  return new2old;
}

}  // namespace hm
