// The command-line part of the bad-input table (issue 10): each broken request gets its exit code
// and a message that names what is wrong. The readers' own tables are in tests/io and tests/iges.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "iges/write_iges.h"
#include "nurbs/generate_hull.h"
#include "support/test_support.h"

namespace {

namespace fs = std::filesystem;
namespace test = hm::test;

using test::q;

struct BadCase {
  const char* what;
  const char* job;   // written to job.json when not empty
  const char* args;  // {dir} is the scratch folder
  int exit_code;
  const char* message;
};

TEST(CliBadInput, EachBrokenRequestHasItsExitCodeAndMessage) {
  const fs::path dir = test::scratch_dir("cli_bad_input");
  ASSERT_EQ(test::run_hullmesh("-q generate wigley --patches 2 -o " + q(dir / "w.igs")).exit_code,
            0);
  fs::create_directories(dir / "taken.gdf");  // an output path that is a folder
  const BadCase cases[] = {
      {"NaN on the command line", "", "unstructured {dir}/w.igs -o {dir}/o.gdf --draft nan", 2,
       "--draft: 'nan' is not a finite number"},
      {"infinity on the command line", "", "structured {dir}/w.igs -o {dir}/o.gdf --trim inf", 2,
       "--trim: Value inf not in range"},
      {"NaN in a job file",
       R"({"command": "unstructured", "file": "w.igs", "output": "o.gdf", "draft": NaN})",
       "run {dir}/job.json", 3, "job.json: not valid JSON"},
      {"a number beyond a double in a job file",
       R"({"command": "unstructured", "file": "w.igs", "output": "o.gdf", "draft": 1e999})",
       "run {dir}/job.json", 3, "job.json"},
      {"a negative panel count", "", "unstructured {dir}/w.igs -o {dir}/o.gdf --panels -5", 2,
       "--panels: Value -5 not in range"},
      {"a negative panel count in a job file",
       R"({"command": "structured", "file": "w.igs", "output": "o.gdf", "panels": -5})",
       "run {dir}/job.json", 2, "key 'panels'"},
      {"an output folder that does not exist", "",
       "unstructured {dir}/w.igs -o {dir}/no/such/o.gdf --panels 100", 6, "does not exist"},
      {"an output path that is a folder", "",
       "structured {dir}/w.igs -o {dir}/taken.gdf --panels 100", 6, "taken.gdf"},
      {"an IGES file that does not exist", "", "unstructured {dir}/none.igs -o {dir}/o.gdf", 6,
       "none.igs"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.what);
    if (*c.job) std::ofstream(dir / "job.json") << c.job;
    std::string args = c.args;
    for (std::size_t at; (at = args.find("{dir}")) != std::string::npos;) {
      args.replace(at, 5, dir.string());
    }
    const auto r = test::run_hullmesh("-q " + args);
    EXPECT_EQ(r.exit_code, c.exit_code) << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << r.out;
    // Nothing half-written is left behind.
    EXPECT_FALSE(fs::exists(dir / "o.gdf"));
  }
}

// A bilinear patch through four corners (00, 10, 01, 11 in (u, v)).
hm::Patch bilinear(const hm::Vec3d& p00, const hm::Vec3d& p10, const hm::Vec3d& p01,
                   const hm::Vec3d& p11) {
  hm::Patch p;
  hm::NurbsSurface& s = p.surface;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.points = {p00, p10, p01, p11};
  s.weights.assign(4, 1.0);
  return p;
}

std::vector<hm::Patch> small_wigley() {
  hm::HullSpec spec;
  spec.length = 20;
  spec.beam = 2;
  spec.depth = 1.6;
  spec.draft = 1.25;
  spec.patches = 2;
  return hm::generate_hull(spec).patches;
}

// The geometry rows of the table: patches with no area, and patches through each other. Each file
// is written with the project's own IGES writer; the patches after the hull's come last (their
// DE numbers are the file's highest).
TEST(CliBadInput, BrokenPatchesAreNamedByEntity) {
  const fs::path dir = test::scratch_dir("cli_bad_patches");
  const std::vector<hm::Patch> hull = small_wigley();
  const hm::Vec3d c{10, 0.5, 0.8};
  auto with = [&](const char* name, std::vector<hm::Patch> extra) {
    std::vector<hm::Patch> all = hull;
    all.insert(all.end(), extra.begin(), extra.end());
    hm::write_iges_file((dir / name).string(), all);
    return dir / name;
  };
  const fs::path point = with("point.igs", {bilinear(c, c, c, c)});
  const fs::path line =
      with("line.igs", {bilinear(c, c + hm::Vec3d{1, 0, 0}, c, c + hm::Vec3d{2, 0, 0})});
  hm::write_iges_file((dir / "only_point.igs").string(), {bilinear(c, c, c, c)});
  // A plate across the port side, from inside the hull to beyond its beam (off the patches' seam
  // at x = 10: a plate through the hull exactly along mesh edges only touches each face).
  const fs::path plate =
      with("plate.igs", {bilinear({7.3, 0.2, 0.3}, {7.3, 3, 0.3}, {7.3, 0.2, 1.0}, {7.3, 3, 1.0})});

  struct Row {
    const char* what;
    std::string args;
    int exit_code;
    std::vector<std::string> messages;
  };
  const std::string out = " -o " + q(dir / "o.gdf");
  const Row rows[] = {
      {"a patch collapsed to a point",
       "unstructured --panels 300 " + q(point) + out,
       0,
       {"point.igs: error: DE ", "the surface collapses to a point", "; skipped"}},
      {"a patch collapsed to a line",
       "unstructured --panels 300 " + q(line) + out,
       0,
       {"line.igs: error: DE ", "the surface collapses to a line", "; skipped"}},
      {"a file of one patch collapsed to a point",
       "structured " + q(dir / "only_point.igs") + out,
       3,
       {"only_point.igs: no readable surface", "DE 1 ", "collapses to a point"}},
      {"a patch through the hull",
       "unstructured --panels 300 " + q(plate) + out,
       0,
       {"warning: ", "plate.igs: the merged surface passes through itself",
        "pairs of faces cross, the first of patch ", "(DE ", ") and patch ",
        "the panel mesh passes through itself"}},
      // The structured mesher checks the merged surface beside its meshing, and still warns.
      {"a patch through the hull, structured",
       "structured --panels 300 " + q(plate) + out,
       0,
       {"warning: ", "plate.igs: the merged surface passes through itself",
        "pairs of faces cross, the first of patch "}},
  };
  for (const Row& r : rows) {
    SCOPED_TRACE(r.what);
    fs::remove(dir / "o.gdf");
    const auto run = test::run_hullmesh(r.args);
    EXPECT_EQ(run.exit_code, r.exit_code) << run.out;
    for (const std::string& m : r.messages) EXPECT_NE(run.out.find(m), std::string::npos) << m;
    EXPECT_EQ(fs::exists(dir / "o.gdf"), r.exit_code == 0);
  }
  // The crossing panels fail the panel-code rules: `quality` names them and exits 7.
  ASSERT_EQ(test::run_hullmesh("-q unstructured --panels 300 " + q(plate) + out).exit_code, 0);
  const auto judged = test::run_hullmesh("quality " + q(dir / "o.gdf"));
  EXPECT_EQ(judged.exit_code, 7) << judged.out;
  EXPECT_NE(judged.out.find("pairs of panels pass through each other"), std::string::npos)
      << judged.out;
  // The hull alone passes that rule.
  hm::write_iges_file((dir / "hull.igs").string(), hull);
  ASSERT_EQ(
      test::run_hullmesh("-q unstructured --panels 300 " + q(dir / "hull.igs") + out).exit_code, 0);
  const auto clean = test::run_hullmesh("quality " + q(dir / "o.gdf"));
  EXPECT_NE(clean.out.find("panels through each other      0 pairs"), std::string::npos)
      << clean.out;
}

}  // namespace
