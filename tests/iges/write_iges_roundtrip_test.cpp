// Generated hulls through the writer and the importer: bit-identical knots, weights and points,
// the names, and the same bytes when the read-back patches are written again.
#include <gtest/gtest.h>

#include <cstring>

#include "iges/read_iges.h"
#include "iges/write_iges.h"
#include "nurbs/generate_hull.h"

namespace hm {
namespace {

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

bool same_bits(const std::vector<Vec3d>& a, const std::vector<Vec3d>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3d)) == 0;
}

void expect_round_trip(const HullSpec& spec) {
  const GeneratedHull hull = generate_hull(spec);
  const std::string text = write_iges(hull.patches);
  const ImportResult back = read_iges(text, "generated.igs");
  const std::string what = std::string(to_string(spec.kind)) + " " + std::to_string(spec.patches);
  ASSERT_EQ(back.patches.size(), hull.patches.size()) << what;
  for (std::size_t k = 0; k < hull.patches.size(); ++k) {
    const NurbsSurface& a = hull.patches[k].surface;
    const NurbsSurface& b = back.patches[k].surface;
    EXPECT_EQ(a.degree_u, b.degree_u) << what;
    EXPECT_EQ(a.degree_v, b.degree_v) << what;
    EXPECT_EQ(a.count_u, b.count_u) << what;
    EXPECT_EQ(a.count_v, b.count_v) << what;
    EXPECT_TRUE(same_bits(a.knots_u, b.knots_u)) << what << " patch " << k;
    EXPECT_TRUE(same_bits(a.knots_v, b.knots_v)) << what << " patch " << k;
    EXPECT_TRUE(same_bits(a.weights, b.weights)) << what << " patch " << k;
    EXPECT_TRUE(same_bits(a.points, b.points)) << what << " patch " << k;
    EXPECT_EQ(a.u0, b.u0);
    EXPECT_EQ(a.u1, b.u1);
    EXPECT_EQ(a.v0, b.v0);
    EXPECT_EQ(a.v1, b.v1);
    EXPECT_EQ(back.patches[k].name, hull.patches[k].name) << what;
    EXPECT_EQ(back.patches[k].source_type, 128);
    EXPECT_TRUE(back.patches[k].loops.empty());
  }
  EXPECT_EQ(write_iges(back.patches), text) << what;
}

TEST(WriteIgesRoundTrip, EveryKindAndCountIsBitIdentical) {
  for (HullKind kind : {HullKind::kWigley, HullKind::kRoundBilge, HullKind::kChine}) {
    for (int n : {1, 7, 48, 1000}) {
      HullSpec spec;
      spec.kind = kind;
      spec.patches = n;
      spec.full_hull = n > 1;
      expect_round_trip(spec);
    }
  }
}

TEST(WriteIgesRoundTrip, DefectsSurviveTheRoundTrip) {
  HullSpec spec;
  spec.kind = HullKind::kChine;
  spec.patches = 48;
  spec.full_hull = true;
  spec.defects = {0.01, 0.05, true, 3, 1};
  expect_round_trip(spec);
}

TEST(WriteIgesRoundTrip, LyingUnitsAreDetected) {
  HullSpec spec;
  spec.kind = HullKind::kRoundBilge;
  spec.patches = 7;
  const GeneratedHull hull = generate_hull(spec);
  IgesWriteOptions o;
  o.unit_flag = 2;  // says millimetres, numbers in metres
  o.lie_about_units = true;
  const ImportResult lying = read_iges(write_iges(hull.patches, o), "lying.igs");
  EXPECT_EQ(lying.header.unit_flag, 2);
  EXPECT_TRUE(lying.units.implausible);
  o.lie_about_units = false;  // honest millimetres: metres again after import
  const ImportResult honest = read_iges(write_iges(hull.patches, o), "honest.igs");
  EXPECT_FALSE(honest.units.implausible);
  ASSERT_EQ(honest.patches.size(), hull.patches.size());
  for (std::size_t k = 0; k < hull.patches.size(); ++k) {
    const auto& a = hull.patches[k].surface.points;
    const auto& b = honest.patches[k].surface.points;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LT(norm(a[i] - b[i]), 1e-9);
  }
}

}  // namespace
}  // namespace hm
