// The coarsening kernels: the per-criterion qualities and the independent-set selection.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>

#include "kernels/collapse_cost.h"
#include "kernels/independent_set.h"
#include "support/test_support.h"

namespace hm::kernel {
namespace {

TEST(CollapseCost, ShapeIsOneForEquilateralAndZeroForDegenerate) {
  const Vec3d a{0, 0, 0}, b{1, 0, 0}, c{0.5, std::sqrt(3.0) / 2, 0};
  EXPECT_NEAR(triangle_shape(a, b, c), 1.0, 1e-12);
  EXPECT_EQ(triangle_shape(a, b, {2, 0, 0}), 0.0);
  EXPECT_EQ(triangle_shape(a, a, a), 0.0);
  // Smallest angle 30 degrees, isosceles with two 75s: about 0.76.
  const double t = 15 * M_PI / 180;
  EXPECT_NEAR(
      triangle_shape({0, 0, 0}, {std::cos(t), std::sin(t), 0}, {std::cos(t), -std::sin(t), 0}),
      0.7637, 1e-3);
}

TEST(CollapseCost, SizeAndAreaRatioQualities) {
  EXPECT_EQ(size_quality(0), 1.0);
  EXPECT_EQ(size_quality(1), 0.5);
  EXPECT_EQ(size_quality(3), 0.0);
  const double areas[] = {1, 2, 4};
  EXPECT_EQ(area_ratio_quality(areas), 0.25);
  EXPECT_NEAR(equilateral_edge(std::sqrt(3.0) / 4), 1.0, 1e-12);
  const CollapseQualities q{1, 0.5, 0.5, 0};
  EXPECT_EQ(weighted_index(q, {}), 0.5);
  EXPECT_EQ(weighted_index(q, {4, 0, 0, 0}), 1.0);
}

TEST(CollapseCost, PointTriangleDistanceAgainstSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3d a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    const Vec3d p{2 * u(rng), 2 * u(rng), 2 * u(rng)};
    double best = 1e30;
    const int n = 200;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const double s = double(i) / n, t = double(j) / n;
        best = std::min(best, squared_norm(p - (a + s * (b - a) + t * (c - a))));
      }
    }
    const double d2 = point_triangle_distance2(p, a, b, c);
    EXPECT_LE(d2, best + 1e-12);
    EXPECT_NEAR(std::sqrt(d2), std::sqrt(best), 2e-2);
  }
}

TEST(IndependentSet, NoTwoChosenShareAVertexAndTheBestAlwaysWins) {
  std::mt19937 rng(3);
  const std::size_t vertices = 5000, candidates = 3000;
  std::vector<Index> offsets{0}, region;
  std::vector<std::uint64_t> keys;
  std::uniform_int_distribution<Index> pick(0, vertices - 1);
  std::uniform_real_distribution<double> pr(0, 1);
  for (std::size_t i = 0; i < candidates; ++i) {
    for (int k = 0; k < 6; ++k) region.push_back(pick(rng));
    offsets.push_back(static_cast<Index>(region.size()));
    keys.push_back(priority_key(pr(rng), static_cast<Index>(i)));
  }
  std::vector<std::uint64_t> marks(vertices, 0);
  const std::vector<Index> one =
      hm::test::with_threads(1, [&] { return select_independent(keys, offsets, region, marks); });
  for (std::uint64_t m : marks) ASSERT_EQ(m, 0u);  // handed back cleared
  const std::vector<Index> two =
      hm::test::with_threads(8, [&] { return select_independent(keys, offsets, region, marks); });
  EXPECT_EQ(one, two);
  ASSERT_FALSE(one.empty());
  std::set<Index> used;
  for (Index c : one) {
    std::set<Index> mine(region.begin() + offsets[c], region.begin() + offsets[c + 1]);
    for (Index v : mine) EXPECT_TRUE(used.insert(v).second) << "vertex " << v << " shared";
  }
  const auto best = std::max_element(keys.begin(), keys.end()) - keys.begin();
  EXPECT_TRUE(std::find(one.begin(), one.end(), Index(best)) != one.end());
  // Every unchosen candidate lost somewhere to a larger key.
  for (std::size_t i = 0; i < candidates; ++i) {
    if (std::find(one.begin(), one.end(), Index(i)) != one.end()) continue;
    bool beaten = false;
    for (std::size_t j = 0; j < candidates && !beaten; ++j) {
      if (keys[j] <= keys[i]) continue;
      for (Index k = offsets[i]; k < offsets[i + 1] && !beaten; ++k) {
        for (Index l = offsets[j]; l < offsets[j + 1]; ++l) beaten |= region[k] == region[l];
      }
    }
    EXPECT_TRUE(beaten) << i;
  }
}

