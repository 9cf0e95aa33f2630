// `hullmesh quality`: the minimum-angle distribution and, with --iges, the deviation of a mesh
// from the NURBS of the hull it was made from.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::q;
using test::run_hullmesh;

// A Wigley half hull (L = 100 m) and its unstructured panels, half and mirrored whole.
struct WigleyPanels {
  fs::path igs, half, full;
};

const WigleyPanels& wigley_panels() {
  static const WigleyPanels w = [] {
    // One folder per process: ctest runs each test of this file as a process of its own, in
    // parallel, and each builds these files once.
    const fs::path dir = test::scratch_dir("cli_quality_iges_" + std::to_string(::getpid()));
    WigleyPanels p{dir / "wigley.igs", dir / "half.gdf", dir / "full.stl"};
    EXPECT_EQ(run_hullmesh("-q generate wigley --patches 4 -o " + q(p.igs)).exit_code, 0);
    for (const auto& [out, symmetry] : {std::pair{p.half, "auto"}, std::pair{p.full, "full"}}) {
      const auto r = run_hullmesh("-q unstructured " + q(p.igs) + " -o " + q(out) +
                                  " --panels 600 --triangles 20000 --symmetry " + symmetry);
      EXPECT_EQ(r.exit_code, 0) << r.out;
    }
    return p;
  }();
  return w;
}

nlohmann::json quality_json(const std::string& args) {
  const auto r = run_hullmesh("quality --json " + args);
  // stdout and stderr interleaved: the warnings come after the JSON.
  const auto first = r.out.find('{'), last = r.out.rfind('}');
  EXPECT_NE(first, std::string::npos) << r.out;
  if (first == std::string::npos) return nlohmann::json::value_t::discarded;
  return nlohmann::json::parse(r.out.substr(first, last - first + 1), nullptr, false);
}

TEST(CliQuality, MinAngleDistributionIsOrdered) {
  const nlohmann::json j = quality_json(q(wigley_panels().half));
  ASSERT_FALSE(j.is_discarded());
  const nlohmann::json& a = j["min_angle_deg"];
  EXPECT_GE(a["share_20"].get<double>(), a["share_30"].get<double>());
  EXPECT_GE(a["share_30"].get<double>(), a["share_40"].get<double>());
  EXPECT_LE(a["p05"].get<double>(), a["p50"].get<double>());
  EXPECT_LE(a["p50"].get<double>(), a["p95"].get<double>());
  EXPECT_LE(a["p95"].get<double>(), 60.0 + 1e-9);  // no triangle's smallest angle passes 60
  // The rule's share is the same count at its limit (30 degrees, all faces triangles).
  EXPECT_DOUBLE_EQ(a["share_30"].get<double>(),
                   j["rules"]["triangle_min_angle_deg"]["share"].get<double>());
}

