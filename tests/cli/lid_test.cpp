// --lid and --lid-in-mesh on both meshers: the interior free surface, closing the wetted hull at
// its waterline, written where each panel code reads it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/test_json.h"
#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::run_hullmesh;

nlohmann::json quality_json(const fs::path& mesh) {
  const auto r = run_hullmesh("quality --json '" + mesh.string() + "'");
  return nlohmann::json::parse(r.out, nullptr, false);
}

TEST(CliLid, BothMeshersCloseTheWettedHalfHull) {
  const fs::path dir = test::scratch_dir("cli_lid");
  const fs::path igs = dir / "w.igs";
  ASSERT_EQ(run_hullmesh("-q generate wigley --length 100 --beam 10 --depth 8 --draft 6.25 "
                         "--patches 2 -o '" +
                         igs.string() + "'")
                .exit_code,
            0);
  for (const std::string mesher : {"structured", "unstructured"}) {
    const fs::path sub = dir / mesher;
    fs::create_directories(sub);
    // HAMS: the hull in HullMesh.pnl, the lid in WaterplaneMesh.pnl beside it.
    const fs::path pnl = sub / "HullMesh.pnl";
    const auto r = run_hullmesh(mesher + " '" + igs.string() + "' -o '" + pnl.string() +
                                "' --panels 400 --draft 5 --lid");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("lid: "), std::string::npos) << r.out;
    const fs::path lid = sub / "WaterplaneMesh.pnl";
    ASSERT_TRUE(fs::exists(lid)) << mesher;
    std::stringstream text;
    text << std::ifstream(lid).rdbuf();
    EXPECT_NE(text.str().find("Waterplane Mesh File"), std::string::npos);
    const nlohmann::json record = test::read_json(sub / "HullMesh.run.json");
    ASSERT_EQ(record["outputs"].size(), 2u) << mesher;
    EXPECT_EQ(fs::path(record["outputs"][1]["path"].get<std::string>()).filename(),
              "WaterplaneMesh.pnl");
    // The lid covers the waterplane inside the mesh's waterline: its area is half the mesh's
    // waterplane area (a half hull's hydrostatics count both sides).
    const double lid_area = record["results"]["lid"]["area_m2"].get<double>();
    const double awp = record["results"]["hydrostatics"]["waterplane_area_m2"].get<double>();
    EXPECT_NEAR(2 * lid_area / awp, 1.0, 1e-9) << mesher;
    // Read back: triangles on z = 0, normals up, the half hull's symmetry flag kept.
    const nlohmann::json q = quality_json(lid);
    EXPECT_TRUE(q["half_hull"].get<bool>()) << mesher;
    EXPECT_EQ(q["faces"], record["results"]["lid"]["panels"]) << mesher;
    EXPECT_EQ(q["zero_area"], 0) << mesher;
    EXPECT_TRUE(q["topology"]["orientation_consistent"].get<bool>()) << mesher;

    // WAMIT IRR = 1: the lid's panels after the hull's in the one GDF. Hull and lid then leave
    // no free edge on the waterline, only the open centre plane.
    const fs::path gdf = sub / "body.gdf";
    const auto g = run_hullmesh("-q " + mesher + " '" + igs.string() + "' -o '" + gdf.string() +
                                "' --panels 400 --draft 5 --lid-in-mesh");
    ASSERT_EQ(g.exit_code, 0) << g.out;
    EXPECT_FALSE(fs::exists(sub / "body_lid.gdf"));
    const nlohmann::json qg = quality_json(gdf);
    const nlohmann::json rec = test::read_json(sub / "body.run.json");
    const int hull_panels = rec["quality"]["panels"].get<int>();
    EXPECT_EQ(qg["faces"].get<int>(), hull_panels + rec["results"]["lid"]["panels"].get<int>());
    EXPECT_EQ(qg["topology"]["waterline_edges"], 0) << mesher;
    EXPECT_EQ(qg["topology"]["boundary_edges"], qg["topology"]["centre_plane_edges"]) << mesher;
    EXPECT_EQ(qg["topology"]["nonmanifold_edges"], 0) << mesher;
  }
}

TEST(CliLid, ALidNeedsAWaterplane) {
  const fs::path dir = test::scratch_dir("cli_lid_errors");
  const fs::path igs = dir / "w.igs";
  ASSERT_EQ(run_hullmesh("-q generate wigley --patches 1 -o '" + igs.string() + "'").exit_code, 0);
  const fs::path out = dir / "x.gdf";
  for (const char* mesher : {"structured", "unstructured"}) {
    const auto r = run_hullmesh(std::string(mesher) + " '" + igs.string() + "' -o '" +
                                out.string() + "' --panels 200 --lid");
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_NE(r.out.find("--lid needs a waterplane"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(dir / "x_lid.gdf"));
  }
}

}  // namespace
}  // namespace hm
