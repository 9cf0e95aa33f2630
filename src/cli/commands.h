// Subcommands of the hullmesh executable. Each registers its options on the CLI11 app and sets
// the action to run once the command line is parsed.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <string>

namespace hm::cli {

struct RunRecord;  // cli/run_record.h

// Options every command shares.
struct GlobalOptions {
  int threads = 0;  // 0 = all cores
  bool quiet = false;
  bool verbose = false;
  bool no_record = false;  // --no-run-json: no `*.run.json` beside the output
  bool validate = false;   // --validate: invariants checked between stages (validate_stage.h)
  // The current run's stage log and record, set before the action runs (never null then).
  RunRecord* record = nullptr;
};

// A path's last part: what titles inside output files carry, so that one job run from two
// folders writes the same bytes.
inline std::string file_name(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

// The command to run after parsing; returns the exit code.
using Action = std::function<int()>;

void register_info(CLI::App& app, const GlobalOptions& global, Action& action);
void register_generate(CLI::App& app, const GlobalOptions& global, Action& action);
void register_tessellate(CLI::App& app, const GlobalOptions& global, Action& action);
void register_section(CLI::App& app, const GlobalOptions& global, Action& action);
void register_convert(CLI::App& app, const GlobalOptions& global, Action& action);
void register_quality(CLI::App& app, const GlobalOptions& global, Action& action);
void register_merge(CLI::App& app, const GlobalOptions& global, Action& action);
void register_unstructured(CLI::App& app, const GlobalOptions& global, Action& action);
void register_structured(CLI::App& app, const GlobalOptions& global, Action& action);
void register_render(CLI::App& app, const GlobalOptions& global, Action& action);
void register_run(CLI::App& app, const GlobalOptions& global, Action& action);
void register_batch(CLI::App& app, const GlobalOptions& global, Action& action);

}  // namespace hm::cli
