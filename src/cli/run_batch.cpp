#include "cli/run_batch.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>

#include "cli/execute.h"
#include "cli/job_file.h"
#include "cli/run_record.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/sha256.h"

namespace hm::cli {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;
namespace fs = std::filesystem;

// ---- stopping on SIGINT / SIGTERM -------------------------------------------------------------
// The first signal stops new jobs from starting; running ones finish and write their records.
// A second one ends the process at once (outputs are written atomically, so nothing is torn).
std::atomic<int> g_stop{0};

extern "C" void on_stop_signal(int sig) {
  if (g_stop.exchange(1) != 0) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

class StopSignals {
 public:
  StopSignals() {
    g_stop = 0;
    int_ = std::signal(SIGINT, on_stop_signal);
    term_ = std::signal(SIGTERM, on_stop_signal);
    // A batch started in the background of a script (SIGINT ignored) keeps ignoring it.
    if (int_ == SIG_IGN) std::signal(SIGINT, SIG_IGN);
  }
  ~StopSignals() {
    std::signal(SIGINT, int_);
    std::signal(SIGTERM, term_);
  }
  bool stopped() const { return g_stop.load() != 0; }

 private:
  void (*int_)(int) = SIG_DFL;
  void (*term_)(int) = SIG_DFL;
};

// ---- summary rows -----------------------------------------------------------------------------
// The figures a row takes from a job's record, and where in the record they are.
// Columns are named apart from the grid's keys ("panels" there is the count asked for).
struct Column {
  const char* name;     // in the summary
  const char* key;      // in the record
  const char* section;  // "quality", "results", "hydrostatics"
};
constexpr Column kFigures[] = {
    {"mesh_panels", "panels", "quality"},
    {"mesh_quads", "quads", "quality"},
    {"mesh_triangles", "triangles", "quality"},
    {"passes_rules", "passes", "quality"},
    {"side_ratio_share", "side_ratio_share", "quality"},
    {"area_ratio_share", "area_ratio_share", "quality"},
    {"normal_angle_share", "normal_angle_share", "quality"},
    {"free_edges_below_waterline", "free_edges_below_waterline", "quality"},
    {"deviation_max_m", "deviation_max_m", "results"},
    {"volume_m3", "volume_m3", "hydrostatics"},
    {"wetted_area_m2", "wetted_area_m2", "hydrostatics"},
    {"volume_error", "volume_error", "hydrostatics"},
    {"wetted_area_error", "wetted_area_error", "hydrostatics"},
};

ordered_json row_head(const Manifest& m, const BatchJob& job) {
  ordered_json row;
  row["id"] = job.id;
  row["hull"] = m.hulls[job.hull].name;
  row["mesher"] = job.mesher;
  for (const std::string& key : m.grid_keys) {
    row[key] = job.point.contains(key) ? job.point[key] : ordered_json(nullptr);
  }
  return row;
}

ordered_json ok_row(const Manifest& m, const BatchJob& job, const ordered_json& record,
                    bool reused) {
  ordered_json row = row_head(m, job);
  row["status"] = "ok";
  row["error"] = "";
  row["seconds"] = record.value("seconds", 0.0);
  row["reused"] = reused;
  const ordered_json none;
  for (const Column& c : kFigures) {
    const std::string section = c.section;
    const ordered_json* from = &none;
    if (section == "hydrostatics") {
      if (record.contains("results") && record["results"].contains("hydrostatics"))
        from = &record["results"]["hydrostatics"];
    } else if (record.contains(section)) {
      from = &record[section];
    }
    row[c.name] = from->is_object() && from->contains(c.key) ? (*from)[c.key] : none;
  }
  return row;
}

ordered_json failed_row(const Manifest& m, const BatchJob& job, const std::string& status,
                        const std::string& error, double seconds) {
  ordered_json row = row_head(m, job);
  row["status"] = status;
  row["error"] = error;
  row["seconds"] = seconds;
  row["reused"] = false;
  for (const Column& c : kFigures) row[c.name] = nullptr;
  return row;
}

std::string csv_cell(const ordered_json& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (!v.is_string()) return v.dump();
  const std::string s = v.get<std::string>();
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) {
    if (ch == '"') q += '"';
    q += ch == '\n' ? ' ' : ch;
  }
  return q + "\"";
}

void write_summary(const std::string& out_dir, const std::string& stem, const Manifest& m,
                   const BatchResult& r, const std::string& shard) {
  ordered_json j;
  j["hullmesh"] = HULLMESH_VERSION;
  j["manifest"] = m.path;
  j["shard"] = shard;
  j["jobs"] = r.rows.size();
  j["ok"] = r.ok;
  j["failed"] = r.failed;
  j["not_run"] = r.not_run;
  j["reused"] = r.reused;
  j["rows"] = r.rows;
  write_file_atomically((fs::path(out_dir) / (stem + ".json")).string(),
                        [&](std::ostream& out) { out << j.dump(2) << '\n'; });
  write_file_atomically((fs::path(out_dir) / (stem + ".csv")).string(), [&](std::ostream& out) {
    if (r.rows.empty()) return;
    bool first = true;
    for (const auto& [key, value] : r.rows.front().items()) {
      out << (first ? "" : ",") << key;
      first = false;
    }
    out << '\n';
    for (const ordered_json& row : r.rows) {
      first = true;
      for (const auto& [key, value] : row.items()) {
        out << (first ? "" : ",") << csv_cell(value);
        first = false;
      }
      out << '\n';
    }
  });
}

// ---- one job ----------------------------------------------------------------------------------
std::string output_path(const std::string& out_dir, const BatchJob& job, const std::string& ext) {
  return (fs::path(out_dir) / (job.id + "." + ext)).string();
}
std::string record_path(const std::string& out_dir, const BatchJob& job) {
  return (fs::path(out_dir) / (job.id + ".run.json")).string();
}

// What a finished job's record must repeat for the job to count as done.
ordered_json job_spec(const Manifest& m, const BatchJob& job) {
  return {{"id", job.id},
          {"hull", m.hulls[job.hull].name},
          {"words", job_words(m, job)},
          {"formats", job.formats}};
}

// The record of a finished job whose outputs are all on disk as it wrote them, else null.
ordered_json finished_record(const std::string& out_dir, const BatchJob& job,
                             const ordered_json& spec, const std::string& input_sha) {
  const std::string path = record_path(out_dir, job);
  std::error_code ec;
  if (!fs::exists(path, ec)) return nullptr;
  std::ifstream in(path);
  const ordered_json rec = ordered_json::parse(in, nullptr, false);
  if (rec.is_discarded() || !rec.is_object()) return nullptr;
  if (rec.value("hullmesh", "") != HULLMESH_VERSION) return nullptr;
  if (!rec.contains("job") || rec["job"].value("spec", ordered_json()) != spec) return nullptr;
  if (!rec.contains("input") || rec["input"].value("sha256", "") != input_sha) return nullptr;
  if (!rec.contains("outputs") || rec["outputs"].size() != job.formats.size()) return nullptr;
  for (std::size_t k = 0; k < job.formats.size(); ++k) {
    const std::string file = output_path(out_dir, job, job.formats[k]);
    const ordered_json& o = rec["outputs"][k];
    if (fs::path(o.value("path", "")).filename() != fs::path(file).filename()) return nullptr;
    if (!fs::exists(file, ec) || fs::file_size(file, ec) != o.value("bytes", std::uintmax_t{0}))
      return nullptr;
    if (sha256_file(file) != o.value("sha256", "")) return nullptr;
  }
  return rec;
}

// Temporary files a killed run left behind for this job (io/atomic_file names them
// ".NAME.tmp.PID.N"). Only this job's own names: another shard may be writing beside them, and
// one id can begin another ("..._panels-1" and "..._panels-1.5").
void remove_stale_temps(const std::string& out_dir, const BatchJob& job) {
  std::vector<std::string> prefixes = {"." + job.id + ".run.json.tmp."};
  for (const std::string& ext : job.formats) prefixes.push_back("." + job.id + "." + ext + ".tmp.");
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(out_dir, ec)) {
    const std::string name = e.path().filename().string();
    for (const std::string& p : prefixes) {
      if (name.rfind(p, 0) == 0) fs::remove(e.path(), ec);
    }
  }
}

