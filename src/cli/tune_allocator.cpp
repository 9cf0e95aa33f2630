// Why: each first touch of a fresh page is a fault, and on these virtual machines a fault costs
// microseconds. A 2,000-panel kcs structured run took 11,900-13,300 faults with glibc's
// defaults, 9,100 with freed memory kept (mallopt), and about 1,000 with huge pages as well; wall
// time on 2 threads 0.37 -> 0.32 -> 0.24 s. The other shared hulls and the unstructured and merge
// commands gain 10-35%, for 3-11 MB more peak memory (38 MB, 19%, on a 470,000-triangle merge).
// Huge pages for malloc's memory are a glibc tunable (glibc.malloc.hugetlb, 2.35 on), read only
// when a program starts: hence the re-run.
#include "cli/tune_allocator.h"

#include <cstdlib>
#include <cstring>
#include <string>

#if defined(__GLIBC__) && defined(__linux__)
#include <malloc.h>
#include <unistd.h>
#endif

namespace hm::cli {
namespace {

// Set by the first run for the second: the caller's GLIBC_TUNABLES ("-" when it had none).
constexpr const char* kWas = "HULLMESH_GLIBC_TUNABLES_WAS";
constexpr const char* kTunables =
    "glibc.malloc.hugetlb=1:glibc.malloc.top_pad=67108864:glibc.malloc.mmap_threshold=33554432";

const char* g_setting = "default";

}  // namespace

const char* allocator_setting() { return g_setting; }

void tune_allocator(char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  if (const char* was = std::getenv(kWas)) {
    // The re-run: the tunables are in force; the environment goes back to the caller's.
    if (std::strcmp(was, "-") == 0) {
      unsetenv("GLIBC_TUNABLES");
    } else {
      setenv("GLIBC_TUNABLES", was, 1);
    }
    unsetenv(kWas);
    g_setting = "huge pages, 64 MB kept (re-run)";
    return;
  }
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, "glibc.malloc.") != nullptr) {
    g_setting = "the caller's GLIBC_TUNABLES";
    return;
  }
  if (std::getenv("HULLMESH_DEFAULT_ALLOCATOR") != nullptr) {
    g_setting = "default (HULLMESH_DEFAULT_ALLOCATOR)";
    return;
  }
  const std::string before = tunables != nullptr ? tunables : "";
  const std::string wanted = before.empty() ? kTunables : before + ":" + kTunables;
  if (setenv(kWas, tunables != nullptr ? tunables : "-", 1) == 0 &&
      setenv("GLIBC_TUNABLES", wanted.c_str(), 1) == 0) {
    execv("/proc/self/exe", argv);
  }
  // No re-run (no /proc, or exec refused): the environment as it was, and the kept memory.
  unsetenv(kWas);
  if (tunables != nullptr) {
    setenv("GLIBC_TUNABLES", before.c_str(), 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  g_setting = "64 MB kept (mallopt)";
#else
  (void)argv;
#endif
}

}  // namespace hm::cli
