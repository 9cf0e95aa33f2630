// Batch manifests: hulls (files or generator settings) and a parameter grid, expanded into jobs
// with stable ids.
//   {"hulls": [{"name": "wigley", "generate": {"kind": "wigley", "length": 100}, "draft": [5, 6]},
//              {"name": "dtmb", "file": "hulls/dtmb5415.iges", "draft": [0.2, 0.25]}],
//    "grid": {"mesher": ["structured", "unstructured"], "panels": [1000, 2000]},
//    "options": {"knuckle-angle": 35, "structured": {"auto-blocks": true}},
//    "formats": ["gdf", "vtu"]}
// Grid and option keys are the meshers' own option names. A hull's other keys replace the grid's
// values for that hull. Relative paths are taken from the manifest's folder.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace hm::cli {

struct BatchHull {
  std::string name;
  std::string file;                        // the IGES file (for a generated hull: where it goes)
  std::optional<nlohmann::json> generate;  // `hullmesh generate` options, kind included
};

struct BatchJob {
  std::string id;  // hull, mesher and grid values: stable whatever the manifest's order
  std::size_t hull = 0;
  std::string mesher;                // "structured" or "unstructured"
  nlohmann::ordered_json point;      // the grid values of this job, key -> value
  nlohmann::ordered_json options;    // every option the job sets (grid values included)
  std::vector<std::string> formats;  // output extensions without the dot, the first written
};

struct Manifest {
  std::string path;
  std::vector<BatchHull> hulls;
  std::vector<std::string> grid_keys;  // in the summary's column order (mesher excluded)
  std::vector<BatchJob> jobs;          // sorted by id
};

// Reads and expands a manifest; generated hulls are placed under `out_dir`/hulls. Throws
// UsageError naming the manifest and the key for a structural fault: an unknown key, a wrong type,
// a mesher option that the mesher does not have, two jobs with one id, more than `max_jobs` jobs.
Manifest read_manifest(const std::string& path, const std::string& out_dir,
                       std::size_t max_jobs = 100'000);

// read_manifest for a manifest already parsed: `path` names it in messages and its folder is where
// relative paths start.
Manifest read_manifest_json(const nlohmann::json& manifest, const std::string& path,
                            const std::string& out_dir, std::size_t max_jobs = 100'000);

// The jobs of shard `k` of `n`: every n-th job of the sorted list, starting at the k-th.
std::vector<std::size_t> shard_jobs(const Manifest& m, std::size_t k, std::size_t n);

// The `hullmesh` words of a job, output excluded: the mesher, the hull file and its options.
std::vector<std::string> job_words(const Manifest& m, const BatchJob& job);

}  // namespace hm::cli
