// End-to-end tests of job files, run records and batches: what a user running sweeps relies on.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "support/test_json.h"
#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::run_hullmesh;

using test::q;

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// Rows of a summary by id, without the columns that may differ between two runs of one sweep.
std::map<std::string, json> comparable_rows(const fs::path& summary) {
  std::map<std::string, json> rows;
  // Named: a range-for over test::read_json(...)["rows"] would walk a destroyed temporary.
  const json s = test::read_json(summary);
  for (json row : s["rows"]) {
    row.erase("seconds");
    row.erase("reused");
    rows[row["id"]] = row;
  }
  return rows;
}

// Finished jobs' records: NAME.run.json, not a temporary ".NAME.run.json.tmp.PID.N" being written.
std::size_t count_records(const fs::path& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    n += name[0] != '.' && name.size() > 9 && name.substr(name.size() - 9) == ".run.json" ? 1 : 0;
  }
  return n;
}

std::size_t count_files(const fs::path& dir, const std::string& part) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    n += e.path().filename().string().find(part) != std::string::npos ? 1 : 0;
  }
  return n;
}

// A small sweep of generated hulls: 2 hulls x 2 drafts x 2 meshers = 8 jobs.
std::string small_manifest(int panels = 150) {
  const std::string p = std::to_string(panels);
  return R"({
  "hulls": [
    {"name": "wigley", "generate": {"kind": "wigley", "length": 50, "beam": 5, "depth": 4,
      "draft": 3, "patches": 2}, "draft": [2.5, 3]},
    {"name": "chine", "generate": {"kind": "chine", "length": 40, "beam": 8, "depth": 4,
      "draft": 2, "patches": 4}, "draft": [1.8, 2.2]}
  ],
  "grid": {"mesher": ["structured", "unstructured"], "panels": [)" +
         p + R"(]},
  "formats": ["gdf", "obj"]
})";
}

TEST(CliRun, JobFileRunsAndTheCommandLineOverridesIt) {
  const fs::path dir = test::scratch_dir("cli_run_job");
  ASSERT_EQ(run_hullmesh("-q generate wigley --patches 2 -o " + q(dir / "w.igs")).exit_code, 0);
  // Relative paths in a job file are the job file's own folder's.
  write_text(dir / "job.json",
             R"({"command": "structured", "file": "w.igs", "output": "panels.gdf",
                 "panels": 200, "draft": 5, "auto_blocks": true})");
  const auto r = run_hullmesh("-q run " + q(dir / "job.json"));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  const json rec = test::read_json(dir / "panels.run.json");
  ASSERT_FALSE(rec.is_discarded());
  EXPECT_EQ(rec["command"], "structured");
  EXPECT_EQ(rec["parameters"]["panels"], 200);
  EXPECT_EQ(rec["parameters"]["draft"], 5.0);
  EXPECT_EQ(rec["parameters"]["auto-blocks"], true);
  EXPECT_EQ(rec["input"]["sha256"].get<std::string>().size(), 64u);
  EXPECT_EQ(rec["outputs"][0]["bytes"].get<std::uintmax_t>(), fs::file_size(dir / "panels.gdf"));
  EXPECT_GT(rec["quality"]["panels"].get<int>(), 100);

  const auto o =
      run_hullmesh("-q run " + q(dir / "job.json") + " --panels 600 -o " + q(dir / "more.gdf"));
  ASSERT_EQ(o.exit_code, 0) << o.out;
  const json more = test::read_json(dir / "more.run.json");
  EXPECT_EQ(more["parameters"]["panels"], 600);
  EXPECT_EQ(more["input"]["sha256"], rec["input"]["sha256"]);
  EXPECT_GT(more["quality"]["panels"].get<int>(), 2 * rec["quality"]["panels"].get<int>());
}

