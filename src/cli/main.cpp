// hullmesh: panel meshes of ship hulls from IGES NURBS patches.
// The only place that catches hullmesh's typed errors and turns them into exit codes.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <thread>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "cli/execute.h"
#include "core/error.h"

namespace {

// Every stage builds arrays of the whole mesh and frees them. glibc hands large blocks back to the
// kernel on free and maps them again on the next allocation, and each first touch of a page is
// a fault (a quarter of the faults of a 2,000-panel kcs run came from that). Keeping 64 MB of
// freed memory for reuse: 10% less wall time on 2 threads (structured kcs 2,000 panels 0.37 ->
// 0.32 s, unstructured ship_449 4,000 panels 0.84 -> 0.76 s) for 2 MB more peak memory. A user's
// own GLIBC_TUNABLES for malloc win.
void keep_freed_memory() {
#if defined(__GLIBC__)
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, "glibc.malloc.") != nullptr) return;
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
#endif
}

int run(int argc, char** argv) {
  using namespace hm::cli;
  auto inv = make_invocation();
  try {
    inv->app->parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = inv->app->exit(e);
    return code == 0 ? 0 : static_cast<int>(hm::ExitCode::kUsage);
  }
  const int requested = inv->global.threads;
  const std::size_t threads = requested > 0 ? static_cast<std::size_t>(requested)
                                            : std::max(1u, std::thread::hardware_concurrency());
  // Both are needed for --threads above the core count: the limit alone caps the workers but
  // leaves the default arena at one slot per core; an arena alone gets no more workers than the
  // cores. With both, --threads 8 runs 8 threads on 2 cores (as the determinism tests want).
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  tbb::task_arena arena(static_cast<int>(threads));
  return arena.execute([&] { return execute(*inv, {}).exit_code; });
}

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  try {
    return run(argc, argv);
  } catch (const hm::Error& e) {
    std::fprintf(stderr, "hullmesh: error: %s\n", e.what());
    return static_cast<int>(e.exit_code());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "hullmesh: error: out of memory\n");
    return static_cast<int>(hm::ExitCode::kInternal);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hullmesh: internal error: %s\n", e.what());
    return static_cast<int>(hm::ExitCode::kInternal);
  }
}