ordered_json run_job(const Manifest& m, const BatchJob& job, const std::string& out_dir,
                     const ordered_json& spec, bool validate) {
  remove_stale_temps(out_dir, job);
  ExecuteOptions eo;
  eo.force_quiet = true;
  eo.write_record = false;
  eo.keep_record = true;
  eo.validate = validate;
  // The words the spec already holds (job_spec built them), so a job is expanded once.
  std::vector<std::string> words = spec["words"].get<std::vector<std::string>>();
  const std::string first = output_path(out_dir, job, job.formats.front());
  words.insert(words.end(), {"-o", first});
  ExecuteResult r = execute_args(words, job.id, eo);
  if (r.exit_code != 0) throw Error(job.id + ": exit code " + std::to_string(r.exit_code));
  ordered_json rec = std::move(r.record);
  // The job's record has hashed `first` already; the conversions' records would only be dropped.
  ordered_json outputs = ordered_json::array();
  for (const ordered_json& o : rec.value("outputs", ordered_json::array())) {
    if (o.value("path", "") == first) outputs.push_back(o);
  }
  if (outputs.empty()) outputs.push_back(file_record(first));
  ExecuteOptions convert = eo;
  convert.keep_record = false;
  for (std::size_t k = 1; k < job.formats.size(); ++k) {
    const std::string out = output_path(out_dir, job, job.formats[k]);
    execute_args({"convert", first, out}, job.id, convert);
    outputs.push_back(file_record(out));
  }
  rec["outputs"] = outputs;
  rec["job"] = {{"id", job.id}, {"spec", spec}};
  // Last: a record on disk means every output before it is complete.
  write_file_atomically(record_path(out_dir, job),
                        [&](std::ostream& out) { out << rec.dump(2) << '\n'; });
  return rec;
}

