// hullmesh batch MANIFEST --out DIR [--shard K/N | --merge-shards N]: every job of a manifest
// (hulls x parameter grid), in parallel, resumable; a summary table of the results.
#include <cstdio>

#include "cli/batch_manifest.h"
#include "cli/commands.h"
#include "cli/run_batch.h"
#include "cli/run_log.h"
#include "core/error.h"

namespace hm::cli {
namespace {

// Exit code of a batch with failed jobs (the good ones are done and summarised).
constexpr int kJobsFailed = 8;
// Interrupted by SIGINT or SIGTERM (128 + SIGINT, as shells report it).
constexpr int kInterrupted = 130;

struct BatchCommand {
  std::string manifest, out, shard;
  std::size_t merge = 0;
  bool list = false, rerun = false;
};

void parse_shard(const std::string& text, BatchOptions& o) {
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument(text);
    std::size_t used = 0;
    o.shard = std::stoul(text.substr(0, slash), &used);
    o.shards = std::stoul(text.substr(slash + 1));
  } catch (const std::exception&) {
    throw UsageError("--shard " + text + ": expected K/N, for example 0/4");
  }
  if (o.shards == 0 || o.shard >= o.shards || o.shards > 100'000) {
    throw UsageError("--shard " + text + ": need 0 <= K < N <= 100000");
  }
  o.sharded = true;
}

int run_batch_command(const BatchCommand& c, const GlobalOptions& g) {
  const Manifest m = read_manifest(c.manifest, c.out);
  if (c.list) {
    for (const BatchJob& job : m.jobs) std::printf("%s\n", job.id.c_str());
    return 0;
  }
  BatchResult r;
  const char* what = "";
  if (c.merge > 0) {
    r = merge_shards(m, c.out, c.merge);
    what = "merged";
  } else {
    BatchOptions o;
    o.out_dir = c.out;
    o.rerun = c.rerun;
    if (!c.shard.empty()) parse_shard(c.shard, o);
    o.display = RunLog::mode_for(g.quiet);
    o.verbose = g.verbose && !g.quiet;
    o.validate = g.validate;
    r = run_batch(m, o);
    what = r.interrupted ? "interrupted" : "done";
  }
  if (!g.quiet) {
    std::printf(
        "%s: %zu jobs %s: %zu ok (%zu done before), %zu failed, %zu not run; summary in %s\n",
        c.manifest.c_str(), r.rows.size(), what, r.ok, r.reused, r.failed, r.not_run,
        c.out.c_str());
    for (const auto& row : r.rows) {
      if (row["status"] == "failed") {
        std::printf("  FAILED %s: %s\n", row["id"].get<std::string>().c_str(),
                    row["error"].get<std::string>().c_str());
      }
    }
  }
  if (r.interrupted) return kInterrupted;
  return r.failed > 0 || r.not_run > 0 ? kJobsFailed : 0;
}

}  // namespace

void register_batch(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto c = std::make_shared<BatchCommand>();
  CLI::App* cmd = app.add_subcommand(
      "batch",
      "Run every job of a manifest (hulls x drafts x meshers x panel counts ...) in parallel, "
      "resumably, with a summary table");
  cmd->add_option("manifest", c->manifest, "JSON manifest")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", c->out, "Output folder")->required();
  cmd->add_option("--shard", c->shard, "Run share K of N (0 <= K < N), for cluster job arrays");
  cmd->add_option("--merge-shards", c->merge, "Combine the summaries of N shards in --out into one")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100'000}));
  cmd->add_flag("--list", c->list, "Print the job ids and stop");
  cmd->add_flag("--rerun", c->rerun, "Run every job again, even those already done");
  cmd->callback(
      [c, &global, &action] { action = [c, &global] { return run_batch_command(*c, global); }; });
}

}  // namespace hm::cli
