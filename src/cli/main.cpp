// hullmesh: panel meshes of ship hulls from IGES NURBS patches.
// The only place that catches hullmesh's typed errors and turns them into exit codes.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <new>
#include <thread>

#include "cli/execute.h"
#include "cli/tune_allocator.h"
#include "core/error.h"

namespace {

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
  hm::cli::tune_allocator(argv);
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