// ---- what the user sees -----------------------------------------------------------------------
class BatchDisplay {
 public:
  BatchDisplay(RunLog::Mode mode, std::size_t total) : mode_(mode), total_(total) {}
  ~BatchDisplay() {
    if (mode_ == RunLog::Mode::kBar) std::fprintf(stderr, "\r\033[K");
  }
  void finished(const ordered_json& row, bool ok, bool reused) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++done_;
    failed_ += ok ? 0 : 1;
    if (mode_ == RunLog::Mode::kLines) {
      const std::string id = row["id"];
      if (!ok) {
        const std::string error = row["error"];
        std::fprintf(stderr, "hullmesh: batch [%zu/%zu] %s FAILED: %s\n", done_, total_, id.c_str(),
                     error.c_str());
      } else {
        std::fprintf(stderr, "hullmesh: batch [%zu/%zu] %s %s %.2f s, %s panels\n", done_, total_,
                     id.c_str(), reused ? "done before," : "ok", row["seconds"].get<double>(),
                     csv_cell(row["mesh_panels"]).c_str());
      }
    } else if (mode_ == RunLog::Mode::kBar) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
      const double rate = elapsed > 0 ? done_ / elapsed : 0;
      std::fprintf(stderr,
                   "\r\033[Khullmesh: batch %zu/%zu done, %zu failed, %zu left, %.2f jobs/s", done_,
                   total_, failed_, total_ - done_, rate);
      if (rate > 0 && done_ < total_)
        std::fprintf(stderr, ", ~%.0f s left", (total_ - done_) / rate);
    }
    std::fflush(stderr);
  }

 private:
  using Clock = std::chrono::steady_clock;
  RunLog::Mode mode_;
  std::size_t total_, done_ = 0, failed_ = 0;
  Clock::time_point start_ = Clock::now();
  std::mutex mutex_;
};

void print_words(const BatchJob& job, const ordered_json& words) {
  std::string line = "hullmesh: batch " + job.id + " starts: hullmesh";
  for (const ordered_json& w : words) line += " " + w.get<std::string>();
  std::fprintf(stderr, "%s\n", line.c_str());
}

void generate_hulls(const Manifest& m) {
  for (const BatchHull& h : m.hulls) {
    if (!h.generate) continue;
    json spec = *h.generate;
    spec["command"] = "generate";
    spec["output"] = h.file;
    ExecuteOptions eo;
    eo.force_quiet = true;
    eo.write_record = false;
    execute_args(job_arguments(spec, m.path + ": hull " + h.name, "", {}), m.path, eo);
  }
}

std::string shard_stem(std::size_t k, std::size_t n) {
  return "summary.shard-" + std::to_string(k) + "-of-" + std::to_string(n);
}

