// The butterfly predictor: Zorin's weights and linear precision of every rule.
#include "tessellate/butterfly.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace hm {
namespace {

TEST(Butterfly, ExtraordinaryWeightsSumToAQuarter) {
  for (int k = 3; k <= 12; ++k) {
    double sum = 0;
    for (int j = 0; j < k; ++j) sum += extraordinary_weight(k, j);
    EXPECT_NEAR(sum, 0.25, 1e-15) << "valence " << k;
  }
}

// A fan of k triangles around the origin (a closed ring), plus the planar points' images under
// an affine map: every rule must reproduce the midpoint of a planar edge exactly.
TEST(Butterfly, ExtraordinaryRuleReproducesPlanarMidpoints) {
  for (int k : {3, 4, 5, 7, 8}) {
    std::vector<Vec3d> p{{0, 0, 0}};
    std::vector<Tri> tris;
    for (int j = 0; j < k; ++j) {
      const double a = 2 * std::numbers::pi * j / k;
      p.push_back({std::cos(a), std::sin(a), 0});
      tris.push_back({0, Index(1 + j), Index(1 + (j + 1) % k)});
    }
    const VertexRings rings = build_rings(tris, p.size());
    ASSERT_EQ(rings.kind[0], RingKind::kClosed);
    ASSERT_EQ(rings.size[0], Index(k));
    const std::vector<std::uint8_t> boundary(p.size(), 0);
    const Vec3d q = butterfly_midpoint(rings, p, boundary, 0, 1, false, 0.0);
    EXPECT_NEAR(q.x, 0.5, 1e-14) << k;
    EXPECT_NEAR(q.y, 0.0, 1e-14) << k;
  }
}

// Regular triangular lattice: the 10-point stencil on a planar mesh gives the exact midpoint, and
// on z = x^2 + y^2 it lies above the chord's midpoint (it predicts the curved surface).
TEST(Butterfly, RegularStencilOnALattice) {
  const int n = 9;
  const double s = std::sqrt(3.0) / 2;
  std::vector<Vec3d> flat, bowl;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = i + 0.5 * j - 4, y = s * j - 4 * s;
      flat.push_back({x, y, 0});
      bowl.push_back({x, y, 0.01 * (x * x + y * y)});
    }
  }
  std::vector<Tri> tris;
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const Index a = Index(i + n * j), b = a + 1, c = Index(a + n), d = c + 1;
      tris.push_back({a, b, c});
      tris.push_back({b, d, c});
    }
  }
  const VertexRings rings = build_rings(tris, flat.size());
  const Index a = 4 + n * 4, b = a + 1;
  ASSERT_EQ(rings.kind[a], RingKind::kClosed);
  ASSERT_EQ(rings.size[a], 6u);
  const std::vector<std::uint8_t> boundary(flat.size(), 0);
  for (double w : {0.0, -1.0 / 16, 0.02}) {
    const Vec3d q = butterfly_midpoint(rings, flat, boundary, a, b, false, w);
    const Vec3d m = 0.5 * (flat[a] + flat[b]);
    EXPECT_NEAR(norm(q - m), 0.0, 1e-13);
  }
  const Vec3d q = butterfly_midpoint(rings, bowl, boundary, a, b, false, 0.0);
  const Vec3d m = 0.5 * (bowl[a] + bowl[b]);
  const double exact = 0.01 * (m.x * m.x + m.y * m.y);
  EXPECT_LT(q.z, m.z);  // below the chord, towards the convex surface
  EXPECT_NEAR(q.z, exact, 0.5 * std::abs(m.z - exact));
  // Boundary edge on the lattice's bottom row: the 4-point rule, exact for the planar lattice.
  EXPECT_EQ(rings.kind[3], RingKind::kOpen);
  std::vector<std::uint8_t> on_boundary(flat.size(), 0);
  for (int i = 0; i < n; ++i) on_boundary[i] = 1;
  const Vec3d qb = butterfly_midpoint(rings, bowl, on_boundary, 3, 4, true, 0.0);
  const double xb = 0.5 * (bowl[3].x + bowl[4].x), yb = bowl[3].y;
  // The 4-point rule reproduces cubics along the row: exact for this quadratic.
  EXPECT_NEAR(qb.z, 0.01 * (xb * xb + yb * yb), 1e-14);
}

}  // namespace
}  // namespace hm