TEST(CliRun, JobFileErrorsNameTheKeyAndWhatIsAllowed) {
  const fs::path dir = test::scratch_dir("cli_run_errors");
  struct Case {
    const char* job;
    const char* expect;
  };
  for (const Case& c : {
           Case{R"({"command": "structured", "file": "w.igs", "output": "x.gdf", "panel": 5})",
                "unknown key 'panel' for structured; allowed: command, file, output"},
           Case{R"({"command": "structured", "file": "w.igs", "output": "x.gdf", "panels": "9"})",
                "key 'panels': expected a number, got a string"},
           Case{R"({"command": "structured", "file": "w.igs", "output": "x.gdf", "panels": 2})",
                "key 'panels': Value 2 not in range 4 to"},
           Case{R"({"command": "unstructured", "file": "w.igs", "output": "x.gdf",
                    "serial": "yes"})",
                "key 'serial': expected true or false"},
           Case{R"({"command": "batch"})", "key 'command': 'batch' cannot be a job"},
           Case{R"({"file": "w.igs"})", "key 'command' (a string) is missing"},
       }) {
    write_text(dir / "job.json", c.job);
    const auto r = run_hullmesh("run " + q(dir / "job.json"));
    EXPECT_EQ(r.exit_code, 2) << c.job << "\n" << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("job.json"), std::string::npos) << r.out;
  }
}

TEST(CliRunRecord, MeshersRecordEveryParameterStagesAndQuality) {
  const fs::path dir = test::scratch_dir("cli_run_record");
  ASSERT_EQ(run_hullmesh("-q generate chine --patches 4 -o " + q(dir / "c.igs")).exit_code, 0);
  const auto r = run_hullmesh("unstructured " + q(dir / "c.igs") + " -o " + q(dir / "u.vtu") +
                              " --panels 300 --draft 2");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  // Not a terminal: each stage ends with a plain log line.
  EXPECT_NE(r.out.find("hullmesh: coarsen done in"), std::string::npos) << r.out;
  const json rec = test::read_json(dir / "u.run.json");
  ASSERT_FALSE(rec.is_discarded());
  // Options not given carry their defaults.
  EXPECT_EQ(rec["parameters"]["panels"], 300);
  EXPECT_TRUE(rec["parameters"].contains("knuckle-angle"));
  EXPECT_TRUE(rec["parameters"]["knuckle-angle"].is_number());
  EXPECT_EQ(rec["parameters"]["serial"], false);
  std::set<std::string> stages;
  double sum = 0;
  for (const json& s : rec["stages"]) {
    stages.insert(s["name"].get<std::string>());
    sum += s["seconds"].get<double>();
  }
  for (const char* s : {"import", "tessellate", "merge", "features", "coarsen", "report", "write"})
    EXPECT_TRUE(stages.count(s)) << s;
  EXPECT_NEAR(rec["seconds"].get<double>(), sum, 1e-9);
  EXPECT_NEAR(rec["quality"]["panels"].get<int>(), 300, 3);
  EXPECT_LT(std::abs(rec["results"]["hydrostatics"]["volume_error"].get<double>()), 0.02);
  // The other commands that write meshes from a hull keep records too.
  ASSERT_EQ(run_hullmesh("-q merge " + q(dir / "c.igs") + " -o " + q(dir / "m.vtu")).exit_code, 0);
  const json merged = test::read_json(dir / "m.run.json");
  ASSERT_EQ(merged["outputs"].size(), 3u);  // the surface, its knuckles and its boundaries
  EXPECT_GT(merged["results"]["knuckle_lines"].get<int>(), 0);
  ASSERT_EQ(run_hullmesh("-q tessellate " + q(dir / "c.igs") + " -o " + q(dir / "t.vtu")).exit_code,
            0);
  EXPECT_GT(test::read_json(dir / "t.run.json")["results"]["triangles"].get<int>(), 100);
  // --no-run-json leaves the record out.
  ASSERT_EQ(run_hullmesh("-q --no-run-json structured " + q(dir / "c.igs") + " -o " +
                         q(dir / "s.gdf") + " --panels 100")
                .exit_code,
            0);
  EXPECT_TRUE(fs::exists(dir / "s.gdf"));
  EXPECT_FALSE(fs::exists(dir / "s.run.json"));
}

