// The box-pair kernel against a brute-force double loop: every overlapping pair once, on dense
// clouds (the counting sort) and sparse ones (the sorted keys), with boxes that touch, boxes that
// are points, long boxes across many cells and boxes that are not boxes.
#include "kernels/box_pairs.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/error.h"

namespace hm {
namespace {

struct Boxes {
  std::vector<Vec3d> lo, hi;
};

// n boxes in a slab like a hull's (10 x 2 x 1): most about 0.1 across, every 50th ten times
// longer, every 97th a point, and two that share a face exactly.
Boxes slab(std::size_t n, double spread, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Boxes b;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d c{spread * 10 * u(rng), spread * 2 * u(rng), spread * u(rng)};
    Vec3d e{0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng)};
    if (i % 50 == 0) e.x *= 10;
    if (i % 97 == 0) e = {0, 0, 0};
    b.lo.push_back(c);
    b.hi.push_back(c + e);
  }
  b.lo.push_back({1, 1, 0.5});
  b.hi.push_back({1.2, 1.1, 0.6});
  b.lo.push_back({1.2, 1.05, 0.55});  // touches the one before at x = 1.2
  b.hi.push_back({1.3, 1.2, 0.7});
  return b;
}

std::vector<std::array<Index, 2>> brute(const Boxes& b, bool (*keep)(Index, Index)) {
  std::vector<std::array<Index, 2>> out;
  for (Index a = 0; a < b.lo.size(); ++a) {
    for (Index c = a + 1; c < b.lo.size(); ++c) {
      const bool meet = b.lo[a].x <= b.hi[c].x && b.lo[c].x <= b.hi[a].x &&
                        b.lo[a].y <= b.hi[c].y && b.lo[c].y <= b.hi[a].y &&
                        b.lo[a].z <= b.hi[c].z && b.lo[c].z <= b.hi[a].z;
      if (meet && keep(a, c)) out.push_back({a, c});
    }
  }
  return out;
}

bool every(Index, Index) { return true; }
bool some(Index a, Index b) { return (a + 2 * b) % 3 != 0; }

TEST(OverlappingBoxPairs, EqualsTheBruteForcePairsAndTestsEachOnce) {
  // spread 1: a few cells, counted into an array; spread 1e5: far too many cells for one, sorted.
  for (double spread : {1.0, 30.0, 1e5}) {
    const Boxes b = slab(2000, spread, 7);
    for (auto keep : {every, some}) {
      const auto expect = brute(b, keep);
      std::atomic<std::size_t> calls{0};
      const auto got = overlapping_box_pairs(b.lo, b.hi, [&](Index x, Index y) {
        ++calls;
        EXPECT_LT(x, y);
        return keep(x, y);
      });
      EXPECT_EQ(got, expect) << "spread " << spread;
      // keep is asked once per overlapping pair: no pair is tested in two cells.
      EXPECT_EQ(calls.load(), brute(b, every).size()) << "spread " << spread;
    }
  }
  const auto touching =
      overlapping_box_pairs(slab(0, 1, 1).lo, slab(0, 1, 1).hi, [](Index, Index) { return true; });
  EXPECT_EQ(touching, (std::vector<std::array<Index, 2>>{{0, 1}}));
}

TEST(OverlappingBoxPairs, BoxesThatAreNotBoxesPairWithNothing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Vec3d> lo{{0, 0, 0}, {0.5, 0.5, 0.5}, {nan, 0, 0}, {1, 1, 1}, {0, 0, 0}};
  const std::vector<Vec3d> hi{{1, 1, 1}, {2, 2, 2}, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}};
  const auto got = overlapping_box_pairs(lo, hi, [](Index, Index) { return true; });
  // Box 2 has a NaN corner and box 3 is inside out.
  EXPECT_EQ(got, (std::vector<std::array<Index, 2>>{{0, 1}, {0, 4}, {1, 4}}));
}

TEST(OverlappingBoxPairs, TooManyEntriesIsALimitErrorBeforeTheGridIsMade) {
  // One box across the whole extent of many small ones: its cells alone exceed the budget even
  // after the cell edge is widened eight times.
  Boxes b = slab(1000, 1, 3);
  b.lo.push_back({0, 0, 0});
  b.hi.push_back({1e4, 1e4, 1e4});
  EXPECT_THROW(overlapping_box_pairs(
                   b.lo, b.hi, [](Index, Index) { return true; }, 2000),
               LimitError);
  EXPECT_TRUE(overlapping_box_pairs({}, {}, [](Index, Index) { return true; }).empty());
}

}  // namespace
}  // namespace hm
