// Running a batch: every job of a manifest (or of one shard of it) in parallel, each job's own
// parallelism nested inside without oversubscribing; resumable, interruptible, summarised.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/batch_manifest.h"
#include "cli/run_log.h"

namespace hm::cli {

struct BatchOptions {
  std::string out_dir;
  std::size_t shard = 0, shards = 1;  // run shard `shard` of `shards`
  bool sharded = false;               // --shard given: the summary is the shard's (even for 0/1)
  bool rerun = false;                 // ignore finished jobs' records and run everything again
  RunLog::Mode display = RunLog::Mode::kLines;
  bool verbose = false;   // print each job's command line as it starts
  bool validate = false;  // --validate for every job
};

struct BatchResult {
  std::size_t ok = 0, failed = 0, reused = 0, not_run = 0;
  bool interrupted = false;                  // SIGINT or SIGTERM stopped it early
  std::vector<nlohmann::ordered_json> rows;  // one per job of the shard, sorted by id
};

// Generates the manifest's generated hulls, runs the shard's jobs (skipping those whose outputs
// and `*.run.json` match), and writes the summary (summary.json and .csv, or
// summary.shard-K-of-N.*). A failed job is recorded with its error and the batch goes on.
BatchResult run_batch(const Manifest& manifest, const BatchOptions& options);

// Combines the summaries of shards 0..n-1 in `out_dir` into summary.json and .csv. Throws
// UsageError naming a missing shard, or a job the shards lack or repeat.
BatchResult merge_shards(const Manifest& manifest, const std::string& out_dir, std::size_t n);

}  // namespace hm::cli
