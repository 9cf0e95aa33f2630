// The stable key order: a radix sort that matches a stable comparison sort, on any thread count.
#include "kernels/order_by_key.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "support/test_support.h"

namespace hm {
namespace {

// The reference: a comparison sort of indices by (key, index).
std::vector<Index> reference_order(const std::vector<std::uint64_t>& keys) {
  std::vector<Index> order(keys.size());
  std::iota(order.begin(), order.end(), Index{0});
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return keys[a] < keys[b]; });
  return order;
}

TEST(OrderByKey, MatchesAStableSortOnEverySizeAndKeyWidth) {
  std::mt19937_64 rng(5);
  // Sizes on both sides of the radix cut-off and of one chunk; keys that differ in every digit,
  // in the top digit only, in a few low bits (many ties), or not at all.
  for (std::size_t n : {0, 1, 2, 700, 1023, 1024, 5000, 70000, 200000}) {
    for (int kind = 0; kind < 4; ++kind) {
      std::vector<std::uint64_t> keys(n);
      for (std::uint64_t& k : keys) {
        const std::uint64_t r = rng();
        k = kind == 0 ? r : kind == 1 ? (r & 0xF000000000000000ULL) : kind == 2 ? (r & 0x7) : 42;
      }
      const std::vector<Index> want = reference_order(keys);
      ASSERT_EQ(order_by_key(keys), want) << "n " << n << " kind " << kind;
    }
  }
}

TEST(OrderByKey, IsTheSameOnOneAndManyThreads) {
  std::mt19937_64 rng(9);
  std::vector<std::uint64_t> keys(700000);  // several chunks
  for (std::uint64_t& k : keys) k = rng() >> 20;
  const std::vector<Index> one = hm::test::with_threads(1, [&] { return order_by_key(keys); });
  const std::vector<Index> many = hm::test::with_threads(8, [&] { return order_by_key(keys); });
  EXPECT_EQ(one, many);
  for (std::size_t i = 1; i < one.size(); ++i) {
    ASSERT_TRUE(keys[one[i - 1]] < keys[one[i]] ||
                (keys[one[i - 1]] == keys[one[i]] && one[i - 1] < one[i]));
  }
}

}  // namespace
}  // namespace hm