// Panels of a 100 m hull lie within centimetres of its NURBS; the mean is below the max.
TEST(CliQuality, DeviationFromTheIgesIsSmallForItsOwnPanels) {
  const WigleyPanels& w = wigley_panels();
  const nlohmann::json j = quality_json(q(w.half) + " --iges " + q(w.igs));
  ASSERT_FALSE(j.is_discarded());
  const nlohmann::json& d = j["deviation"];
  EXPECT_GT(d["samples"].get<int>(), 600);
  EXPECT_GT(d["max_m"].get<double>(), 0.0);
  EXPECT_LT(d["max_rel"].get<double>(), 2e-3);
  EXPECT_LE(d["mean_m"].get<double>(), d["max_m"].get<double>());
  EXPECT_NEAR(d["length_m"].get<double>(), 100.0, 1e-6);
  EXPECT_FALSE(d["mirrored"].get<bool>());
  EXPECT_FALSE(d["far_from_hull"].get<bool>());
  // The table says the same.
  const auto t = run_hullmesh("quality " + q(w.half) + " --iges " + q(w.igs));
  EXPECT_NE(t.out.find("deviation from the NURBS of"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("panel min angle"), std::string::npos) << t.out;
}

// A whole hull mirrored from a half-hull file is measured against both sides.
TEST(CliQuality, DeviationOfAMirroredHullUsesTheMirrorImage) {
  const WigleyPanels& w = wigley_panels();
  const nlohmann::json j = quality_json(q(w.full) + " --iges " + q(w.igs));
  ASSERT_FALSE(j.is_discarded());
  EXPECT_TRUE(j["deviation"]["mirrored"].get<bool>());
  EXPECT_LT(j["deviation"]["max_rel"].get<double>(), 2e-3);
}

// Panels of a 100 m hull against a 10 m hull's file: a clear figure and a warning, not a crash.
TEST(CliQuality, MeshFarFromTheIgesHullIsNamed) {
  const WigleyPanels& w = wigley_panels();
  const fs::path other = w.igs.parent_path() / "big.igs";
  ASSERT_EQ(
      run_hullmesh("-q generate round-bilge --length 10 --patches 12 -o " + q(other)).exit_code, 0);
  const auto r = run_hullmesh("quality " + q(w.half) + " --iges " + q(other));
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 7) << r.out;  // 7: the panel rules' verdict
  EXPECT_NE(r.out.find("from the hull of"), std::string::npos) << r.out;
  const nlohmann::json j = quality_json(q(w.half) + " --iges " + q(other));
  ASSERT_FALSE(j.is_discarded());
  EXPECT_TRUE(j["deviation"]["far_from_hull"].get<bool>());
  EXPECT_GT(j["deviation"]["max_rel"].get<double>(), 0.05);
}

TEST(CliQuality, MissingIgesIsAnIoError) {
  const WigleyPanels& w = wigley_panels();
  const fs::path nope = w.igs.parent_path() / "nope.igs";
  const auto r = run_hullmesh("quality " + q(w.half) + " --iges " + q(nope));
  EXPECT_EQ(r.exit_code, 6) << r.out;
  EXPECT_NE(r.out.find("nope.igs"), std::string::npos) << r.out;
}

// Not an IGES file: a bad-input error naming it.
TEST(CliQuality, MeshFileGivenAsIgesIsBadInput) {
  const WigleyPanels& w = wigley_panels();
  const auto r = run_hullmesh("quality " + q(w.half) + " --iges " + q(w.half));
  EXPECT_EQ(r.exit_code, 3) << r.out;
  EXPECT_NE(r.out.find("half.gdf"), std::string::npos) << r.out;
}

// DTMB 5415 meshed with no draft ends at its deck edge, which falls from 0.50 m at the bow to
// 0.26 m amidships, and at its open stern (the file has no transom), down to 0.075 m. The mesher
// reads that as the hull's upper edge, and so does `hullmesh quality --uncut`; judged against a
// waterline at the top of the mesh (the default, for a wetted mesh) it was 166 free edges below.
TEST(CliQuality, AnUncutHullsDeckEdgeIsNoHole) {
  HM_REQUIRE_SHARED_HULL(hull, "dtmb5415.iges");
  const fs::path out = test::scratch_dir("cli_quality_uncut") / "panels.gdf";
  const auto r = run_hullmesh("structured " + q(hull) + " -o " + q(out) + " --panels 2000");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("0 free edges off the deck edge and the centre plane"), std::string::npos)
      << r.out;
  const nlohmann::json uncut = quality_json(q(out) + " --uncut");
  ASSERT_FALSE(uncut.is_discarded());
  EXPECT_TRUE(uncut["topology"]["uncut"].get<bool>());
  EXPECT_EQ(uncut["topology"]["free_edges_below_waterline"].get<int>(), 0);
  EXPECT_EQ(uncut["topology"]["waterline_edges"].get<int>(), 0);
  EXPECT_GT(uncut["topology"]["above_water_edges"].get<int>(), 100);
  const nlohmann::json wetted = quality_json(q(out));
  ASSERT_FALSE(wetted.is_discarded());
  EXPECT_GT(wetted["topology"]["free_edges_below_waterline"].get<int>(), 100);
}

}  // namespace
}  // namespace hm
