// Nothing torn: a mesher killed (SIGKILL, no chance to clean up) at seeded random moments leaves
// its output either as it was before the run or as the finished file, byte for byte, and never a
// half-written one. The same holds for the run record beside it.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <thread>

#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::run_hullmesh;

using test::q;

void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

TEST(CliKill, AKilledMesherLeavesTheOldOutputOrTheNewOneNeverATornFile) {
  const fs::path dir = test::scratch_dir("cli_kill");
  const fs::path igs = dir / "hull.igs";
  ASSERT_EQ(run_hullmesh("-q generate round-bilge --patches 6 -o " + q(igs)).exit_code, 0);
  const fs::path out = dir / "panels.gdf";
  const fs::path record = dir / "panels.gdf.run.json";
  const std::string args =
      "-q --threads 1 unstructured " + q(igs) + " -o " + q(out) + " --panels 800 --draft 5";
  // The finished files, and how long a whole run takes.
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(run_hullmesh(args).exit_code, 0);
  const double whole = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string new_mesh = test::file_bytes(out);
  ASSERT_GT(new_mesh.size(), 1000u);
  const std::string old_mesh = "an older mesh that a killed run must not tear\n";
  const std::string old_record = "{\"older\": true}\n";

  // Strike at seeded random moments over the whole run (and a little past it): early, in the
  // middle of the meshing, and while or after the files are written.
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> when(0.0, 1.1 * whole);
  int kept_old = 0, got_new = 0;
  for (int trial = 0; trial < 12; ++trial) {
    write_bytes(out, old_mesh);
    write_bytes(record, old_record);
    const double delay = when(rng);
    const pid_t pid = test::spawn_hullmesh(args);
    ASSERT_GT(pid, 0);
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    kill(pid, SIGKILL);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    const std::string mesh = test::file_bytes(out);
    const std::string rec = test::file_bytes(record);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", killed after " + std::to_string(delay) +
                 " s of a " + std::to_string(whole) + " s run");
    EXPECT_TRUE(mesh == old_mesh || mesh == new_mesh) << "torn mesh: " << mesh.size() << " bytes";
    EXPECT_TRUE(rec == old_record || nlohmann::json::accept(rec)) << rec;
    (mesh == old_mesh ? kept_old : got_new) += 1;
  }
  // Some strikes came before the rename (else the test proved nothing); how many came after it
  // depends on the machine's load, so it is only reported.
  EXPECT_GT(kept_old, 0);
  std::printf("killed runs: %d left the old file, %d the new one\n", kept_old, got_new);
  // A killed run leaves at most its own temporary beside the target, never under the target's
  // name: the next run replaces the file whole.
  ASSERT_EQ(run_hullmesh(args).exit_code, 0);
  EXPECT_EQ(test::file_bytes(out), new_mesh);
}

}  // namespace
}  // namespace hm
