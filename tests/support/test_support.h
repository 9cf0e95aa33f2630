// Helpers shared by the tests: where the shared hulls are, scratch folders.
#pragma once

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <filesystem>
#include <string>
#include <utility>

namespace hm::test {

// ../shared/data/hulls beside the checkout (HM_SHARED_DIR overrides), or empty when absent.
std::filesystem::path shared_hulls_dir();
// Path of a shared hull file; calls GTEST_SKIP in the caller via the macro below when missing.
std::filesystem::path shared_hull(const std::string& name);
// A fresh, empty scratch folder for this test (under the build tree or /tmp).
std::filesystem::path scratch_dir(const std::string& test_name);
// Path of the built hullmesh executable.
std::filesystem::path hullmesh_exe();
// The whole file as bytes (empty when it cannot be read).
std::string file_bytes(const std::filesystem::path& p);

// A path quoted for the shell that run_hullmesh and spawn_hullmesh go through.
inline std::string q(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

struct RunResult {
  int exit_code = -1;
  std::string out;  // stdout and stderr, interleaved
};
// Runs `hullmesh ARGS` through the shell, capturing output, with HULLMESH_VALIDATE=1 (every
// stage's invariants checked, as `--validate` does).
RunResult run_hullmesh(const std::string& args);
// Starts `hullmesh ARGS` in the background (no validation: kill and soak tests time it), its
// stdout and stderr into `log` (/dev/null when empty). Returns the pid to wait for, or -1.
int spawn_hullmesh(const std::string& args, const std::filesystem::path& log = {});

// The thread counts the determinism tests compare: serial, CI's two cores, and more threads than
// cores, where tasks interleave and steal in ways two threads on two cores rarely show.
inline constexpr int kThreadCounts[] = {1, 2, 8};

// f() run on exactly `threads` threads. An arena of that size with the global limit raised to
// match: an arena alone gets no more workers than there are cores, a limit alone no more slots.
template <class F>
auto with_threads(int threads, F&& f) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  tbb::task_arena arena(threads);
  return arena.execute(std::forward<F>(f));
}

}  // namespace hm::test

// Skips the current test when a shared hull is not present (CI without ../shared).
#define HM_REQUIRE_SHARED_HULL(var, name)                          \
  const std::filesystem::path var = ::hm::test::shared_hull(name); \
  if (var.empty()) GTEST_SKIP() << "shared hull " << name << " not present"
