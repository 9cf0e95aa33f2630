// One hullmesh command line, parsed and run in this process: what main() does with argv, what
// `hullmesh run` does with a job file, and what a batch does for each of its jobs.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace hm::cli {

// The app with its global options and every command registered, and what parsing it sets.
struct Invocation {
  GlobalOptions global;
  Action action;
  std::unique_ptr<CLI::App> app;
  // The command chosen by the parsed line (null before parsing).
  const CLI::App* command() const;
};

std::unique_ptr<Invocation> make_invocation();

struct ExecuteOptions {
  bool force_quiet = false;  // a batch's jobs print nothing of their own
  bool write_record = true;  // `*.run.json` beside the output (a batch writes its own)
  bool keep_record = false;  // hand the record back in ExecuteResult (a batch's jobs)
  bool validate = false;     // --validate for the command run, whatever its own words say
};

struct ExecuteResult {
  int exit_code = 0;
  // The run record (cli/run_record.h) of a command that wrote an output when keep_record was
  // asked for, else null.
  nlohmann::ordered_json record;
};

// Runs a parsed invocation's action with a fresh run record and stage log. hm::Error and
// everything else the command throws propagate.
ExecuteResult execute(Invocation& invocation, const ExecuteOptions& options);

// Parses `args` (the words after the program name) and runs them. A parse error becomes a
// UsageError that begins with `where` (the job file it came from).
ExecuteResult execute_args(const std::vector<std::string>& args, const std::string& where,
                           const ExecuteOptions& options);

}  // namespace hm::cli
