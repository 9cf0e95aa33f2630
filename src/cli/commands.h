// Subcommands of the hullmesh executable. Each registers its options on the CLI11 app and sets
// the action to run once the command line is parsed.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace hm::cli {

// Options every command shares.
struct GlobalOptions {
  int threads = 0;  // 0 = all cores
  bool quiet = false;
  bool verbose = false;
};

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

}  // namespace hm::cli
