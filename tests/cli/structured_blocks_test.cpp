// Issue 6's generated hulls with user blocks: the chine hull and the bulbous-bow hull meshed from
// a block file (cut stations, a waterline plane, and a box of finer panels at the bow) meet the
// panel-code rules as they do with automatic blocks, and the box's panels are the smaller ones.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "io/read_mesh.h"
#include "mesh/surface_mesh.h"
#include "support/test_json.h"
#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::quality_json;
using test::run_hullmesh;

struct Case {
  const char* name;
  const char* generate;  // `hullmesh generate` arguments
  const char* draft;
  const char* blocks;     // the block file (floating frame: the free surface is z = 0)
  double box_x0;          // the size box's aft face, m; it reaches past the bow
  double box_size, size;  // the box's panel size and the global one (m), for the area check
};

TEST(CliStructured, GeneratedChineAndBulbHullsWithUserBlocks) {
  const Case cases[] = {
      {"chine", "chine --patches 24", "5",
       R"({"planes": [{"name": "aft body", "x": 30}, {"name": "fore body", "x": 70},
                      {"name": "WL -2.5", "z": -2.5}],
           "blocks": [{"name": "bow", "min": [80, -10, -10], "max": [101, 10, 10],
                       "size": [0.35, 0.35, 0.35]}]})",
       80, 0.35, 0.5757},
      {"bulb", "round-bilge --patches 48", "6.15",
       R"({"planes": [{"name": "aft body", "x": 25}, {"name": "midship", "x": 52.5},
                      {"name": "fore body", "x": 85}, {"name": "WL -3", "z": -3}],
           "blocks": [{"name": "bulb", "min": [95, -10, -10], "max": [106, 10, 10],
                       "size": [0.4, 0.4, 0.4]}]})",
       95, 0.4, 0.6419},
  };
  for (const Case& c : cases) {
    const fs::path dir = test::scratch_dir(std::string("cli_structured_blocks_") + c.name);
    const fs::path igs = dir / "hull.igs", blocks = dir / "blocks.json", out = dir / "panels.vtu";
    ASSERT_EQ(
        run_hullmesh(std::string("-q generate ") + c.generate + " -o " + test::q(igs)).exit_code,
        0);
    std::ofstream(blocks) << c.blocks;
    const auto r =
        run_hullmesh("structured " + test::q(igs) + " -o " + test::q(out) +
                     " --panels 2000 --draft " + c.draft + " --blocks " + test::q(blocks));
    ASSERT_EQ(r.exit_code, 0) << c.name << r.out;
    EXPECT_NE(r.out.find("cut stations (block file)"), std::string::npos) << c.name << r.out;
    EXPECT_NE(r.out.find(".. plane "), std::string::npos) << c.name << r.out;  // the waterline
    // The rules issue 6 asks of DTMB 5415, and a conforming, closed, uncrossed mesh.
    const nlohmann::json q = quality_json(out);
    const double faces = q["faces"].get<double>();
    EXPECT_GE(q["quads"].get<double>() / faces, 0.9) << c.name;
    EXPECT_GE(q["rules"]["side_ratio"]["share"].get<double>(), 0.98) << c.name;
    EXPECT_GE(q["rules"]["area_ratio"]["share"].get<double>(), 0.98) << c.name;
    EXPECT_EQ(q["topology"]["nonmanifold_edges"].get<std::size_t>(), 0u) << c.name;
    EXPECT_EQ(q["topology"]["free_edges_below_waterline"].get<std::size_t>(), 0u) << c.name;
    EXPECT_EQ(q["topology"]["boundary_loops"].get<std::size_t>(), 1u) << c.name;
    EXPECT_EQ(q["crossing_pairs"].get<std::size_t>(), 0u) << c.name;
    // The box's panels are about (box size / size)^2 of the others' area: below 0.6 of it
    // inside the box, against those beyond its transition zone (more than 2 sizes aft).
    const SurfaceMesh m = read_mesh(out.string()).mesh;
    double in_area = 0, out_area = 0;
    std::size_t in_count = 0, out_count = 0;
    const double zone = (c.size - c.box_size) / 0.2 + 2 * c.size;
    for (std::size_t f = 0; f < m.face_count(); ++f) {
      const Vec3d centre = face_centroid(m.positions, m.faces[f]);
      const double area = face_area(m.positions, m.faces[f]);
      if (centre.x > c.box_x0) {
        in_area += area;
        ++in_count;
      } else if (centre.x < c.box_x0 - zone) {
        out_area += area;
        ++out_count;
      }
    }
    ASSERT_GT(in_count, 50u) << c.name;
    ASSERT_GT(out_count, 500u) << c.name;
    EXPECT_LT((in_area / double(in_count)) / (out_area / double(out_count)), 0.6) << c.name;
  }
}

}  // namespace
}  // namespace hm
