// The weld kernel against a brute-force double loop, and its clustering rules.
#include "kernels/weld.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>
#include <vector>

#include "core/error.h"
#include "support/test_support.h"

namespace hm {
namespace {

std::vector<Vec3d> cloud(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 10);
  std::vector<Vec3d> p(n);
  for (Vec3d& x : p) x = {u(rng), u(rng) * 0.2, u(rng) * 0.1};
  return p;
}

TEST(FindClosePairs, EqualsTheBruteForcePairs) {
  const std::vector<Vec3d> p = cloud(3000, 3);
  std::vector<std::uint32_t> group(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) group[i] = std::uint32_t(i % 3);
  for (bool grouped : {false, true}) {
    const double tol = 0.12;
    std::vector<ClosePair> expect;
    for (Index a = 0; a < p.size(); ++a) {
      for (Index b = a + 1; b < p.size(); ++b) {
        if (grouped && group[a] == group[b]) continue;
        const double d = norm(p[b] - p[a]);
        if (d < tol) expect.push_back({a, b, d});
      }
    }
    const std::vector<ClosePair> got = find_close_pairs(
        p, grouped ? std::span<const std::uint32_t>(group) : std::span<const std::uint32_t>(), tol);
    ASSERT_EQ(got.size(), expect.size());
    ASSERT_GT(got.size(), 100u);
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].a, expect[i].a);
      EXPECT_EQ(got[i].b, expect[i].b);
      EXPECT_EQ(got[i].distance, expect[i].distance);
    }
  }
}

TEST(FindClosePairs, SameWithOneAndEightThreads) {
  const std::vector<Vec3d> p = cloud(20000, 5);
  const std::vector<ClosePair> one =
      hm::test::with_threads(1, [&] { return find_close_pairs(p, {}, 0.05); });
  const std::vector<ClosePair> two =
      hm::test::with_threads(8, [&] { return find_close_pairs(p, {}, 0.05); });
  ASSERT_EQ(one.size(), two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].a, two[i].a);
    EXPECT_EQ(one[i].b, two[i].b);
  }
}

TEST(FindClosePairs, RejectsATolerancetooSmallForTheExtent) {
  const std::vector<Vec3d> p = {{0, 0, 0}, {1e6, 0, 0}};
  EXPECT_THROW(find_close_pairs(p, {}, 1e-6), LimitError);
}

TEST(WeldClusters, NearestFirstAndNeverTwoOfOneGroup) {
  // Points 0 and 1 belong to group 0; 2 to group 1. 2 is nearer to 1 than to 0.
  const std::vector<ClosePair> pairs = {{0, 2, 0.3}, {1, 2, 0.1}, {0, 1, 0.2}};
  const std::vector<std::uint32_t> group = {0, 0, 1};
  const std::vector<Index> rep = weld_clusters(3, pairs, group);
  EXPECT_EQ(rep[1], 1u);
  EXPECT_EQ(rep[2], 1u);  // joined its nearest partner
  EXPECT_EQ(rep[0], 0u);  // 0 would bring a second group-0 point into the cluster
  // Without groups everything joins, represented by the smallest index.
  const std::vector<Index> all = weld_clusters(3, pairs, {});
  EXPECT_EQ(all, (std::vector<Index>{0, 0, 0}));
}

// The clustering against the rule written out plainly: pairs nearest first (ties by (a, b)), each
// joining two clusters unless they share a group, the groups kept as a set per cluster. Random
// pairs over a few groups make clusters of several points and many refusals (the kernel keeps
// its clusters' members in circular lists since 2026-12-04, where it kept sorted group vectors).
TEST(WeldClusters, SameAsTheRuleWithGroupSets) {
  std::mt19937_64 rng(7);
  const std::size_t n = 3000;
  std::vector<std::uint32_t> group(n);
  for (auto& g : group) g = static_cast<std::uint32_t>(rng() % 6);
  std::vector<ClosePair> pairs;
  for (int k = 0; k < 6000; ++k) {
    const Index a = static_cast<Index>(rng() % n), b = static_cast<Index>(rng() % n);
    if (a == b) continue;
    pairs.push_back({std::min(a, b), std::max(a, b), double(rng() % 1000) * 1e-3});
  }
  std::sort(pairs.begin(), pairs.end(), [](const ClosePair& x, const ClosePair& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  pairs.erase(
      std::unique(pairs.begin(), pairs.end(),
                  [](const ClosePair& x, const ClosePair& y) { return x.a == y.a && x.b == y.b; }),
      pairs.end());

  std::vector<Index> parent(n);
  std::iota(parent.begin(), parent.end(), Index{0});
  std::vector<std::set<std::uint32_t>> groups(n);
  for (std::size_t i = 0; i < n; ++i) groups[i] = {group[i]};
  const auto find = [&](Index x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  std::vector<ClosePair> order = pairs;
  std::stable_sort(order.begin(), order.end(),
                   [](const ClosePair& x, const ClosePair& y) { return x.distance < y.distance; });
  std::size_t refused = 0;
  for (const ClosePair& p : order) {
    Index ra = find(p.a), rb = find(p.b);
    if (ra == rb) continue;
    bool shared = false;
    for (std::uint32_t g : groups[rb]) shared = shared || groups[ra].count(g) > 0;
    if (shared) {
      ++refused;
      continue;
    }
    if (rb < ra) std::swap(ra, rb);
    parent[rb] = ra;
    groups[ra].insert(groups[rb].begin(), groups[rb].end());
  }
  std::vector<Index> expected(n);
  for (std::size_t i = 0; i < n; ++i) expected[i] = find(Index(i));
  ASSERT_GT(refused, 100u);

  EXPECT_EQ(weld_clusters(n, pairs, group), expected);
}

}  // namespace
}  // namespace hm
