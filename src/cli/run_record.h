// The small `*.run.json` every output mesh is accompanied by: hullmesh's version, the input's
// SHA-256, every option with its effective value, the time per stage, and the quality summary;
// enough to reproduce the mesh and to judge it without opening it. Batches read it back to
// decide whether a job is done.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/run_log.h"
#include "quality/hydrostatics.h"
#include "quality/quality_report.h"

namespace hm::cli {

// Filled by a command as it runs; GlobalOptions::record points at the current one.
struct RunRecord {
  explicit RunRecord(RunLog::Mode mode) : log(mode) {}
  RunLog log;
  std::string command;               // "structured", "unstructured", ...
  std::string input;                 // the file read, as given
  std::vector<std::string> outputs;  // the files written, the mesh first
  nlohmann::ordered_json parameters = nlohmann::ordered_json::object();  // option -> value
  nlohmann::ordered_json results = nlohmann::ordered_json::object();     // counts, sizes, figures
  nlohmann::ordered_json quality;                                        // null when not measured
};

// Whether the option's value is a number (so JSON holds it as one).
bool option_takes_number(const CLI::Option& opt);

// Every option of a parsed command with its effective value: what was given, else the default
// (null when the option has none). Flags are booleans; numbers are numbers.
nlohmann::ordered_json effective_options(const CLI::App& command);

// The quality report's headline figures (not its per-face arrays or worst list).
nlohmann::ordered_json quality_summary(const QualityReport& report, const QualityRules& rules);
// Displaced volume, wetted and waterplane area and LCB of the panels, and their relative error
// against the NURBS when `exact` is given.
nlohmann::ordered_json hydrostatics_summary(const Hydrostatics& mesh, const Hydrostatics* exact);

// {path, bytes, sha256} of a file; IoError when it cannot be read.
nlohmann::ordered_json file_record(const std::string& path);

// `dir/stem.run.json` for output `dir/stem.ext`.
std::string record_path_for(const std::string& output);
// The record as written: version, command, input {path, sha256, bytes}, parameters, outputs
// [{path, bytes, sha256}], stages [{name, seconds}], results, quality. Reads the files it hashes;
// throws IoError when one is missing.
nlohmann::ordered_json record_json(const RunRecord& record);
// Writes `built` (record_json() of the record) atomically beside the first output (nothing when
// there is none).
void write_run_record(const RunRecord& record, const nlohmann::ordered_json& built);

}  // namespace hm::cli
