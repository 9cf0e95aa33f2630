// libFuzzer target for job files (`hullmesh run JOB.json`): the input is the file's bytes. It is
// parsed, turned into a command line, with and without override words, and that line is parsed as
// execute_args() parses it, short of running the command. Typed hullmesh errors and CLI11 parse
// errors (which execute_args turns into UsageError) are the expected answers to a broken job;
// anything else, a crash, an escaping std::exception, a hang or an unbounded allocation is a
// finding.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cli/execute.h"
#include "cli/job_file.h"
#include "core/error.h"

namespace {

// Words typed after the job file: a bare file, an option with `=` and one with its value apart.
const std::vector<std::string> kOverrides = {"other.igs", "--output=o.gdf", "--draft", "1.5"};

void parse_only(const std::vector<std::string>& args) {
  auto inv = hm::cli::make_invocation();
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes the last first
  try {
    inv->app->parse(reversed);
  } catch (const CLI::ParseError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json job = hm::cli::parse_json_text(text, "fuzz.json");
    parse_only(hm::cli::job_arguments(job, "fuzz.json", "jobs", {}));
    parse_only(hm::cli::job_arguments(job, "fuzz.json", "jobs", kOverrides));
  } catch (const hm::Error&) {
    // Typed errors are the expected outcome for a broken job.
  }
  return 0;
}