void count(BatchResult& r) {
  r.ok = r.failed = r.reused = r.not_run = 0;
  for (const ordered_json& row : r.rows) {
    const std::string status = row["status"];
    if (status == "ok") ++r.ok;
    if (status == "failed") ++r.failed;
    if (status == "not run") ++r.not_run;
    if (row["reused"].get<bool>()) ++r.reused;
  }
}

}  // namespace

BatchResult run_batch(const Manifest& m, const BatchOptions& o) {
  std::error_code ec;
  fs::create_directories(fs::path(o.out_dir) / "hulls", ec);
  if (ec) throw IoError(o.out_dir + ": cannot create the output folder (" + ec.message() + ")");
  generate_hulls(m);
  const std::vector<std::size_t> mine = shard_jobs(m, o.shard, o.shards);
  // Each hull's hash once: a job is done only if its record names the input as it is now.
  std::vector<std::string> hull_sha(m.hulls.size());
  for (std::size_t h = 0; h < m.hulls.size(); ++h) {
    try {
      hull_sha[h] = sha256_file(m.hulls[h].file);
    } catch (const IoError&) {
      // A missing file fails its jobs when they run, each with the reader's message.
    }
  }

  BatchResult result;
  result.rows.resize(mine.size());
  BatchDisplay display(o.display, mine.size());
  StopSignals signals;
  // One job per task. isolate(): a thread waiting inside one job's parallel loop may help only
  // that job, never start another, so no more jobs run at once than there are threads.
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, mine.size(), 1),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
          const BatchJob& job = m.jobs[mine[i]];
          ordered_json& row = result.rows[i];
          if (signals.stopped()) {
            row = failed_row(m, job, "not run", "interrupted", 0);
            continue;
          }
          const auto t0 = std::chrono::steady_clock::now();
          bool ok = false, reused = false;
          tbb::this_task_arena::isolate([&] {
            try {
              const ordered_json spec = job_spec(m, job);
              ordered_json rec;
              if (!o.rerun) rec = finished_record(o.out_dir, job, spec, hull_sha[job.hull]);
              reused = !rec.is_null();
              if (!reused && o.verbose) print_words(job, spec["words"]);
              if (!reused) rec = run_job(m, job, o.out_dir, spec, o.validate);
              row = ok_row(m, job, rec, reused);
              ok = true;
            } catch (const std::exception& e) {
              const double s =
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
              row = failed_row(m, job, "failed", e.what(), s);
            }
          });
          display.finished(row, ok, reused);
        }
      });
  result.interrupted = signals.stopped();
  count(result);
  const bool sharded = o.sharded;
  write_summary(o.out_dir, sharded ? shard_stem(o.shard, o.shards) : "summary", m, result,
                sharded ? std::to_string(o.shard) + "/" + std::to_string(o.shards) : "");
  return result;
}

BatchResult merge_shards(const Manifest& m, const std::string& out_dir, std::size_t n) {
  std::map<std::string, ordered_json> by_id;
  for (std::size_t k = 0; k < n; ++k) {
    const std::string path = (fs::path(out_dir) / (shard_stem(k, n) + ".json")).string();
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      throw UsageError(path + ": shard " + std::to_string(k) + " of " + std::to_string(n) +
                       " has no summary (did it run?)");
    }
    std::ifstream in(path);
    const ordered_json s = ordered_json::parse(in, nullptr, false);
    if (s.is_discarded() || !s.contains("rows")) throw InputError(path + ": not a shard summary");
    for (const ordered_json& row : s["rows"]) {
      const std::string id = row.value("id", "");
      if (!by_id.emplace(id, row).second) {
        throw InputError(path + ": job " + id + " is in two shards");
      }
    }
  }
  BatchResult result;
  for (const BatchJob& job : m.jobs) {
    auto it = by_id.find(job.id);
    if (it == by_id.end()) throw InputError(out_dir + ": no shard ran job " + job.id);
    result.rows.push_back(it->second);
    by_id.erase(it);
  }
  if (!by_id.empty()) {
    throw InputError(out_dir + ": the shards ran job " + by_id.begin()->first +
                     ", which the manifest does not have");
  }
  count(result);
  write_summary(out_dir, "summary", m, result, "merged from " + std::to_string(n));
  return result;
}

}  // namespace hm::cli
