#include "structured/nearest_on_lines.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace hm::structured {
namespace {

// The scan the grid must agree with: every segment in line order, ties to the first.
Vec3d nearest_by_scan(const std::vector<std::vector<Vec3d>>& lines, const Vec3d& q) {
  Vec3d best = q;
  double best_d = std::numeric_limits<double>::infinity();
  for (const std::vector<Vec3d>& l : lines) {
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec3d& a = l[i];
      const Vec3d d = i + 1 < l.size() ? l[i + 1] - a : Vec3d{0, 0, 0};
      const double dd = squared_norm(d);
      const double f = dd > 0 ? std::clamp(dot(q - a, d) / dd, 0.0, 1.0) : 0.0;
      const Vec3d p = a + d * f;
      if (squared_norm(p - q) < best_d) {
        best_d = squared_norm(p - q);
        best = p;
      }
    }
  }
  return best;
}

TEST(NearestOnLines, SameAsScanningEverySegmentInsideAndOutsideTheSection) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  // A ship-like section (a bilge arc, a flat bottom) and a short second curve, in x = 2, with a
  // dense stretch and a lone point; queries from the next station, near and far, in and out.
  std::vector<std::vector<Vec3d>> lines(3);
  for (int k = 0; k <= 60; ++k) {
    const double t = k / 60.0 * 1.5707963;
    lines[0].push_back({2, 3 + 2 * std::sin(t), -2 * std::cos(t) + 1e-3 * u(rng)});
  }
  for (int k = 0; k <= 400; ++k) lines[1].push_back({2, -0.5 + 0.001 * k, -2.5 + 0.01 * u(rng)});
  lines[2].push_back({2, 0, 1});
  NearestOnLines grid;
  grid.build(lines);
  int checked = 0;
  for (int n = 0; n < 4000; ++n) {
    const double reach = n < 2000 ? 3 : 40;
    const Vec3d q{2 + 0.1 * u(rng), 2 + reach * u(rng), -1 + reach * u(rng)};
    const Vec3d a = grid.nearest(q), b = nearest_by_scan(lines, q);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    EXPECT_EQ(a.z, b.z);
    ++checked;
  }
  EXPECT_EQ(checked, 4000);
}

TEST(NearestOnLines, NoLinesGivesTheQueryAndOnePointGivesThatPoint) {
  NearestOnLines grid;
  grid.build({});
  EXPECT_EQ(grid.nearest({1, 2, 3}).y, 2.0);
  grid.build({{{0, 5, 5}}});
  const Vec3d p = grid.nearest({0, -100, 40});
  EXPECT_EQ(p.y, 5.0);
  EXPECT_EQ(p.z, 5.0);
}

}  // namespace
}  // namespace hm::structured
