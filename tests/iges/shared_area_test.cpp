// The real hulls' surface areas, as `hullmesh info` reports them (patch_area: Gauss-Legendre over
// knot spans), against an independent fine integration of the same NURBS: the composite midpoint
// rule at two resolutions with Richardson extrapolation (error O(h^4) on smooth spans).
#include <gtest/gtest.h>

#include <cmath>

#include "core/parallel.h"
#include "iges/read_iges.h"
#include "support/test_support.h"

namespace hm {
namespace {

bool inside(const std::vector<std::vector<Vec2d>>& loops, Vec2d q) {
  // Even-odd rule over all loops: holes subtract, the outer loop bounds.
  bool in = false;
  for (const auto& poly : loops) {
    for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
      const Vec2d& a = poly[i];
      const Vec2d& b = poly[j];
      if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x)
        in = !in;
    }
  }
  return in;
}

// Composite midpoint rule with m x m points in every knot-span cell (span-aligned, so that
// real files' tiny spans between near-duplicate knots are sampled too), inside the loops.
double midpoint_area(const Patch& p, int m) {
  const NurbsSurface& s = p.surface;
  const auto loops = sample_loops_uv(p, 1e-7 * std::max(s.u1 - s.u0, s.v1 - s.v0));
  const std::vector<double> bu = span_breaks_u(s), bv = span_breaks_v(s);
  double sum = 0;
  for (std::size_t sj = 0; sj + 1 < bv.size(); ++sj) {
    for (std::size_t si = 0; si + 1 < bu.size(); ++si) {
      const double du = (bu[si + 1] - bu[si]) / m, dv = (bv[sj + 1] - bv[sj]) / m;
      for (int j = 0; j < m; ++j) {
        for (int i = 0; i < m; ++i) {
          const double u = bu[si] + (i + 0.5) * du, v = bv[sj] + (j + 0.5) * dv;
          if (!loops.empty() && !inside(loops, {u, v})) continue;
          const SurfaceDerivs d = evaluate_derivs(s, u, v, 1);
          sum += norm(cross(d.su, d.sv)) * du * dv;
        }
      }
    }
  }
  return sum;
}

void check_area(const char* file, double rel_tol) {
  const auto path = test::shared_hull(file);
  if (path.empty()) GTEST_SKIP() << "shared hulls not present";
  const ImportResult r = read_iges_file(path.string());
  std::vector<double> reported(r.patches.size()), fine(r.patches.size());
  parallel_for_each_item(r.patches.size(), [&](std::size_t i) {
    reported[i] = patch_area(r.patches[i]);
    // Richardson on smooth spans (error O(h^4)); trimmed patches keep the finer sum, whose
    // error is O(h) along the trim curves.
    const bool trimmed = !r.patches[i].loops.empty();
    const double coarse = midpoint_area(r.patches[i], trimmed ? 24 : 6);
    const double finer = midpoint_area(r.patches[i], trimmed ? 48 : 12);
    fine[i] = trimmed ? finer : (4 * finer - coarse) / 3;
  });
  double total_reported = 0, total_fine = 0;
  for (std::size_t i = 0; i < r.patches.size(); ++i) {
    total_reported += reported[i];
    total_fine += fine[i];
  }
  EXPECT_GT(total_fine, 0);
  EXPECT_NEAR(total_reported / total_fine, 1.0, rel_tol) << file;
}

TEST(SharedHullArea, Dtmb5415) { check_area("dtmb5415.iges", 1e-4); }
TEST(SharedHullArea, Wigley) { check_area("wigley.iges", 1e-4); }
TEST(SharedHullArea, Series60) { check_area("series60.iges", 1e-4); }
TEST(SharedHullArea, Kcs) { check_area("kcs.iges", 1e-4); }
TEST(SharedHullArea, NplRoundBilge) { check_area("npl_round_bilge.iges", 1e-4); }
TEST(SharedHullArea, Ship449) { check_area("ship_449_patches.iges", 1e-4); }

}  // namespace
}  // namespace hm
