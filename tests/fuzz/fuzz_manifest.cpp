// libFuzzer target for batch manifests (`hullmesh batch MANIFEST`): the input is the file's bytes.
// It is parsed and expanded into jobs, and each job's words are built as the batch builds them
// (job ids and records), short of running anything. A small job limit keeps a big grid cheap while
// still exercising the count check. Typed hullmesh errors are the expected answer to a broken
// manifest; anything else, a crash, an escaping std::exception, a hang or an unbounded allocation
// is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "cli/batch_manifest.h"
#include "cli/job_file.h"
#include "core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kMaxJobs = 1000;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto m = hm::cli::read_manifest_json(hm::cli::parse_json_text(text, "fuzz.json"),
                                               "sweeps/fuzz.json", "out", kMaxJobs);
    if (m.jobs.size() > kMaxJobs) __builtin_trap();
    // Shards as `--shard K/N` picks them: together they hold every job once.
    std::size_t sharded = 0;
    for (std::size_t k = 0; k < 3; ++k) sharded += hm::cli::shard_jobs(m, k, 3).size();
    if (sharded != m.jobs.size()) __builtin_trap();
    for (const hm::cli::BatchJob& job : m.jobs) hm::cli::job_words(m, job);
    // Generated hulls become `hullmesh generate` words before the jobs run.
    for (const hm::cli::BatchHull& h : m.hulls) {
      if (!h.generate) continue;
      nlohmann::json spec = *h.generate;
      spec["command"] = "generate";
      spec["output"] = h.file;
      hm::cli::job_arguments(spec, "fuzz.json: hull " + h.name, "", {});
    }
  } catch (const hm::Error&) {
    // Typed errors are the expected outcome for a broken manifest.
  }
  return 0;
}