TEST(CliBatch, SweepRerunsNothingAndRedoesExactlyADeletedOutput) {
  const fs::path dir = test::scratch_dir("cli_batch_resume");
  write_text(dir / "sweep.json", small_manifest());
  const fs::path out = dir / "out";
  const std::string cmd = "batch " + q(dir / "sweep.json") + " --out " + q(out);
  const auto list = run_hullmesh("-q " + cmd + " --list");
  ASSERT_EQ(list.exit_code, 0) << list.out;
  EXPECT_NE(list.out.find("chine_structured_draft-1.8_panels-150\n"), std::string::npos);
  const auto first = run_hullmesh(cmd);
  ASSERT_EQ(first.exit_code, 0) << first.out;
  const json s1 = test::read_json(out / "summary.json");
  ASSERT_EQ(s1["rows"].size(), 8u);
  EXPECT_EQ(s1["ok"], 8);
  EXPECT_EQ(count_files(out, ".gdf"), 8u);
  EXPECT_EQ(count_files(out, ".obj"), 8u);
  EXPECT_EQ(count_files(out, ".run.json"), 8u);
  std::ifstream csv(out / "summary.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("id,hull,mesher,draft,panels,status,error,seconds,reused,mesh_panels", 0),
            0u)
      << header;

  const auto stamp = fs::last_write_time(out / "wigley_unstructured_draft-3_panels-150.gdf");
  const auto again = run_hullmesh(cmd);
  ASSERT_EQ(again.exit_code, 0) << again.out;
  EXPECT_EQ(test::read_json(out / "summary.json")["reused"], 8);
  EXPECT_EQ(fs::last_write_time(out / "wigley_unstructured_draft-3_panels-150.gdf"), stamp);
  EXPECT_EQ(comparable_rows(out / "summary.json"), comparable_rows(dir / "out" / "summary.json"));

  fs::remove(out / "chine_unstructured_draft-2.2_panels-150.obj");
  const auto redo = run_hullmesh(cmd);
  ASSERT_EQ(redo.exit_code, 0) << redo.out;
  const json s3 = test::read_json(out / "summary.json");
  EXPECT_EQ(s3["reused"], 7);
  for (const json& row : s3["rows"]) {
    EXPECT_EQ(row["reused"].get<bool>(), row["id"] != "chine_unstructured_draft-2.2_panels-150")
        << row["id"];
  }
  EXPECT_TRUE(fs::exists(out / "chine_unstructured_draft-2.2_panels-150.obj"));
}

TEST(CliBatch, BrokenEntriesFailAloneWithTheirErrors) {
  const fs::path dir = test::scratch_dir("cli_batch_broken");
  write_text(dir / "corrupt.igs", "this is not an IGES file\n");
  write_text(dir / "sweep.json", R"({
  "hulls": [
    {"name": "good", "generate": {"kind": "wigley", "length": 50, "beam": 5, "depth": 4,
      "draft": 3, "patches": 2}, "draft": [3, 9]},
    {"name": "missing", "file": "no/such/hull.igs", "draft": 1},
    {"name": "corrupt", "file": "corrupt.igs", "draft": 1}
  ],
  "grid": {"panels": 150}
})");
  const auto r = run_hullmesh("batch " + q(dir / "sweep.json") + " --out " + q(dir / "out"));
  EXPECT_EQ(r.exit_code, 8) << r.out;
  const json s = test::read_json(dir / "out" / "summary.json");
  ASSERT_EQ(s["rows"].size(), 4u);
  EXPECT_EQ(s["ok"], 1);
  EXPECT_EQ(s["failed"], 3);
  std::map<std::string, std::string> error;
  for (const json& row : s["rows"]) error[row["id"]] = row["error"];
  EXPECT_EQ(error["good_structured_draft-3_panels-150"], "");
  EXPECT_NE(error["good_structured_draft-9_panels-150"].find("highest point"), std::string::npos);
  EXPECT_NE(error["missing_structured_draft-1_panels-150"].find("no/such/hull.igs"),
            std::string::npos);
  EXPECT_NE(error["corrupt_structured_draft-1_panels-150"].find("corrupt.igs"), std::string::npos);
  EXPECT_NE(r.out.find("FAILED corrupt_structured_draft-1_panels-150"), std::string::npos);

  // A misspelt option stops the batch before anything runs, naming the key.
  write_text(dir / "typo.json", R"({"hulls": [{"name": "a", "file": "corrupt.igs"}],
                                   "grid": {"panel": [1]}})");
  const auto t = run_hullmesh("batch " + q(dir / "typo.json") + " --out " + q(dir / "out2"));
  EXPECT_EQ(t.exit_code, 2) << t.out;
  EXPECT_NE(t.out.find("unknown key 'panel'"), std::string::npos) << t.out;
}

