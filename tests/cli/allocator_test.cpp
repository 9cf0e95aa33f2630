// The allocator setting the CLI starts with (cli/tune_allocator.h): the re-run with glibc's
// tunables, the opt-out and the caller's own tunables each leave their mark in the run record,
// and the mesh is the same bytes whichever allocator made it.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.h"

namespace {

namespace fs = std::filesystem;
namespace test = hm::test;
using test::q;

// Sets an environment variable for the scope of one run (popen passes the environment on).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = getenv(name)) old_ = old, had_ = true;
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (had_) {
      setenv(name_, old_.c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

struct MeshRun {
  std::string allocator;
  std::string mesh;
};

MeshRun mesh_once(const fs::path& dir, const fs::path& igs) {
  const fs::path out = dir / "panels.gdf";
  const auto r = test::run_hullmesh("-q structured " + q(igs) + " --panels 300 -o " + q(out));
  EXPECT_EQ(r.exit_code, 0) << r.out;
  std::ifstream in(dir / "panels.run.json");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  EXPECT_FALSE(j.is_discarded());
  return {j.value("allocator", std::string{}), test::file_bytes(out)};
}

TEST(CliAllocator, EachSettingIsRecordedAndMakesTheSameMesh) {
  const fs::path root = test::scratch_dir("cli_allocator");
  const fs::path igs = root / "wigley.igs";
  ASSERT_EQ(test::run_hullmesh("-q generate wigley --patches 4 -o " + q(igs)).exit_code, 0);
  std::string tunables_before;
  if (const char* t = getenv("GLIBC_TUNABLES")) tunables_before = t;
  const bool caller_has_malloc_tunables =
      tunables_before.find("glibc.malloc.") != std::string::npos;

  fs::create_directories(root / "tuned");
  const MeshRun tuned = mesh_once(root / "tuned", igs);
#if defined(__GLIBC__) && defined(__linux__)
  if (!caller_has_malloc_tunables) {
    // /proc/self/exe is there on Linux, so the re-run happens.
    EXPECT_EQ(tuned.allocator, "huge pages, 64 MB kept (re-run)");
  }
#endif
  {
    const ScopedEnv opt_out("HULLMESH_DEFAULT_ALLOCATOR", "1");
    fs::create_directories(root / "default");
    const MeshRun plain = mesh_once(root / "default", igs);
    if (!caller_has_malloc_tunables) {
      EXPECT_EQ(plain.allocator, "default (HULLMESH_DEFAULT_ALLOCATOR)");
    }
    EXPECT_EQ(plain.mesh, tuned.mesh);
  }
  {
    const ScopedEnv own("GLIBC_TUNABLES", "glibc.malloc.arena_max=2");
    fs::create_directories(root / "own");
    const MeshRun own_run = mesh_once(root / "own", igs);
#if defined(__GLIBC__) && defined(__linux__)
    EXPECT_EQ(own_run.allocator, "the caller's GLIBC_TUNABLES");
#endif
    EXPECT_EQ(own_run.mesh, tuned.mesh);
  }
}

}  // namespace
