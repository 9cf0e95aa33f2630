// EdgeTable::build's counting sort against the comparison sort it replaced.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "tessellate/patch_mesh.h"

namespace hm {
namespace {

// Random triangles over few vertices: shared edges, edges with three or more triangles, both
// directions, and vertices that no triangle uses.
std::vector<Tri> random_triangles(std::uint32_t seed, int count, Index vertices) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<Index> v(0, vertices - 1);
  std::vector<Tri> tris;
  while (static_cast<int>(tris.size()) < count) {
    const Tri t{v(rng), v(rng), v(rng)};
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) tris.push_back(t);
  }
  return tris;
}

TEST(EdgeTable, HalfEdgesAreSortedByKeyThenCorner) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    const std::vector<Tri> tris = random_triangles(seed, 3000, 400 + 300 * seed);
    EdgeTable table;
    table.build(tris);
    std::vector<HalfEdge> want;
    for (std::size_t t = 0; t < tris.size(); ++t) {
      for (int i = 0; i < 3; ++i) {
        want.push_back({edge_key(tris[t][i], tris[t][(i + 1) % 3]), Index(3 * t + i)});
      }
    }
    std::sort(want.begin(), want.end());
    ASSERT_EQ(table.he.size(), want.size());
    int mismatches = 0;
    for (std::size_t k = 0; k < want.size(); ++k) {
      mismatches += table.he[k].key != want[k].key || table.he[k].corner != want[k].corner;
    }
    EXPECT_EQ(mismatches, 0) << "seed " << seed;
    // Unique edges: each run of one key, and every corner maps into its run.
    for (std::size_t e = 0; e < table.count(); ++e) {
      for (Index k = table.first[e]; k < table.first[e + 1]; ++k) {
        EXPECT_EQ(table.he[k].key, table.he[table.first[e]].key);
        EXPECT_EQ(table.edge_of_corner[table.he[k].corner], Index(e));
      }
      if (e > 0) {
        EXPECT_LT(table.he[table.first[e - 1]].key, table.he[table.first[e]].key);
      }
    }
    EXPECT_EQ(table.find(want.front().key), 0u);
  }
}

}  // namespace
}  // namespace hm