TEST(IndependentSet, GreedyIsMaximalBestFirstAndKeepsMoreThanLocalMaxima) {
  std::mt19937 rng(5);
  const std::size_t vertices = 4000, candidates = 3000;
  std::vector<Index> offsets{0}, region;
  std::vector<std::uint64_t> keys;
  std::uniform_int_distribution<Index> pick(0, vertices - 1);
  std::uniform_real_distribution<double> pr(0, 1);
  for (std::size_t i = 0; i < candidates; ++i) {
    // Regions of nearby vertices, with a repeat, as collapse regions have.
    const Index base = pick(rng);
    for (int k = 0; k < 12; ++k) region.push_back((base + pick(rng) % 40) % vertices);
    region.push_back(region[offsets.back()]);
    offsets.push_back(static_cast<Index>(region.size()));
    keys.push_back(priority_key(pr(rng), static_cast<Index>(i)));
  }
  std::vector<std::uint8_t> held(vertices, 0);
  const std::vector<Index> kept = select_greedy(keys, offsets, region, held);
  for (std::uint8_t h : held) ASSERT_EQ(h, 0u);  // handed back cleared
  ASSERT_FALSE(kept.empty());
  for (std::size_t i = 1; i < kept.size(); ++i) EXPECT_GT(keys[kept[i - 1]], keys[kept[i]]);
  std::vector<Index> owner(vertices, kInvalid);
  for (Index c : kept) {
    for (Index k = offsets[c]; k < offsets[c + 1]; ++k) {
      EXPECT_TRUE(owner[region[k]] == kInvalid || owner[region[k]] == c)
          << "vertex " << region[k] << " shared";
      owner[region[k]] = c;
    }
  }
  // Maximal: each candidate left out meets a kept one of larger key.
  for (std::size_t i = 0; i < candidates; ++i) {
    if (std::find(kept.begin(), kept.end(), Index(i)) != kept.end()) continue;
    bool blocked = false;
    for (Index k = offsets[i]; k < offsets[i + 1] && !blocked; ++k) {
      const Index o = owner[region[k]];
      blocked = o != kInvalid && keys[o] > keys[i];
    }
    EXPECT_TRUE(blocked) << i;
  }
  std::vector<std::uint64_t> marks(vertices, 0);
  EXPECT_GT(kept.size(), select_independent(keys, offsets, region, marks).size());
  // The same candidates handed over best first (the sort is skipped) keep the same ones.
  std::vector<Index> order(candidates);
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return keys[a] > keys[b]; });
  std::vector<std::uint64_t> ranked_keys;
  std::vector<Index> ranked_offsets{0}, ranked_region;
  for (Index c : order) {
    ranked_keys.push_back(keys[c]);
    ranked_region.insert(ranked_region.end(), region.begin() + offsets[c],
                         region.begin() + offsets[c + 1]);
    ranked_offsets.push_back(static_cast<Index>(ranked_region.size()));
  }
  std::vector<Index> ranked_kept = select_greedy(ranked_keys, ranked_offsets, ranked_region, held);
  for (Index& c : ranked_kept) c = order[c];
  EXPECT_EQ(ranked_kept, kept);
}

TEST(IndependentSet, ApartKeepsNoTwoNeighboursIsMaximalAndKeepsMoreThanGreedy) {
  // A ring of vertices, each joined to the next three on either side (symmetric), listed with
  // the centre among its neighbours as smoothing lists it (the corners of its faces).
  std::mt19937 rng(7);
  const Index vertices = 3000;
  std::vector<Index> centres, offsets{0}, region;
  std::vector<std::uint64_t> keys;
  std::uniform_real_distribution<double> pr(0, 1);
  for (Index v = 0; v < vertices; v += 1 + (v % 5 == 0)) {  // some vertices are no candidate
    centres.push_back(v);
    region.push_back(v);
    for (Index d = 1; d <= 3; ++d) {
      region.push_back((v + d) % vertices);
      region.push_back((v + vertices - d) % vertices);
    }
    offsets.push_back(static_cast<Index>(region.size()));
    keys.push_back(priority_key(pr(rng), static_cast<Index>(keys.size())));
  }
  auto near = [&](Index a, Index b) {
    const Index d = a > b ? a - b : b - a;
    return std::min(d, vertices - d) <= 3;
  };
  std::vector<std::uint8_t> held(vertices, 0);
  const std::vector<Index> kept = select_greedy_apart(keys, centres, offsets, region, held);
  for (std::uint8_t h : held) ASSERT_EQ(h, 0u);
  ASSERT_FALSE(kept.empty());
  EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
  for (std::size_t a = 0; a < kept.size(); ++a) {
    for (std::size_t b = a + 1; b < kept.size(); ++b) {
      EXPECT_FALSE(near(centres[kept[a]], centres[kept[b]]))
          << centres[kept[a]] << " and " << centres[kept[b]] << " are neighbours";
    }
  }
  // Maximal, best first: each candidate left out has a kept neighbour of larger key.
  for (std::size_t i = 0; i < centres.size(); ++i) {
    if (std::binary_search(kept.begin(), kept.end(), Index(i))) continue;
    bool blocked = false;
    for (Index c : kept) blocked = blocked || (near(centres[c], centres[i]) && keys[c] > keys[i]);
    EXPECT_TRUE(blocked) << i;
  }
  // A neighbour listed on one side only still keeps the two apart.
  const std::vector<Index> one_way_offsets{0, 1, 1};
  const std::vector<Index> one_way_region{1}, one_way_centres{0, 1};
  const std::vector<std::uint64_t> one_way_keys{priority_key(0.2, 0), priority_key(0.9, 1)};
  EXPECT_EQ(
      select_greedy_apart(one_way_keys, one_way_centres, one_way_offsets, one_way_region, held),
      std::vector<Index>{1});
  EXPECT_EQ(
      select_greedy_apart(std::vector<std::uint64_t>{priority_key(0.9, 0), priority_key(0.2, 1)},
                          one_way_centres, one_way_offsets, one_way_region, held),
      std::vector<Index>{0});
  EXPECT_GT(kept.size(), select_greedy(keys, offsets, region, held).size());
}

TEST(IndependentSet, PriorityKeyOrdersByPriorityThenSmallerIndex) {
  EXPECT_GT(priority_key(0.6, 9), priority_key(0.5, 1));
  EXPECT_GT(priority_key(0.5, 1), priority_key(0.5, 2));
  EXPECT_EQ(priority_key(-1, 3), priority_key(0, 3));
  EXPECT_EQ(key_index(priority_key(0.3, 77)), 77u);
  EXPECT_EQ(key_index(priority_key(0, 0xfffffffeu)), 0xfffffffeu);
  EXPECT_EQ(priority_key(NAN, 3), priority_key(0, 3));
}

}  // namespace
}  // namespace hm::kernel
