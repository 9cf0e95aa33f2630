// End-to-end tests of the hullmesh executable: what a user types, what comes back.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::run_hullmesh;

nlohmann::json info_json(const fs::path& file, const std::string& extra = "") {
  const auto r = run_hullmesh("info --json " + extra + " '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.out;
  return nlohmann::json::parse(r.out, nullptr, false);
}

TEST(CliGenerate, WigleyRoundTripsThroughInfo) {
  const fs::path dir = test::scratch_dir("cli_wigley");
  const fs::path igs = dir / "wigley.igs";
  const auto g = run_hullmesh(
      "generate wigley --length 100 --beam 10 --draft 6.25 --depth 6.25 -o '" + igs.string() + "'");
  ASSERT_EQ(g.exit_code, 0) << g.out;
  const auto j = info_json(igs);
  ASSERT_FALSE(j.is_discarded());
  EXPECT_EQ(j["patch_count"], 1);
  EXPECT_NEAR(j["bbox_m"]["max"][0].get<double>() - j["bbox_m"]["min"][0].get<double>(), 100.0,
              1e-9);
  EXPECT_NEAR(j["bbox_m"]["max"][1].get<double>(), 5.0, 1e-9);
  EXPECT_EQ(j["hull_side"], "half hull, port side (y >= 0)");
}

TEST(CliGenerate, PatchCountIsExactForEveryKind) {
  const fs::path dir = test::scratch_dir("cli_counts");
  for (const char* kind : {"wigley", "round-bilge", "chine"}) {
    for (int n : {7, 48}) {
      const fs::path igs = dir / (std::string(kind) + std::to_string(n) + ".igs");
      const auto g = run_hullmesh(std::string("-q generate ") + kind + " --patches " +
                                  std::to_string(n) + " -o '" + igs.string() + "'");
      ASSERT_EQ(g.exit_code, 0) << kind << n << g.out;
      EXPECT_EQ(info_json(igs)["patch_count"], n) << kind;
    }
  }
}

TEST(CliGenerate, LyingUnitsAreDetectedAndCanBeForced) {
  const fs::path dir = test::scratch_dir("cli_units");
  const fs::path igs = dir / "lying.igs";
  ASSERT_EQ(
      run_hullmesh("-q generate round-bilge --length 120 --lie-units mm -o '" + igs.string() + "'")
          .exit_code,
      0);
  const auto j = info_json(igs);
  EXPECT_TRUE(j["units"]["implausible"].get<bool>());
  EXPECT_EQ(j["units"]["suggestion"], "m");
  const auto forced = info_json(igs, "--units m");
  EXPECT_TRUE(forced["units"]["forced"].get<bool>());
  EXPECT_NEAR(forced["bbox_m"]["max"][0].get<double>() - forced["bbox_m"]["min"][0].get<double>(),
              120.0, 1e-6);
}

TEST(CliErrors, OutOfRangePatchCountIsUsageError) {
  const auto r = run_hullmesh("generate wigley --patches 0 -o /tmp/x.igs");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  const auto r2 = run_hullmesh("generate boat -o /tmp/x.igs");
  EXPECT_EQ(r2.exit_code, 2) << r2.out;
  EXPECT_NE(r2.out.find("unknown hull kind 'boat'"), std::string::npos) << r2.out;
}

TEST(CliErrors, MissingFileIsIoErrorNamingTheFile) {
  const auto r = run_hullmesh("info /nonexistent/hull.igs");
  EXPECT_EQ(r.exit_code, 6) << r.out;
  EXPECT_NE(r.out.find("/nonexistent/hull.igs"), std::string::npos) << r.out;
}

TEST(CliErrors, NonIgesTextIsBadInput) {
  const fs::path dir = test::scratch_dir("cli_bad");
  const fs::path bad = dir / "notes.igs";
  std::ofstream(bad) << "This is a shopping list, not an IGES file.\nmilk\neggs\n";
  const auto r = run_hullmesh("info '" + bad.string() + "'");
  EXPECT_EQ(r.exit_code, 3) << r.out;
  EXPECT_NE(r.out.find("notes.igs"), std::string::npos) << r.out;
  const fs::path empty = dir / "empty.igs";
  std::ofstream(empty).flush();
  const auto e = run_hullmesh("info '" + empty.string() + "'");
  EXPECT_EQ(e.exit_code, 3) << e.out;
}

TEST(CliErrors, UnwritableOutputIsIoErrorAndLeavesNothing) {
  const auto r = run_hullmesh("generate wigley -o /nonexistent-folder/w.igs");
  EXPECT_EQ(r.exit_code, 6) << r.out;
}

struct SharedHull {
  const char* file;
  int patches;
  double length_min, length_max;  // plausible x extent in metres
};

TEST(CliInfo, SharedHullsLoadWithTheirPatchCounts) {
  const SharedHull hulls[] = {
      {"dtmb5415.iges", 3, 5.0, 6.5},         {"wigley.iges", 1, 2.4, 2.6},
      {"series60.iges", 1, 100, 140},         {"kcs.iges", 55, 7.0, 8.0},
      {"npl_round_bilge.iges", 21, 2.0, 3.2}, {"ship_449_patches.iges", 449, 150, 200}};
  for (const SharedHull& h : hulls) {
    const fs::path p = test::shared_hull(h.file);
    if (p.empty()) GTEST_SKIP() << "shared hulls not present";
    const auto j = info_json(p);
    ASSERT_FALSE(j.is_discarded()) << h.file;
    EXPECT_EQ(j["patch_count"], h.patches) << h.file;
    const double lx = j["bbox_m"]["max"][0].get<double>() - j["bbox_m"]["min"][0].get<double>();
    EXPECT_GT(lx, h.length_min) << h.file;
    EXPECT_LT(lx, h.length_max) << h.file;
    EXPECT_GT(j["surface_area_m2"].get<double>(), 0.0) << h.file;
    for (const auto& d : j["diagnostics"]) EXPECT_NE(d["severity"], "error") << h.file << d.dump();
  }
}

TEST(CliInfo, TableNamesWhatAnEngineerNeeds) {
  const fs::path p = test::shared_hull("kcs.iges");
  if (p.empty()) GTEST_SKIP() << "shared hulls not present";
  const auto r = run_hullmesh("info '" + p.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  for (const char* key : {"sent by", "units", "patches", "surface types", "bounding box",
                          "surface area", "skipped", "diagnostics", "surface of revolution"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
}

}  // namespace
}  // namespace hm
