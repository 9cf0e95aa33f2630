// Helpers shared by the tests: where the shared hulls are, scratch folders.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace hm::test {

// ../shared/data/hulls beside the checkout (HM_SHARED_DIR overrides), or empty when absent.
std::filesystem::path shared_hulls_dir();
// Path of a shared hull file; calls GTEST_SKIP in the caller via the macro below when missing.
std::filesystem::path shared_hull(const std::string& name);
// A fresh, empty scratch folder for this test (under the build tree or /tmp).
std::filesystem::path scratch_dir(const std::string& test_name);
// Path of the built hullmesh executable.
std::filesystem::path hullmesh_exe();

// A JSON file's value; a discarded value (is_discarded()) when it is missing or not JSON.
nlohmann::json read_json(const std::filesystem::path& path);

struct RunResult {
  int exit_code = -1;
  std::string out;  // stdout and stderr, interleaved
};
// Runs `hullmesh ARGS` through the shell, capturing output, with HULLMESH_VALIDATE=1 (every
// stage's invariants checked, as `--validate` does).
RunResult run_hullmesh(const std::string& args);

}  // namespace hm::test

// Skips the current test when a shared hull is not present (CI without ../shared).
#define HM_REQUIRE_SHARED_HULL(var, name)                          \
  const std::filesystem::path var = ::hm::test::shared_hull(name); \
  if (var.empty()) GTEST_SKIP() << "shared hull " << name << " not present"
