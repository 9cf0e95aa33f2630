// --add-knuckle / --suppress-knuckle: the spec parser in process, and the hints end to end
// through merge and unstructured on generated hulls.
#include "cli/knuckle_hints.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/read_mesh.h"
#include "support/test_support.h"

namespace hm::cli {
namespace {

namespace fs = std::filesystem;

// The message of the UsageError `spec` raises as --add-knuckle, or "" if none.
std::string parse_fault(const std::string& spec) {
  try {
    parse_knuckle_hints({{spec}, {}});
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(KnuckleHints, ParsesEveryForm) {
  const KnuckleHintSpecs s = parse_knuckle_hints(
      {{"plane:1,2,3,0,0,2@0.5", "points:0,0,0;1,0,0;1,1,0"}, {"patches:4,7", "de:15,3"}});
  ASSERT_EQ(s.add.size(), 2u);
  ASSERT_EQ(s.suppress.size(), 2u);
  const KnuckleHint& plane = s.add[0].hint;
  EXPECT_EQ(plane.kind, KnuckleHint::Kind::kPlane);
  EXPECT_EQ(plane.plane_point.z, 3.0);
  EXPECT_EQ(plane.plane_normal.z, 2.0);
  EXPECT_EQ(plane.distance, 0.5);
  const KnuckleHint& line = s.add[1].hint;
  EXPECT_EQ(line.kind, KnuckleHint::Kind::kPoints);
  ASSERT_EQ(line.points.size(), 3u);
  EXPECT_EQ(line.points[2].y, 1.0);
  EXPECT_EQ(line.distance, 0.0);  // the library's 1e-3 L
  EXPECT_EQ(s.suppress[0].hint.patch_a, 4u);
  EXPECT_EQ(s.suppress[0].hint.patch_b, 7u);
  EXPECT_EQ(s.suppress[1].de_a, 15);
  EXPECT_EQ(s.suppress[1].de_b, 3);
}

TEST(KnuckleHints, RefusesBadSpecsNamingWhatIsWrong) {
  const std::pair<const char*, const char*> bad[] = {
      {"plane:1,2,3", "expected 6 comma-separated numbers"},
      {"plane:0,0,0,0,0,0", "normal is zero"},
      {"plane:0,0,0,0,0,1@-1", "must be > 0"},
      {"plane:0,0,0,0,0,1@x", "is not a number"},
      {"points:0,0,0", "2 to"},
      {"points:0,0,0;1,nan,0", "finite"},
      {"patches:3", "two numbers"},
      {"patches:3,3", "must differ"},
      {"patches:-1,2", "not a patch index"},
      {"de:0,5", "start at 1"},
      {"cone:1,2", "unknown kind 'cone'"},
      {"0,0,0", "expected plane:"},
  };
  for (const auto& [spec, why] : bad) {
    const std::string m = parse_fault(spec);
    EXPECT_NE(m.find(why), std::string::npos) << spec << ": " << m;
    EXPECT_NE(m.find("--add-knuckle"), std::string::npos) << m;
  }
}

TEST(KnuckleHints, ResolvesDeNumbersToEveryPatchAndPlacesPointsAfloat) {
  std::vector<Patch> patches(4);
  patches[0].de = 3;
  patches[1].de = 7;
  patches[2].de = 3;  // a mirrored image keeps its original's DE
  patches[3].de = 7;
  KnuckleHintSpecs s = parse_knuckle_hints({{"de:3,7", "plane:0,0,5,0,0,1"}, {"patches:0,3"}});
  FloatingTransform up;
  up.translation = {0, 0, -5};
  FeatureOptions f;
  apply_knuckle_hints(s, patches, &up, "hull.igs", f);
  ASSERT_EQ(f.add.size(), 5u);  // four patch pairs and the plane
  std::set<std::pair<PatchId, PatchId>> pairs;
  for (std::size_t i = 0; i < 4; ++i) pairs.insert({f.add[i].patch_a, f.add[i].patch_b});
  EXPECT_EQ(pairs, (std::set<std::pair<PatchId, PatchId>>{{0, 1}, {0, 3}, {2, 1}, {2, 3}}));
  EXPECT_EQ(f.add[4].plane_point.z, 0.0);  // moved with the hull
  ASSERT_EQ(f.suppress.size(), 1u);

  FeatureOptions g;
  try {
    apply_knuckle_hints(parse_knuckle_hints({{"de:3,9"}, {}}), patches, nullptr, "hull.igs", g);
    FAIL() << "a DE number no patch has was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("hull.igs: knuckle hint de:3,9: no surface patch has "
                                         "DE 9"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(
      apply_knuckle_hints(parse_knuckle_hints({{}, {"patches:1,4"}}), patches, nullptr, "h", g),
      UsageError);
}

// "knuckle lines: N, X m" from a merge report.
std::pair<int, double> knuckle_lines(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("knuckle lines: ([0-9]+), ([0-9.]+) m")))
    return {-1, 0};
  return {std::stoi(m[1]), std::stod(m[2])};
}

TEST(CliKnuckleHints, MergeAddsAndSuppressesKnuckles) {
  const fs::path dir = test::scratch_dir("cli_knuckle_hints_merge");
  const fs::path chine = dir / "chine.igs", wigley = dir / "wigley.igs", out = dir / "m.vtu";
  ASSERT_EQ(test::run_hullmesh("-q generate chine --patches 24 -o " + test::q(chine)).exit_code, 0);
  ASSERT_EQ(test::run_hullmesh("-q generate wigley --patches 4 -o " + test::q(wigley)).exit_code,
            0);
  const std::string merge_chine = "merge " + test::q(chine) + " -o " + test::q(out);
  // The chine hull's transom (x = 0) meets the bottom and the side in two knuckles; the chine
  // runs on to the stem.
  auto r = test::run_hullmesh(merge_chine);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(knuckle_lines(r.out).first, 3) << r.out;
  // The transom plane takes both transom knuckles; the DE pair transom_1 (95) / bottom_1 (63)
  // takes one.
  r = test::run_hullmesh(merge_chine + " --suppress-knuckle plane:0,0,0,1,0,0@0.01");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(knuckle_lines(r.out).first, 1) << r.out;
  r = test::run_hullmesh(merge_chine + " --suppress-knuckle de:95,63");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(knuckle_lines(r.out).first, 2) << r.out;
  // Suppressing wins over adding.
  r = test::run_hullmesh(merge_chine + " --add-knuckle de:95,63 --suppress-knuckle de:95,63");
  EXPECT_EQ(knuckle_lines(r.out).first, 2) << r.out;
  // The smooth Wigley has none; the border of its first two patches (the station x = 25 m,
  // keel to deck) becomes one when asked.
  const std::string merge_wigley = "merge " + test::q(wigley) + " -o " + test::q(out);
  r = test::run_hullmesh(merge_wigley);
  EXPECT_EQ(knuckle_lines(r.out).first, 0) << r.out;
  r = test::run_hullmesh(merge_wigley + " --add-knuckle patches:0,1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const auto [count, length] = knuckle_lines(r.out);
  EXPECT_EQ(count, 1) << r.out;
  EXPECT_NEAR(length, 9.31, 0.05) << r.out;
}

// Total length of the mesh's edges whose two ends lie on the plane x = x0.
double edge_length_on_station(const fs::path& path, double x0) {
  const SurfaceMesh m = read_mesh(path.string()).mesh;
  std::set<std::pair<Index, Index>> edges;
  for (const Face& f : m.faces) {
    const int n = is_triangle(f) ? 3 : 4;
    for (int k = 0; k < n; ++k) {
      const Index a = f[k], b = f[(k + 1) % n];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  double total = 0;
  for (const auto& [a, b] : edges) {
    const Vec3d &p = m.positions[a], &q = m.positions[b];
    if (std::abs(p.x - x0) < 1e-6 && std::abs(q.x - x0) < 1e-6) total += norm(q - p);
  }
  return total;
}

// A repeatable option takes one value per occurrence: the input file after it is the input
// file (it was taken as one more value, and the command said "file is required"), on the
// command line and from a job file, whose keys come in alphabetical order.
TEST(CliKnuckleHints, RepeatedHintsBeforeTheFileAndInAJobFile) {
  const fs::path dir = test::scratch_dir("cli_knuckle_hints_repeat");
  const fs::path wigley = dir / "wigley.igs", out = dir / "m.vtu", job = dir / "job.json";
  ASSERT_EQ(test::run_hullmesh("-q generate wigley --patches 4 -o " + test::q(wigley)).exit_code,
            0);
  auto r = test::run_hullmesh("merge --add-knuckle patches:0,1 --add-knuckle patches:2,3 " +
                              test::q(wigley) + " -o " + test::q(out));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(knuckle_lines(r.out).first, 2) << r.out;
  std::ofstream(job) << R"({"command": "merge", "file": "wigley.igs", "output": "j.vtu",
                           "add-knuckle": ["patches:0,1"], "suppress-knuckle": ["de:11,15"]})";
  r = test::run_hullmesh("run " + test::q(job));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_EQ(knuckle_lines(r.out).first, 1) << r.out;
  r = test::run_hullmesh("-q unstructured --source 10,1,2,5,1 " + test::q(wigley) + " -o " +
                         test::q(dir / "s.gdf") + " --panels 300 --triangles 20000");
  EXPECT_EQ(r.exit_code, 0) << r.out;
}

TEST(CliKnuckleHints, UnstructuredKeepsAnAddedKnuckleAsPanelEdges) {
  const fs::path dir = test::scratch_dir("cli_knuckle_hints_unstructured");
  const fs::path wigley = dir / "wigley.igs", plain = dir / "plain.obj",
                 hinted = dir / "hinted.obj";
  ASSERT_EQ(test::run_hullmesh("-q generate wigley --patches 4 -o " + test::q(wigley)).exit_code,
            0);
  const std::string run =
      "-q unstructured " + test::q(wigley) + " --panels 600 --triangles 20000 -o ";
  ASSERT_EQ(test::run_hullmesh(run + test::q(plain)).exit_code, 0);
  const auto r = test::run_hullmesh(run + test::q(hinted) + " --add-knuckle de:3,7");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // The station x = 25 m from keel to deck is 9.31 m long: kept as a line of panel edges (its
  // chords), and not there without the hint.
  EXPECT_GT(edge_length_on_station(hinted, 25.0), 9.25);
  EXPECT_LT(edge_length_on_station(plain, 25.0), 1.0);
}

TEST(CliKnuckleHints, BadHintExitsWithUsageErrorBeforeAnyOutput) {
  const fs::path dir = test::scratch_dir("cli_knuckle_hints_bad");
  const fs::path wigley = dir / "wigley.igs", out = dir / "panels.gdf";
  ASSERT_EQ(test::run_hullmesh("-q generate wigley --patches 4 -o " + test::q(wigley)).exit_code,
            0);
  auto r = test::run_hullmesh("unstructured " + test::q(wigley) + " -o " + test::q(out) +
                              " --suppress-knuckle plane:0,0,1");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--suppress-knuckle plane:0,0,1: expected 6 comma-separated numbers"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(out));
  r = test::run_hullmesh("structured " + test::q(wigley) + " -o " + test::q(out) +
                         " --add-knuckle patches:0,9");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("names patch 9, but the hull has patches 0 to 3"), std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace hm::cli
