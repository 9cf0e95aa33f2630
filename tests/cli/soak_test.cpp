// Soak: a long batch of equal jobs must not grow in resident memory. The jobs are alike (one
// hull, drafts a few centimetres apart, both meshers), so once the allocator has settled, the
// peak resident set of the last third of the run must be that of the first third. LeakSanitizer
// (scripts/test --sanitize) finds the small leaks this cannot see. HM_SOAK_JOBS=N runs a longer
// sweep (default 48 jobs).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/test_json.h"
#include "support/test_support.h"

namespace {

namespace fs = std::filesystem;
namespace test = hm::test;

using test::q;

// Resident set of a process in KiB, or -1 once it has gone.
long resident_kib(int pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) return std::strtol(line.c_str() + 6, nullptr, 10);
  }
  return -1;
}

int soak_jobs() {
  const char* env = std::getenv("HM_SOAK_JOBS");
  const int n = env ? std::atoi(env) : 48;
  return std::max(n, 12);
}

TEST(Soak, ResidentMemoryOfALongBatchLevelsOff) {
  const fs::path dir = test::scratch_dir("cli_soak");
  const int jobs = soak_jobs();
  {
    // jobs/2 drafts x 2 meshers, one small generated hull.
    std::ofstream m(dir / "sweep.json");
    m << R"({"hulls": [{"name": "h", "generate": {"kind": "round-bilge", "length": 60,
             "beam": 10, "depth": 6, "draft": 3, "patches": 4}}],
             "grid": {"mesher": ["unstructured", "structured"], "panels": [300], "draft": [)";
    for (int k = 0; k < jobs / 2; ++k) m << (k ? ", " : "") << 2.5 + 0.02 * k;
    m << R"(]}, "options": {"triangles": 8000}, "formats": ["gdf"]})";
  }
  const auto t0 = std::chrono::steady_clock::now();
  const int pid = test::spawn_hullmesh(
      "-q --threads 2 batch " + q(dir / "sweep.json") + " --out " + q(dir / "out"),
      dir / "log.txt");
  ASSERT_GT(pid, 0);
  std::vector<long> rss;
  std::vector<double> when;
  int status = 0;
  for (;;) {
    const long kib = resident_kib(pid);
    if (kib > 0) {
      rss.push_back(kib);
      when.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    if (waitpid(pid, &status, WNOHANG) == pid) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  std::ifstream log_file(dir / "log.txt");
  std::stringstream log;
  log << log_file.rdbuf();
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << log.str();
  const nlohmann::json summary = test::read_json(dir / "out" / "summary.json");
  ASSERT_FALSE(summary.is_discarded());
  ASSERT_EQ(summary["ok"], jobs / 2 * 2);
  ASSERT_GE(rss.size(), 30u) << "too few samples to judge";

  // Peak of the first and of the last third of the run, by time.
  const double end = when.back();
  long first = 0, last = 0;
  for (std::size_t i = 0; i < rss.size(); ++i) {
    if (when[i] <= end / 3) first = std::max(first, rss[i]);
    if (when[i] >= 2 * end / 3) last = std::max(last, rss[i]);
  }
  std::printf(
      "soak: %d jobs in %.1f s; peak resident memory %.1f MiB in the first third, "
      "%.1f MiB in the last\n",
      jobs, end, first / 1024.0, last / 1024.0);
  // Allocator slack: 10% and 16 MiB. A leak of 2 MiB per job, planted by hand in run_job, took
  // the last third's peak from 60 to 124 MiB (first third 60 MiB) and failed this.
  EXPECT_LE(last, first + first / 10 + 16 * 1024)
      << "resident memory grew from " << first << " KiB to " << last << " KiB";
}

}  // namespace
