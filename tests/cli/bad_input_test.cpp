// The command-line part of the bad-input table (issue 10): each broken request gets its exit code
// and a message that names what is wrong. The readers' own tables are in tests/io and tests/iges.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

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

}  // namespace
