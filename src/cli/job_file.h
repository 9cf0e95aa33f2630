// Job files: a meshing command written as JSON, with the command-line options' own names.
//   {"command": "structured", "file": "hull.igs", "output": "panels.gdf", "panels": 2000,
//    "draft": 6.2, "auto-blocks": true}
// Relative paths under "file", "output" and "blocks" are taken from the job file's folder.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace hm::cli {

// The command line (words after the program name) that `job` stands for, with `overrides`
// (words typed after the job file) appended; an option given there replaces the file's key, and a
// bare word replaces "file". Throws UsageError beginning with `where` for an unknown command or
// key (listing the allowed ones), a value of the wrong type, or a command that cannot be a job.
std::vector<std::string> job_arguments(const nlohmann::json& job, const std::string& where,
                                       const std::string& base_folder,
                                       const std::vector<std::string>& overrides);

// Deepest nesting of arrays and objects a job file or manifest may have. Copying and printing a
// JSON value recurse once per level, so a deeper file could overflow the stack; real ones need 4.
inline constexpr int kMaxJsonDepth = 64;

// Parses the text of a job file or manifest; InputError beginning with `where` (the file) for a
// JSON fault or nesting deeper than kMaxJsonDepth.
nlohmann::json parse_json_text(std::string_view text, const std::string& where);

// Reads and parses a job file (parse_json_text); IoError if it cannot be read.
nlohmann::json read_json_file(const std::string& path);

}  // namespace hm::cli
