// The structured mesher on heeled hulls: each side meshed in the ship's own frame and the two
// joined on the centre plane. Before, rows ran round the keel from one waterline to the other,
// and at 5-15 degrees they crossed each other by the thousand and left free edges and panels of
// no area. Generated chine, round-bilge and Wigley hulls, heeled either way, with a user block
// file, and the output the same with 1 and 2 threads.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::run_hullmesh;

nlohmann::json run_record(fs::path mesh) {
  std::ifstream in(mesh.replace_extension(".run.json"));
  return nlohmann::json::parse(in, nullptr, false);
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Case {
  const char* generate;  // `hullmesh generate` arguments
  const char* position;  // draft and heel (and trim)
};

TEST(CliStructured, HeeledHullsMeshSideBySide) {
  const fs::path dir = test::scratch_dir("cli_structured_heel");
  const Case cases[] = {
      {"chine --full --patches 6", "--draft 4 --heel 10"},
      {"chine --full --patches 6", "--draft 4 --heel -25"},
      {"round-bilge --full --patches 2", "--draft 4.5 --heel 15 --trim 0.5"},
      {"wigley --patches 3", "--draft 5 --heel 20"},  // a half hull, mirrored first
  };
  int k = 0;
  for (const Case& c : cases) {
    const std::string igs = (dir / ("h" + std::to_string(k) + ".igs")).string();
    ASSERT_EQ(
        run_hullmesh("-q generate " + std::string(c.generate) + " -o '" + igs + "'").exit_code, 0);
    const fs::path out = dir / ("h" + std::to_string(k++) + ".gdf");
    const auto r = run_hullmesh("--validate structured '" + igs + "' -o '" + out.string() +
                                "' --panels 1200 " + c.position);
    ASSERT_EQ(r.exit_code, 0) << c.generate << " " << c.position << "\n" << r.out;
    EXPECT_NE(r.out.find("heeled: each side meshed in the ship's frame"), std::string::npos)
        << r.out;
    const nlohmann::json rec = run_record(out);
    const nlohmann::json& q = rec["quality"];
    SCOPED_TRACE(std::string(c.generate) + " " + c.position);
    EXPECT_EQ(q["free_edges_below_waterline"], 0);
    EXPECT_EQ(q["crossing_pairs"], 0);
    EXPECT_EQ(q["nonmanifold_edges"], 0);
    EXPECT_TRUE(q["orientation_consistent"].get<bool>());
    EXPECT_FALSE(q["half_hull"].get<bool>());
    // Upright, these hulls keep 98-100% of quads within the side ratio and of neighbours within
    // the area ratio; heeled, the seam adds a few triangles and nothing worse.
    EXPECT_GE(q["side_ratio_share"].get<double>(), 0.97);
    EXPECT_GE(q["area_ratio_pair_share"].get<double>(), 0.98);
    EXPECT_GT(q["quads"].get<double>(), 0.9 * q["panels"].get<double>());
    EXPECT_LT(std::abs(rec["results"]["hydrostatics"]["volume_error"].get<double>()), 0.01);
  }
}

// kcs.iges heeled 15 degrees: the border gap from the first row's end along the waterline to the
// stem was fanned from the row's end, and the fan's last triangle lay on the waterline, a panel
// of 1.2e-5 m^2 beside one of 0.0026 (largest area ratio 222; 178 and 162 heeled -8 and 5
// degrees). The gap is now closed by its best triangulation where the fan has a sliver.
TEST(CliStructured, AHeeledStemsBorderGapHasNoSliverOnTheWaterline) {
  HM_REQUIRE_SHARED_HULL(kcs, "kcs.iges");
  const fs::path out = test::scratch_dir("cli_structured_heel_gap") / "k.gdf";
  const auto r = run_hullmesh("--validate structured '" + kcs.string() + "' -o '" + out.string() +
                              "' --panels 3000 --draft 0.4464 --heel 15");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const nlohmann::json q = run_record(out)["quality"];
  EXPECT_LT(q["max_area_ratio"].get<double>(), 20);
  EXPECT_EQ(q["crossing_pairs"], 0);
}

TEST(CliStructured, HeeledHullIsTheSameWithOneAndTwoThreadsAndTakesABlockFile) {
  const fs::path dir = test::scratch_dir("cli_structured_heel_threads");
  const std::string igs = (dir / "c.igs").string();
  ASSERT_EQ(run_hullmesh("-q generate chine --full --patches 6 -o '" + igs + "'").exit_code, 0);
  // Block planes in the floating frame, as upright: a cut station and a waterline plane.
  const fs::path blocks = dir / "b.json";
  std::ofstream(blocks) << R"({"planes": [{"name": "mid", "x": 50}, {"name": "WL", "z": -2}]})";
  std::string bytes[2];
  for (int t = 1; t <= 2; ++t) {
    const fs::path out = dir / ("c" + std::to_string(t) + ".obj");
    const auto r = run_hullmesh("--threads " + std::to_string(t) + " --validate structured '" +
                                igs + "' -o '" + out.string() + "' --panels 800 --draft 4 " +
                                "--heel 12 --blocks '" + blocks.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("(block file)"), std::string::npos) << r.out;
    const nlohmann::json q = run_record(out)["quality"];
    EXPECT_EQ(q["free_edges_below_waterline"], 0);
    EXPECT_EQ(q["crossing_pairs"], 0);
    bytes[t - 1] = read_bytes(out);
  }
  EXPECT_FALSE(bytes[0].empty());
  EXPECT_EQ(bytes[0], bytes[1]);
}

}  // namespace
}  // namespace hm
