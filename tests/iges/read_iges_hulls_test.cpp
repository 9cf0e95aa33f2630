// IGES reader on the six shared real hull files: patch counts of SOURCES.md, plausible
// bounding boxes in metres, no error diagnostics, and parse speed.
#include <gtest/gtest.h>

#include <cstdio>

#include "iges/read_iges.h"
#include "support/test_support.h"

namespace hm {
namespace {

struct HullCase {
  const char* file;
  std::size_t patches;
  double min_length, max_length;  // longest bounding-box extent, m
};

void PrintTo(const HullCase& c, std::ostream* os) { *os << c.file; }

class SharedHull : public ::testing::TestWithParam<HullCase> {};

TEST_P(SharedHull, LoadsWithTheDocumentedPatchCountAndSize) {
  const HullCase& c = GetParam();
  HM_REQUIRE_SHARED_HULL(path, c.file);
  const ImportResult r = read_iges_file(path.string());
  EXPECT_EQ(r.patches.size(), c.patches);
  EXPECT_EQ(r.diagnostics.count(Severity::kError), 0u);
  for (const Diagnostic& d : r.diagnostics.items()) {
    EXPECT_NE(d.severity, Severity::kError) << format(d);
  }
  const Vec3d e = r.bbox.extent();
  const double length = std::max({e.x, e.y, e.z});
  EXPECT_GE(length, c.min_length);
  EXPECT_LE(length, c.max_length);
  EXPECT_FALSE(r.units.implausible);
  EXPECT_TRUE(r.skipped_by_type.empty()) << "every entity of these files belongs to a face";
  for (const Patch& p : r.patches) {
    EXPECT_EQ(p.wrapping, Wrapping::kFace);
    EXPECT_GT(p.wrapper_de, 0);
    EXPECT_EQ(p.surface.points.size(), static_cast<std::size_t>(p.surface.count_u) *
                                           static_cast<std::size_t>(p.surface.count_v));
  }
}

INSTANTIATE_TEST_SUITE_P(Hulls, SharedHull,
                         ::testing::Values(HullCase{"dtmb5415.iges", 3, 5.0, 6.5},
                                           HullCase{"wigley.iges", 1, 2.49, 2.51},
                                           HullCase{"series60.iges", 1, 110, 150},
                                           HullCase{"kcs.iges", 55, 6.0, 8.5},
                                           HullCase{"npl_round_bilge.iges", 21, 2.4, 2.9},
                                           HullCase{"ship_449_patches.iges", 449, 160, 190}),
                         [](const auto& info) {
                           std::string n = info.param.file;
                           return n.substr(0, n.find('.'));
                         });

TEST(SharedHulls, KcsHasTwoSurfacesOfRevolutionAndOrientedFaces) {
  HM_REQUIRE_SHARED_HULL(path, "kcs.iges");
  const ImportResult r = read_iges_file(path.string());
  int revolution = 0, bspline = 0, reversed = 0;
  for (const Patch& p : r.patches) {
    revolution += p.source_type == 120;
    bspline += p.source_type == 128;
    reversed += p.reversed;
  }
  EXPECT_EQ(revolution, 2);
  EXPECT_EQ(bspline, 53);
  EXPECT_GT(reversed, 0) << "kcs.iges has 514 faces with orientation flag 0";
  EXPECT_EQ(r.groups.size(), 1u);
}

TEST(SharedHulls, WigleyIsUntrimmedAndMatchesItsFormula) {
  HM_REQUIRE_SHARED_HULL(path, "wigley.iges");
  const ImportResult r = read_iges_file(path.string());
  ASSERT_EQ(r.patches.size(), 1u);
  EXPECT_TRUE(r.patches[0].loops.empty()) << "the face's loop is its natural boundary";
  EXPECT_NEAR(r.bbox.lo.x, -1.25, 1e-9);
  EXPECT_NEAR(r.bbox.hi.x, 1.25, 1e-9);
}

// Parsing speed is measured by bench_iges; here, that repeated parses agree.
TEST(SharedHulls, Ship449ParsesTheSameEveryTime) {
  HM_REQUIRE_SHARED_HULL(path, "ship_449_patches.iges");
  const ImportResult first = read_iges_file(path.string());
  ASSERT_EQ(first.patches.size(), 449u);
  const ImportResult again = read_iges_file(path.string());
  ASSERT_EQ(again.patches.size(), 449u);
  for (std::size_t p = 0; p < 449; ++p) {
    ASSERT_EQ(first.patches[p].surface.points.size(), again.patches[p].surface.points.size());
    ASSERT_EQ(first.patches[p].de, again.patches[p].de);
  }
}

}  // namespace
}  // namespace hm
