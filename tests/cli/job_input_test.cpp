// Job files and manifests read in process, for what the fuzz targets (tests/fuzz) found: broken
// input must end in a typed hullmesh error, never a library exception, a crash or a silent loss.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli/batch_manifest.h"
#include "cli/job_file.h"
#include "core/error.h"

namespace hm::cli {
namespace {

using nlohmann::json;

// The message of the InputError that `text` raises as a job file, or "" if it raises none.
std::string parse_fault(const std::string& text) {
  try {
    parse_json_text(text, "job.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

Manifest manifest(const std::string& text, std::size_t max_jobs = 1000) {
  return read_manifest_json(parse_json_text(text, "m.json"), "sweeps/m.json", "out", max_jobs);
}

TEST(JobInput, ParsesFromMemoryWithTheNameInFaults) {
  const json job = parse_json_text(R"({"command": "structured", "panels": 200})", "job.json");
  EXPECT_EQ(job["panels"], 200);
  EXPECT_NE(parse_fault(R"({"command": )").find("job.json: not valid JSON"), std::string::npos);
}

// nlohmann reports a number beyond a double as out_of_range, not parse_error: it escaped the
// reader and the CLI called it an internal error (exit 1) instead of bad input (exit 3).
TEST(JobInput, NumberBeyondDoubleIsInputError) {
  EXPECT_NE(parse_fault(R"({"command": "structured", "draft": 1e400})").find("job.json"),
            std::string::npos);
  EXPECT_NE(parse_fault("[-1e999]").find("not valid JSON"), std::string::npos);
}

// Copying or printing a JSON value recurses once per level: a manifest of a few hundred kB of
// '[' overflowed the stack when its grid was expanded.
TEST(JobInput, NestingDeeperThanTheLimitIsInputError) {
  const auto nested = [](int depth) {
    return R"({"x": )" + std::string(depth - 1, '[') + std::string(depth - 1, ']') + "}";
  };
  EXPECT_EQ(parse_fault(nested(kMaxJsonDepth)), "");
  EXPECT_NE(parse_fault(nested(kMaxJsonDepth + 1)).find("nested deeper than"), std::string::npos);
  const std::string deep = R"({"hulls": [{"name": "a", "file": "a.igs", "draft": )" +
                           std::string(500'000, '[') + std::string(500'000, ']') + "}]}";
  EXPECT_THROW(manifest(deep), InputError);
}

// "help" matched the command's --help flag, and the job then failed with CLI11's "This should be
// caught in your main function" instead of naming the unknown key.
TEST(JobInput, HelpIsAnUnknownJobKey) {
  const json job = {{"command", "info"}, {"file", "a.igs"}, {"help", true}};
  try {
    job_arguments(job, "job.json", "", {});
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key 'help'"), std::string::npos) << e.what();
  }
}

TEST(JobInput, ManifestFromMemoryExpandsTheGrid) {
  const Manifest m = manifest(R"({"hulls": [{"name": "a", "file": "a.igs", "draft": [1, 2]}],
                                  "grid": {"mesher": ["structured", "unstructured"]}})");
  ASSERT_EQ(m.jobs.size(), 4u);
  EXPECT_EQ(m.jobs[0].id, "a_structured_draft-1");
  EXPECT_EQ(m.hulls[0].file, "sweeps/a.igs");
}

// 32 keys of 4 values make 4^32 = 2^64 jobs: the product wrapped to 0, passed the job limit and
// the hull silently had no jobs.
TEST(JobInput, GridProductBeyondSizeTIsOverTheLimit) {
  std::string grid;
  for (int k = 0; k < 32; ++k) {
    grid += (k ? ", " : "") + std::string("\"k") + std::to_string(k) + "\": [1, 2, 3, 4]";
  }
  try {
    manifest(R"({"hulls": [{"name": "a", "file": "a.igs"}], "grid": {)" + grid + "}}");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("more than 1000 jobs"), std::string::npos) << e.what();
  }
}

TEST(JobInput, GridOverTheLimitStopsBeforeExpanding) {
  EXPECT_THROW(manifest(R"({"hulls": [{"name": "a", "file": "a.igs", "draft": [1, 2, 3]}],
                            "grid": {"panels": [100, 200]}})",
                        5),
               UsageError);
  EXPECT_EQ(manifest(R"({"hulls": [{"name": "a", "file": "a.igs", "draft": [1, 2, 3]}],
                         "grid": {"panels": [100, 200]}})",
                     6)
                .jobs.size(),
            6u);
}

// An empty mesher list dropped the hull's jobs without a word.
TEST(JobInput, EmptyMesherListIsUsageError) {
  try {
    manifest(R"({"hulls": [{"name": "a", "file": "a.igs"}], "grid": {"mesher": []}})");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("'mesher' has no values"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hm::cli
