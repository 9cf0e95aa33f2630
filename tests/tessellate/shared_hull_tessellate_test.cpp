// The shared real hull files (skipped when ../shared is absent).
#include <gtest/gtest.h>

#include "hull_checks.h"
#include "iges/read_iges.h"
#include "support/test_support.h"

namespace hm {
namespace {

class SharedHull : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedHull, MeetsToleranceAndTopology) {
  HM_REQUIRE_SHARED_HULL(path, GetParam());
  const ImportResult in = read_iges_file(path.string());
  const Tessellation t = tessellate(in.patches, {}, silent_progress());
  test::expect_good_tessellation(in.patches, t, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Files, SharedHull,
                         ::testing::Values("dtmb5415.iges", "wigley.iges", "series60.iges",
                                           "kcs.iges", "npl_round_bilge.iges",
                                           "ship_449_patches.iges"));

}  // namespace
}  // namespace hm
