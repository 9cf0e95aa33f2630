// hullmesh: panel meshes of ship hulls from IGES NURBS patches.
// The only place that catches hullmesh's typed errors and turns them into exit codes.
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <new>
#include <thread>

#include "cli/commands.h"
#include "core/error.h"

namespace {

int run(int argc, char** argv) {
  using namespace hm::cli;
  CLI::App app{"hullmesh " HULLMESH_VERSION
               ": panel meshes of ship hulls from IGES NURBS patches, for panel codes"};
  app.require_subcommand(1);
  // Global options may also follow the command name: `hullmesh info -q FILE`.
  app.fallthrough();
  app.set_version_flag("--version", "hullmesh " HULLMESH_VERSION);
  GlobalOptions global;
  app.add_option("--threads", global.threads, "Threads to use (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  app.add_flag("-q,--quiet", global.quiet, "Print only errors");
  app.add_flag("-v,--verbose", global.verbose, "Print more detail");

  Action action;
  register_info(app, global, action);
  register_generate(app, global, action);
  register_tessellate(app, global, action);
  register_section(app, global, action);
  register_convert(app, global, action);
  register_quality(app, global, action);
  register_merge(app, global, action);
  register_unstructured(app, global, action);
  register_structured(app, global, action);
  register_render(app, global, action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : static_cast<int>(hm::ExitCode::kUsage);
  }
  const std::size_t threads = global.threads > 0
                                  ? static_cast<std::size_t>(global.threads)
                                  : std::max(1u, std::thread::hardware_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  return action ? action() : 0;
}

}  // namespace

int main(int argc, char** argv) {
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