TEST(CliBatch, ShardsMergeToTheSingleMachineRunByteForByte) {
  const fs::path dir = test::scratch_dir("cli_batch_shards");
  write_text(dir / "sweep.json", small_manifest());
  const std::string manifest = q(dir / "sweep.json");
  for (int k = 0; k < 3; ++k) {
    const auto r = run_hullmesh("-q --threads 1 batch " + manifest + " --out " +
                                q(dir / "sharded") + " --shard " + std::to_string(k) + "/3");
    ASSERT_EQ(r.exit_code, 0) << r.out;
  }
  const auto m =
      run_hullmesh("-q batch " + manifest + " --out " + q(dir / "sharded") + " --merge-shards 3");
  ASSERT_EQ(m.exit_code, 0) << m.out;
  const auto one = run_hullmesh("-q --threads 2 batch " + manifest + " --out " + q(dir / "one"));
  ASSERT_EQ(one.exit_code, 0) << one.out;
  EXPECT_EQ(comparable_rows(dir / "sharded" / "summary.json"),
            comparable_rows(dir / "one" / "summary.json"));
  // 1 thread per shard against 2 threads in one run: the same bytes.
  for (const auto& e : fs::directory_iterator(dir / "one")) {
    const std::string name = e.path().filename().string();
    if (name.size() < 9 || name.substr(name.size() - 9) != ".run.json") continue;
    const json a = test::read_json(e.path()), b = test::read_json(dir / "sharded" / name);
    ASSERT_FALSE(b.is_discarded()) << name;
    for (std::size_t k = 0; k < a["outputs"].size(); ++k) {
      EXPECT_EQ(a["outputs"][k]["sha256"], b["outputs"][k]["sha256"]) << name;
    }
  }
  // A shard that did not run is named.
  const auto missing =
      run_hullmesh("-q batch " + manifest + " --out " + q(dir / "one") + " --merge-shards 2");
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.out.find("shard 0 of 2 has no summary"), std::string::npos) << missing.out;
}

void interrupt_and_resume(int signal_number, const std::string& name) {
  const fs::path dir = test::scratch_dir(name);
  // 4 hulls x 2 drafts x 2 meshers = 16 jobs of a few tenths of a second on one thread.
  std::string manifest = small_manifest(250);
  manifest.replace(manifest.find("\"hulls\": ["), 10,
                   R"("hulls": [
    {"name": "w2", "generate": {"kind": "wigley", "patches": 3}, "draft": [5, 6]},
    {"name": "c2", "generate": {"kind": "round-bilge", "patches": 4}, "draft": [5, 6]},)");
  write_text(dir / "sweep.json", manifest);
  const fs::path out = dir / "out";
  const std::string cmd = "--threads 1 batch " + q(dir / "sweep.json") + " --out " + q(out);
  const pid_t pid = test::spawn_hullmesh(cmd, dir / "log.txt");
  ASSERT_GT(pid, 0);
  // Strike once the first job has finished and others are under way.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < deadline &&
         (!fs::exists(out) || count_records(out) < 1)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(kill(pid, signal_number), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  std::stringstream log;
  log << std::ifstream(dir / "log.txt").rdbuf();
  if (signal_number == SIGINT) {
    // Stopped cleanly: running jobs finished, nothing half-written, a summary of what ran.
    ASSERT_TRUE(WIFEXITED(status)) << log.str();
    EXPECT_EQ(WEXITSTATUS(status), 130) << log.str();
    EXPECT_EQ(count_files(out, ".tmp."), 0u);
    const json s = test::read_json(out / "summary.json");
    EXPECT_GT(s["not_run"].get<int>(), 0) << log.str();
  } else {
    ASSERT_TRUE(WIFSIGNALED(status));
  }
  const std::size_t done_before = count_records(out);
  ASSERT_LT(done_before, 16u) << "the batch finished before the signal; nothing was tested";

  const auto resumed = run_hullmesh("-q " + cmd);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.out;
  const json s = test::read_json(out / "summary.json");
  EXPECT_EQ(s["ok"], 16);
  EXPECT_EQ(s["reused"].get<std::size_t>(), done_before);  // nothing lost
  EXPECT_EQ(count_files(out, ".tmp."), 0u);
  // Every output is the one its record names (a third run re-checks each hash).
  const auto check = run_hullmesh("-q " + cmd);
  ASSERT_EQ(check.exit_code, 0) << check.out;
  EXPECT_EQ(test::read_json(out / "summary.json")["reused"], 16);
}

TEST(CliBatch, SigintStopsCleanlyAndTheRestResumes) {
  interrupt_and_resume(SIGINT, "cli_batch_sigint");
}

TEST(CliBatch, SigkillLosesNothingAndTheRestResumes) {
  interrupt_and_resume(SIGKILL, "cli_batch_sigkill");
}

}  // namespace
}  // namespace hm
