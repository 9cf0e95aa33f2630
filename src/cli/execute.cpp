#include "cli/execute.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>

#include "cli/run_record.h"
#include "cli/validate_stage.h"
#include "core/error.h"

namespace hm::cli {
namespace {

// CLI11 reads "nan" and "inf" as doubles, and ranges like POSITIVE let them through; no length,
// draft or angle of ours may be either. Called once the command line is parsed.
void require_finite_numbers(const CLI::App& cmd) {
  for (const CLI::Option* opt : cmd.get_options()) {
    if (opt->get_type_name().rfind("FLOAT", 0) != 0) continue;
    for (const std::string& word : opt->results()) {
      char* end = nullptr;
      const double x = std::strtod(word.c_str(), &end);
      if (end != word.c_str() && *end == '\0' && !std::isfinite(x)) {
        throw CLI::ValidationError(opt->get_name(), "'" + word + "' is not a finite number");
      }
    }
  }
}

}  // namespace

const CLI::App* Invocation::command() const {
  const auto parsed = app->get_subcommands();
  return parsed.empty() ? nullptr : parsed.front();
}

std::unique_ptr<Invocation> make_invocation() {
  auto inv = std::make_unique<Invocation>();
  inv->app = std::make_unique<CLI::App>(
      "hullmesh " HULLMESH_VERSION
      ": panel meshes of ship hulls from IGES NURBS patches, for panel codes");
  CLI::App& app = *inv->app;
  app.require_subcommand(1);
  // Global options may also follow the command name: `hullmesh info -q FILE`.
  app.fallthrough();
  // Every option's default is kept, so that a run record can name each effective value.
  app.option_defaults()->always_capture_default();
  app.set_version_flag("--version", "hullmesh " HULLMESH_VERSION);
  GlobalOptions& global = inv->global;
  app.add_option("--threads", global.threads, "Threads to use (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  app.add_flag("-q,--quiet", global.quiet, "Print only errors");
  app.add_flag("-v,--verbose", global.verbose, "Print more detail");
  app.add_flag("--no-run-json", global.no_record,
               "Do not write the *.run.json record beside an output mesh");
  global.validate = validation_from_environment();
  app.add_flag("--validate", global.validate,
               "Check the mesh invariants between stages (manifold, oriented, no zero-area "
               "panels, deviation bound, feature lines kept); exit 1 naming a stage that breaks "
               "one (default on when HULLMESH_VALIDATE is set)");
  app.parse_complete_callback([&app] {
    for (const CLI::App* cmd : app.get_subcommands()) require_finite_numbers(*cmd);
  });
  Action& action = inv->action;
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
  register_run(app, global, action);
  register_batch(app, global, action);
  return inv;
}

ExecuteResult execute(Invocation& inv, const ExecuteOptions& options) {
  ExecuteResult result;
  if (!inv.action) return result;
  if (options.force_quiet) inv.global.quiet = true;
  if (options.validate) inv.global.validate = true;
  RunRecord record(RunLog::mode_for(inv.global.quiet));
  if (const CLI::App* cmd = inv.command()) {
    record.command = cmd->get_name();
    record.parameters = effective_options(*cmd);
  }
  inv.global.record = &record;
  result.exit_code = inv.action();
  record.log.finish();
  inv.global.record = nullptr;
  // The record hashes the input and every output: built once, and only when it is wanted.
  const bool write = options.write_record && !inv.global.no_record;
  if (result.exit_code == 0 && !record.outputs.empty() && (write || options.keep_record)) {
    nlohmann::ordered_json j = record_json(record);
    if (write) write_run_record(record, j);
    if (options.keep_record) result.record = std::move(j);
  }
  return result;
}

ExecuteResult execute_args(const std::vector<std::string>& args, const std::string& where,
                           const ExecuteOptions& options) {
  auto inv = make_invocation();
  // CLI11 takes the words last first.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    inv->app->parse(reversed);
  } catch (const CLI::ParseError& e) {
    // "--panels: Value 0 not in range ..." reads, for a job file, as the key it came from.
    std::string message =
        std::regex_replace(std::string(e.what()), std::regex("--([a-z0-9-]+)"), "key '$1'");
    throw UsageError(where + ": " + message);
  }
  return execute(*inv, options);
}

}  // namespace hm::cli
