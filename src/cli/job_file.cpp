#include "cli/job_file.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "cli/execute.h"
#include "cli/run_record.h"
#include "core/error.h"

namespace hm::cli {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// Commands a job may name: the ones that read a hull and write something.
const std::set<std::string> kJobCommands = {"tessellate", "merge",    "unstructured",
                                            "structured", "section",  "convert",
                                            "quality",    "generate", "info"};
const std::set<std::string> kPathKeys = {"file", "output", "blocks"};

// --help is no job key: a job saying "help": true would stop the parser with CLI11's own
// "This should be caught in your main function" as the job's error.
bool is_help(const CLI::Option* opt) {
  const std::string name = opt->get_single_name();
  return name == "help" || name == "h";
}

std::string key_list(const CLI::App& cmd) {
  std::string s;
  for (const CLI::Option* opt : cmd.get_options()) {
    if (!is_help(opt)) s += (s.empty() ? "" : ", ") + opt->get_single_name();
  }
  return s;
}

const CLI::Option* find_option(const CLI::App& cmd, const std::string& key) {
  for (const CLI::Option* opt : cmd.get_options()) {
    if (!is_help(opt) && opt->get_single_name() == key) return opt;
  }
  return nullptr;
}

bool numeric(const CLI::Option* opt) { return option_takes_number(*opt); }

std::string type_name(const json& v) {
  if (v.is_boolean()) return "true/false";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "a list";
  if (v.is_object()) return "an object";
  return "null";
}

std::string scalar_text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// The option names (without dashes) the override words set, and whether they name a file.
void scan_overrides(const CLI::App& cmd, const std::vector<std::string>& words,
                    std::set<std::string>& keys) {
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& w = words[i];
    if (w.size() > 1 && w[0] == '-') {
      const std::string name = w.substr(0, w.find('='));
      const CLI::Option* opt = cmd.get_option_no_throw(name);
      if (!opt) continue;  // the parser reports it
      keys.insert(opt->get_single_name());
      if (opt->get_expected_min() > 0 && w.find('=') == std::string::npos) ++i;
    } else {
      keys.insert("file");
    }
  }
}

}  // namespace

json parse_json_text(std::string_view text, const std::string& where) {
  // Depth is the number of enclosing arrays and objects; stopping at the opening bracket keeps
  // every later copy and dump of the value shallow.
  const auto limit_depth = [&where](int depth, json::parse_event_t event, json&) {
    const bool opens =
        event == json::parse_event_t::object_start || event == json::parse_event_t::array_start;
    if (opens && depth >= kMaxJsonDepth) {
      throw InputError(where + ": not valid JSON: nested deeper than " +
                       std::to_string(kMaxJsonDepth) + " levels");
    }
    return true;
  };
  try {
    return json::parse(text, limit_depth);
  } catch (const json::exception& e) {
    // parse_error for bad syntax, out_of_range for a number beyond a double (1e400).
    throw InputError(where + ": not valid JSON: " + e.what());
  }
}

json read_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path + ": cannot read the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_json_text(ss.str(), path);
}

std::vector<std::string> job_arguments(const json& job, const std::string& where,
                                       const std::string& base_folder,
                                       const std::vector<std::string>& overrides) {
  if (!job.is_object()) throw UsageError(where + ": a job is a JSON object");
  if (!job.contains("command") || !job["command"].is_string()) {
    throw UsageError(where +
                     ": key 'command' (a string) is missing; one of structured, "
                     "unstructured, merge, tessellate, section, convert, quality");
  }
  const std::string command = job["command"];
  if (!kJobCommands.count(command)) {
    throw UsageError(where + ": key 'command': '" + command +
                     "' cannot be a job; one of structured, unstructured, merge, tessellate, "
                     "section, convert, quality, generate, info");
  }
  // The command's own options, as a fresh app declares them.
  auto inv = make_invocation();
  const CLI::App* cmd = inv->app->get_subcommand(command);
  std::set<std::string> overridden;
  scan_overrides(*cmd, overrides, overridden);

  std::vector<std::string> args = {command};
  for (const auto& [raw_key, value] : job.items()) {
    if (raw_key == "command") continue;
    std::string key = raw_key;
    std::replace(key.begin(), key.end(), '_', '-');
    const CLI::Option* opt = find_option(*cmd, key);
    if (!opt) {
      throw UsageError(where + ": unknown key '" + raw_key + "' for " + command +
                       "; allowed: command, " + key_list(*cmd));
    }
    if (overridden.count(key)) continue;
    const std::string what = where + ": key '" + raw_key + "': ";
    const bool flag = opt->get_expected_min() == 0;
    const bool positional = opt->get_lnames().empty() && opt->get_snames().empty();
    const std::string word = positional ? "" : "--" + key;
    auto push = [&](const std::string& text) {
      std::string t = text;
      if (kPathKeys.count(key) && !t.empty() && fs::path(t).is_relative()) {
        t = (fs::path(base_folder) / t).lexically_normal().string();
      }
      if (!word.empty()) args.push_back(word);
      args.push_back(t);
    };
    if (flag) {
      if (!value.is_boolean()) {
        throw UsageError(what + "expected true or false, got " + type_name(value));
      }
      if (value.get<bool>()) args.push_back(word);
      continue;
    }
    if (value.is_boolean() || value.is_null() || value.is_object()) {
      throw UsageError(what + "expected " + (numeric(opt) ? "a number" : "a value") + ", got " +
                       type_name(value));
    }
    if (value.is_string() && numeric(opt)) {
      throw UsageError(what + "expected a number, got a string");
    }
    if (value.is_array()) {
      if (opt->get_items_expected_max() > 1) {  // a repeatable option: one word per element
        for (const json& e : value) push(scalar_text(e));
        continue;
      }
      // A list option such as "size": [dx, dy, dz] is the comma-separated form.
      std::string joined;
      for (const json& e : value) {
        if (!e.is_number()) throw UsageError(what + "a list must hold numbers");
        joined += (joined.empty() ? "" : ",") + e.dump();
      }
      push(joined);
      continue;
    }
    push(scalar_text(value));
  }
  args.insert(args.end(), overrides.begin(), overrides.end());
  return args;
}

}  // namespace hm::cli
