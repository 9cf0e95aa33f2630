#include "cli/batch_manifest.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "cli/job_file.h"
#include "core/error.h"

namespace hm::cli {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;
namespace fs = std::filesystem;

const std::set<std::string> kMeshers = {"structured", "unstructured"};
const std::set<std::string> kTopKeys = {"hulls", "grid", "options", "formats"};
const std::set<std::string> kHullKeys = {"name", "file", "generate", "options"};

// A grid axis: a list of values, or one value standing for a list of one.
std::vector<json> axis_values(const json& v) {
  if (v.is_array()) return std::vector<json>(v.begin(), v.end());
  return {v};
}

std::string id_text(const json& v) {
  std::string s = v.is_string() ? v.get<std::string>() : v.dump();
  for (char& ch : s) {
    const bool keep = std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-';
    if (!keep) ch = '-';
  }
  return s;
}

// Option keys for one mesher: the manifest's, then the hull's; a nested object under a mesher's
// name applies to that mesher only.
void add_options(const json& options, const std::string& mesher, const std::string& where,
                 ordered_json& out) {
  if (options.is_null()) return;
  if (!options.is_object()) throw UsageError(where + ": 'options' must be an object");
  for (const auto& [key, value] : options.items()) {
    if (kMeshers.count(key)) {
      if (!value.is_object()) throw UsageError(where + ": 'options." + key + "' must be an object");
      if (key == mesher) {
        for (const auto& [k, v] : value.items()) out[k] = v;
      }
      continue;
    }
    out[key] = value;
  }
}

}  // namespace

Manifest read_manifest(const std::string& path, const std::string& out_dir, std::size_t max_jobs) {
  return read_manifest_json(read_json_file(path), path, out_dir, max_jobs);
}

