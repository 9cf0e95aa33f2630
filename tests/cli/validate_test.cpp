// --validate reaches the command that meshes, however it is started: typed before the command,
// before `run JOB`, or for a batch's jobs (in process, so that HULLMESH_VALIDATE, which the
// shell-run tests set, is not what turns it on). The run record says whether it was on.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/execute.h"
#include "support/test_json.h"
#include "support/test_support.h"

namespace hm::cli {
namespace {

namespace fs = std::filesystem;

bool validated(const fs::path& record) {
  const nlohmann::json r = test::read_json(record);
  return r.is_object() && r["results"]["validated"] == true;
}

TEST(Validate, TheFlagReachesTheMesherDirectlyAndThroughAJobFile) {
  unsetenv("HULLMESH_VALIDATE");
  const fs::path dir = test::scratch_dir("cli_validate");
  const std::string igs = (dir / "w.igs").string();
  ASSERT_EQ(
      execute_args({"-q", "generate", "wigley", "--patches", "2", "-o", igs}, "test", {}).exit_code,
      0);
  const std::string out = (dir / "w.obj").string();
  const fs::path record = dir / "w.run.json";
  for (const bool flag : {false, true}) {
    std::vector<std::string> words = {"-q", "unstructured", igs, "-o", out, "--panels", "300"};
    if (flag) words.insert(words.begin(), "--validate");
    ASSERT_EQ(execute_args(words, "test", {}).exit_code, 0);
    EXPECT_EQ(validated(record), flag);
  }
  std::ofstream(dir / "job.json") << R"({"command": "structured", "file": "w.igs", )"
                                  << R"("output": "w.obj", "panels": 300})";
  for (const bool flag : {false, true}) {
    std::vector<std::string> words = {"-q", "run", (dir / "job.json").string()};
    if (flag) words.insert(words.begin(), "--validate");
    ASSERT_EQ(execute_args(words, "test", {}).exit_code, 0);
    EXPECT_EQ(validated(record), flag);
  }
  // The environment turns it on as the flag does.
  setenv("HULLMESH_VALIDATE", "1", 1);
  ASSERT_EQ(
      execute_args({"-q", "unstructured", igs, "-o", out, "--panels", "300"}, "test", {}).exit_code,
      0);
  unsetenv("HULLMESH_VALIDATE");
  EXPECT_TRUE(validated(record));
}

// `hullmesh merge` checks the surface it writes as the meshers check the one they start from
// (until 2026-12-05 the flag did nothing there, and a surface with faces of no area passed).
TEST(Validate, TheFlagReachesTheMerge) {
  unsetenv("HULLMESH_VALIDATE");
  const fs::path dir = test::scratch_dir("cli_validate_merge");
  const std::string igs = (dir / "c.igs").string();
  ASSERT_EQ(execute_args(
                {"-q", "generate", "chine", "--patches", "3", "--full", "--gap", "0.02", "-o", igs},
                "test", {})
                .exit_code,
            0);
  const std::string out = (dir / "c.obj").string();
  for (const bool flag : {false, true}) {
    std::vector<std::string> words = {"-q", "merge", igs, "-o", out, "--triangles", "10000"};
    if (flag) words.insert(words.begin(), "--validate");
    ASSERT_EQ(execute_args(words, "test", {}).exit_code, 0);
    EXPECT_EQ(validated(dir / "c.run.json"), flag);
  }
}

TEST(Validate, ABatchValidatesEveryJob) {
  unsetenv("HULLMESH_VALIDATE");
  const fs::path dir = test::scratch_dir("cli_validate_batch");
  std::ofstream(dir / "sweep.json")
      << R"({"hulls": [{"name": "w", "generate": {"kind": "wigley", "patches": 2}}],)"
      << R"( "grid": {"mesher": ["unstructured", "structured"], "panels": [300]}})";
  const fs::path out = dir / "out";
  ASSERT_EQ(execute_args(
                {"-q", "--validate", "batch", (dir / "sweep.json").string(), "--out", out.string()},
                "test", {})
                .exit_code,
            0);
  std::size_t records = 0;
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string name = e.path().filename().string();
    if (name.size() < 9 || name.substr(name.size() - 9) != ".run.json") continue;
    ++records;
    EXPECT_TRUE(validated(e.path())) << name;
  }
  EXPECT_EQ(records, 2u);
}

}  // namespace
}  // namespace hm::cli
