// Morton ordering: a permutation sorted by code, codes that follow the bit interleaving.
#include "kernels/morton.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "support/test_support.h"

namespace hm {
namespace {

TEST(MortonCodes, InterleaveTheAxesFromTheLowestBit) {
  BBox3d box;
  box.add(Vec3d{0, 0, 0});
  box.add(Vec3d{1, 1, 1});
  std::vector<Vec3d> p = {{0, 0, 0}, {1, 1, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  std::vector<std::uint64_t> c(p.size());
  morton_codes(p, box, c);
  EXPECT_EQ(c[0], 0u);
  EXPECT_EQ(c[1], (std::uint64_t{1} << 63) - 1);  // every one of the 63 bits
  EXPECT_EQ(c[2], 0x1249249249249249ULL);         // x on bits 0, 3, 6, ...
  EXPECT_EQ(c[3], 0x1249249249249249ULL << 1);
  EXPECT_EQ(c[4], 0x1249249249249249ULL << 2);
}

TEST(MortonOrder, IsAPermutationSortedByCodeAndThreadIndependent) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-50, 50);
  std::vector<Vec3d> p(50000);
  for (Vec3d& x : p) x = {u(rng), u(rng) * 0.1, u(rng) * 0.1};
  p[10] = p[20];  // equal codes: ties go by index
  const std::vector<Index> one = hm::test::with_threads(1, [&] { return morton_order(p); });
  const std::vector<Index> two = hm::test::with_threads(8, [&] { return morton_order(p); });
  EXPECT_EQ(one, two);
  std::vector<Index> sorted = one;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
  BBox3d box;
  for (const Vec3d& x : p) box.add(x);
  std::vector<std::uint64_t> c(p.size());
  morton_codes(p, box, c);
  for (std::size_t i = 1; i < one.size(); ++i) {
    ASSERT_LE(c[one[i - 1]], c[one[i]]);
    if (c[one[i - 1]] == c[one[i]]) {
      ASSERT_LT(one[i - 1], one[i]);
    }
  }
}

}  // namespace
}  // namespace hm
