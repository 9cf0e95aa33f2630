// The structured metric's size boxes: the box's size inside, the global size far away, and in
// between a ramp of kBoxGrading per metre from the box's faces, for finer and coarser boxes.
#include <gtest/gtest.h>

#include <cmath>

#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

TEST(Metric, SizeBoxesBlendIntoTheGlobalSizeOutsideThem) {
  Metric m;
  m.size = {1.0, 1.0, 1.0};
  SizeBox fine;
  fine.lo = {10, -5, -5};
  fine.hi = {20, 5, 5};
  fine.size = {0.5, 0.4, 0.5};
  m.boxes = {fine};
  EXPECT_EQ(m.size_at({15, 0, 0}).y, 0.4);
  // 1 m aft of the box's face: 0.2 m of size more, in each direction.
  const Vec3d near = m.size_at({9, 0, 0});
  EXPECT_NEAR(near.x, 0.5 + kBoxGrading, 1e-12);
  EXPECT_NEAR(near.y, 0.4 + kBoxGrading, 1e-12);
  // Beyond the zone (the widest step 0.6 m over 0.2 per metre: 3 m), the global size.
  EXPECT_EQ(m.size_at({6.9, 0, 0}).y, 1.0);
  // The ramp is capped at the global size before the zone ends for the narrower step.
  EXPECT_EQ(m.size_at({7.2, 0, 0}).x, 1.0);
  EXPECT_LT(m.size_at({7.2, 0, 0}).y, 1.0);
  // The distance is to the box, not along x: beside it and off a corner.
  EXPECT_NEAR(m.size_at({15, 6, 0}).y, 0.4 + kBoxGrading, 1e-12);
  EXPECT_NEAR(m.size_at({21, 6, 0}).y, 0.4 + kBoxGrading * std::sqrt(2.0), 1e-12);

  // A coarser box ramps down to the global size.
  SizeBox coarse = fine;
  coarse.size = {2, 2, 2};
  m.boxes = {coarse};
  EXPECT_NEAR(m.size_at({9.5, 0, 0}).z, 2 - 0.5 * kBoxGrading, 1e-12);
  EXPECT_EQ(m.size_at({0, 0, 0}).z, 1.0);
  // Lengths use the blended sizes: no jump across a face.
  m.boxes = {fine};
  const double inside = m.length({10.001, 0, 0}, {10.002, 0, 0});
  const double outside = m.length({9.998, 0, 0}, {9.999, 0, 0});
  EXPECT_NEAR(outside / inside, 1.0, 0.01);
}

}  // namespace
}  // namespace hm::structured
