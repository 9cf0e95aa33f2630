// --above-waterline on both meshers: the hull meshed from the keel up to a height above the
// waterplane, with the waterline kept as a line of panel edges (no panel crosses it), the
// hydrostatics still those of the wetted part, and a lid that still finds its waterline.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_json.h"
#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::run_hullmesh;

struct Obj {
  std::vector<std::array<double, 3>> v;
  std::vector<std::vector<int>> f;  // 0-based
};

Obj read_obj(const fs::path& p) {
  Obj o;
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v") {
      std::array<double, 3> x{};
      s >> x[0] >> x[1] >> x[2];
      o.v.push_back(x);
    } else if (tag == "f") {
      std::vector<int> face;
      std::string corner;
      while (s >> corner) face.push_back(std::stoi(corner.substr(0, corner.find('/'))) - 1);
      o.f.push_back(face);
    }
  }
  return o;
}

TEST(CliAboveWaterline, BothMeshersKeepTheWaterlineAsAPanelLine) {
  const fs::path dir = test::scratch_dir("cli_above_waterline");
  const fs::path igs = dir / "w.igs";
  ASSERT_EQ(run_hullmesh("-q generate wigley --length 100 --beam 10 --depth 8 --draft 6.25 "
                         "--patches 2 -o '" +
                         igs.string() + "'")
                .exit_code,
            0);
  for (const std::string mesher : {"structured", "unstructured"}) {
    const fs::path wet = dir / (mesher + "_wet.obj");
    const fs::path dry = dir / (mesher + "_dry.obj");
    ASSERT_EQ(run_hullmesh("-q " + mesher + " '" + igs.string() + "' -o '" + wet.string() +
                           "' --panels 600 --draft 5")
                  .exit_code,
              0);
    const auto r = run_hullmesh(mesher + " '" + igs.string() + "' -o '" + dry.string() +
                                "' --panels 600 --draft 5 --above-waterline 1.5");
    ASSERT_EQ(r.exit_code, 0) << r.out;
    EXPECT_NE(r.out.find("above the waterline up to z = 1.5 m"), std::string::npos) << r.out;
    const Obj o = read_obj(dry);
    ASSERT_GT(o.f.size(), 300u) << mesher;
    double zmin = 0, zmax = 0;
    std::size_t on_waterline = 0, above = 0, across = 0;
    for (const auto& p : o.v) {
      zmin = std::min(zmin, p[2]);
      zmax = std::max(zmax, p[2]);
      on_waterline += p[2] == 0;
    }
    for (const auto& f : o.f) {
      bool up = false, down = false;
      for (int c : f) {
        up |= o.v[c][2] > 0;
        down |= o.v[c][2] < 0;
      }
      across += up && down;
      above += up && !down;
    }
    // From the keel (draft 5 m) to 1.5 m above the waterplane; panels on both sides of it, none
    // across it, and the waterline's vertices exactly on z = 0.
    EXPECT_NEAR(zmin, -5, 1e-6) << mesher;
    EXPECT_NEAR(zmax, 1.5, 1e-9) << mesher;
    EXPECT_EQ(across, 0u) << mesher;
    EXPECT_GT(above, 30u) << mesher;
    EXPECT_GT(on_waterline, 20u) << mesher;
    // The hydrostatics are the wetted part's: the same as the wetted-only mesh's to the panels'
    // accuracy, and close to the NURBS.
    const nlohmann::json hw =
        test::read_json(dir / (mesher + "_wet.run.json"))["results"]["hydrostatics"];
    const nlohmann::json hd =
        test::read_json(dir / (mesher + "_dry.run.json"))["results"]["hydrostatics"];
    const double v_wet = hw["volume_m3"].get<double>(), v_dry = hd["volume_m3"].get<double>();
    EXPECT_NEAR(v_dry / v_wet, 1, 0.01) << mesher;
    EXPECT_NEAR(hd["waterplane_area_m2"].get<double>() / hw["waterplane_area_m2"].get<double>(), 1,
                0.005)
        << mesher;
    // The quality report finds no panel across z = 0, and can find them: every panel that
    // reaches above z = 0.5 from below it crosses that plane.
    auto topology_at = [&](double z) {
      const auto q = run_hullmesh("quality --json --waterline-z " + std::to_string(z) + " '" +
                                  dry.string() + "'");
      return nlohmann::json::parse(q.out, nullptr, false)["topology"];
    };
    const nlohmann::json t0 = topology_at(0);
    EXPECT_EQ(t0["panels_across_waterline"].get<int>(), 0) << mesher;
    // The dry panels along the waterline: as many as the wet ones below them, roughly.
    EXPECT_GT(t0["panels_above_on_waterline"].get<int>(), 20) << mesher;
    EXPECT_GT(topology_at(0.5)["panels_across_waterline"].get<int>(), 10) << mesher;

    // The lid still finds the waterline, now inside the surface: its area is the waterplane's.
    const fs::path gdf = dir / (mesher + "_lid.gdf");
    const auto l = run_hullmesh("-q " + mesher + " '" + igs.string() + "' -o '" + gdf.string() +
                                "' --panels 600 --draft 5 --above-waterline 1.5 --lid");
    ASSERT_EQ(l.exit_code, 0) << l.out;
    const nlohmann::json rec = test::read_json(dir / (mesher + "_lid.run.json"));
    const double lid_area = rec["results"]["lid"]["area_m2"].get<double>();
    const double awp = rec["results"]["hydrostatics"]["waterplane_area_m2"].get<double>();
    EXPECT_NEAR(2 * lid_area / awp, 1.0, 1e-9) << mesher;
  }
}

TEST(CliAboveWaterline, NeedsAWaterplaneAndAHeightAtLeastZero) {
  const fs::path dir = test::scratch_dir("cli_above_waterline_errors");
  const fs::path igs = dir / "w.igs";
  ASSERT_EQ(run_hullmesh("-q generate wigley --patches 1 -o '" + igs.string() + "'").exit_code, 0);
  const fs::path out = dir / "x.gdf";
  for (const std::string mesher : {"structured", "unstructured"}) {
    const auto a = run_hullmesh(mesher + " '" + igs.string() + "' -o '" + out.string() +
                                "' --panels 200 --above-waterline 1");
    EXPECT_EQ(a.exit_code, 2) << a.out;
    EXPECT_NE(a.out.find("--above-waterline needs a waterplane"), std::string::npos) << a.out;
    const auto b = run_hullmesh(mesher + " '" + igs.string() + "' -o '" + out.string() +
                                "' --panels 200 --draft 5 --above-waterline -1");
    EXPECT_EQ(b.exit_code, 2) << b.out;
    EXPECT_NE(b.out.find("--above-waterline"), std::string::npos) << b.out;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace hm