Manifest read_manifest_json(const json& m, const std::string& path, const std::string& out_dir,
                            std::size_t max_jobs) {
  Manifest result;
  result.path = path;
  if (!m.is_object()) throw UsageError(path + ": a manifest is a JSON object");
  for (const auto& [key, value] : m.items()) {
    if (!kTopKeys.count(key)) {
      throw UsageError(path + ": unknown key '" + key +
                       "'; allowed: hulls, grid, options, formats");
    }
  }
  const fs::path base = fs::path(path).parent_path();
  if (!m.contains("hulls") || !m["hulls"].is_array() || m["hulls"].empty()) {
    throw UsageError(path + ": 'hulls' must be a non-empty list");
  }
  const json grid = m.value("grid", json::object());
  if (!grid.is_object()) throw UsageError(path + ": 'grid' must be an object");
  std::vector<std::string> formats = {"gdf"};
  if (m.contains("formats")) {
    const json& f = m["formats"];
    if (!f.is_array() || f.empty()) throw UsageError(path + ": 'formats' must be a non-empty list");
    formats.clear();
    for (const json& e : f) {
      if (!e.is_string()) throw UsageError(path + ": 'formats' holds extensions such as \"gdf\"");
      std::string ext = e.get<std::string>();
      if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
      formats.push_back(ext);
    }
  }

  std::set<std::string> names;
  for (std::size_t h = 0; h < m["hulls"].size(); ++h) {
    const json& hull = m["hulls"][h];
    const std::string where = path + ": hulls[" + std::to_string(h) + "]";
    if (!hull.is_object() || !hull.contains("name") || !hull["name"].is_string()) {
      throw UsageError(where + ": each hull needs a 'name'");
    }
    BatchHull bh;
    bh.name = hull["name"];
    if (bh.name.empty() || id_text(bh.name) != bh.name) {
      throw UsageError(where + ": name '" + bh.name + "' may hold only letters, digits, '.', '-'");
    }
    if (!names.insert(bh.name).second) throw UsageError(where + ": name '" + bh.name + "' twice");
    const bool has_file = hull.contains("file"), has_gen = hull.contains("generate");
    if (has_file == has_gen) throw UsageError(where + ": give either 'file' or 'generate'");
    if (has_file) {
      if (!hull["file"].is_string()) throw UsageError(where + ": 'file' must be a string");
      const fs::path f = hull["file"].get<std::string>();
      bh.file = (f.is_relative() ? base / f : f).lexically_normal().string();
    } else {
      if (!hull["generate"].is_object() || !hull["generate"].contains("kind")) {
        throw UsageError(where + ": 'generate' is an object with at least 'kind'");
      }
      bh.generate = hull["generate"];
      bh.file = (fs::path(out_dir) / "hulls" / (bh.name + ".igs")).string();
    }
    result.hulls.push_back(bh);

    // The grid for this hull: the manifest's axes, with the hull's own keys replacing them.
    std::map<std::string, std::vector<json>> axes;
    for (const auto& [key, value] : grid.items()) axes[key] = axis_values(value);
    for (const auto& [key, value] : hull.items()) {
      if (!kHullKeys.count(key)) axes[key] = axis_values(value);
    }
    std::vector<std::string> meshers = {"structured"};
    if (axes.count("mesher")) {
      meshers.clear();
      for (const json& v : axes["mesher"]) {
        if (!v.is_string() || !kMeshers.count(v.get<std::string>())) {
          throw UsageError(where + ": 'mesher' values are \"structured\" or \"unstructured\"");
        }
        meshers.push_back(v);
      }
      // An empty list would drop the hull's jobs without a word.
      if (meshers.empty()) throw UsageError(where + ": grid key 'mesher' has no values");
      axes.erase("mesher");
    }
    for (const auto& [key, values] : axes) {
      if (values.empty()) throw UsageError(where + ": grid key '" + key + "' has no values");
      if (std::find(result.grid_keys.begin(), result.grid_keys.end(), key) ==
          result.grid_keys.end()) {
        result.grid_keys.push_back(key);
      }
    }
    // The cartesian product, keys in name order. Its size is checked one factor at a time, before
    // any job exists: 32 keys of 4 values each would wrap a 64-bit product to 0.
    std::vector<std::pair<std::string, std::vector<json>>> ordered(axes.begin(), axes.end());
    const std::size_t room = max_jobs - std::min(max_jobs, result.jobs.size());
    const auto too_many = [&] {
      return UsageError(path + ": more than " + std::to_string(max_jobs) + " jobs");
    };
    std::size_t count = meshers.size();
    if (count > room) throw too_many();
    for (const auto& [key, values] : ordered) {
      if (values.size() > room / count) throw too_many();
      count *= values.size();
    }
    for (const std::string& mesher : meshers) {
      std::vector<std::size_t> at(ordered.size(), 0);
      for (std::size_t n = 0; n < count / meshers.size(); ++n) {
        BatchJob job;
        job.hull = result.hulls.size() - 1;
        job.mesher = mesher;
        job.formats = formats;
        job.id = bh.name + "_" + mesher;
        add_options(m.value("options", json()), mesher, path, job.options);
        add_options(hull.value("options", json()), mesher, where, job.options);
        for (std::size_t a = 0; a < ordered.size(); ++a) {
          const json& v = ordered[a].second[at[a]];
          job.point[ordered[a].first] = v;
          job.options[ordered[a].first] = v;
          job.id += "_" + ordered[a].first + "-" + id_text(v);
        }
        // Validates the keys and types now, so that a misspelt option stops the batch before
        // anything runs (values out of range fail their jobs when they run).
        json spec = job.options;
        spec["command"] = mesher;
        spec["file"] = bh.file;
        spec["output"] = "x.gdf";
        job_arguments(spec, where + " (" + job.id + ")", "", {});
        result.jobs.push_back(std::move(job));
        for (std::size_t a = ordered.size(); a-- > 0;) {  // the next point, last key fastest
          if (++at[a] < ordered[a].second.size()) break;
          at[a] = 0;
        }
      }
    }
  }
  std::sort(result.jobs.begin(), result.jobs.end(),
            [](const BatchJob& a, const BatchJob& b) { return a.id < b.id; });
  for (std::size_t i = 1; i < result.jobs.size(); ++i) {
    if (result.jobs[i].id == result.jobs[i - 1].id) {
      throw UsageError(path + ": two jobs have the id " + result.jobs[i].id);
    }
  }
  return result;
}

std::vector<std::size_t> shard_jobs(const Manifest& m, std::size_t k, std::size_t n) {
  std::vector<std::size_t> jobs;
  for (std::size_t i = k; i < m.jobs.size(); i += n) jobs.push_back(i);
  return jobs;
}

std::vector<std::string> job_words(const Manifest& m, const BatchJob& job) {
  json spec = job.options;
  spec["command"] = job.mesher;
  spec["file"] = m.hulls[job.hull].file;
  return job_arguments(spec, m.path + " (" + job.id + ")", "", {});
}

}  // namespace hm::cli
