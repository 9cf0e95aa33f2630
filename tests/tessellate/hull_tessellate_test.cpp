// Whole generated hulls of every kind and patch count.
#include <gtest/gtest.h>

#include <string>

#include "hull_checks.h"
#include "nurbs/generate_hull.h"
#include "tessellate/tessellate.h"

namespace hm {
namespace {

class GeneratedHullTest : public ::testing::TestWithParam<std::tuple<HullKind, int>> {};

TEST_P(GeneratedHullTest, MeetsToleranceAndTopology) {
  HullSpec spec;
  spec.kind = std::get<0>(GetParam());
  spec.patches = std::get<1>(GetParam());
  const GeneratedHull hull = generate_hull(spec);
  const Tessellation t = tessellate(hull.patches, {}, silent_progress());
  test::expect_good_tessellation(hull.patches, t, to_string(spec.kind));
  // The flat triangles underestimate the area by at most the chord error over the surface.
  double area = 0;
  for (std::size_t f = 0; f < t.mesh.face_count(); ++f) area += test::triangle_area(t.mesh, f);
  EXPECT_NEAR(area, hull.facts.surface_area, 1e-3 * hull.facts.surface_area);
}

INSTANTIATE_TEST_SUITE_P(Kinds, GeneratedHullTest,
                         ::testing::Combine(::testing::Values(HullKind::kWigley, HullKind::kChine,
                                                              HullKind::kRoundBilge),
                                            ::testing::Values(1, 10, 100)));

}  // namespace
}  // namespace hm
