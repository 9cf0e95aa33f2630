#include "support/test_support.h"

#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>

#include "support/test_json.h"

extern char** environ;

namespace hm::test {
namespace fs = std::filesystem;

fs::path shared_hulls_dir() {
  const char* env = std::getenv("HM_SHARED_DIR");
  fs::path dir = env ? fs::path(env) / "data" / "hulls" : fs::path("../shared/data/hulls");
  std::error_code ec;
  return fs::is_directory(dir, ec) ? dir : fs::path();
}

fs::path shared_hull(const std::string& name) {
  const fs::path dir = shared_hulls_dir();
  if (dir.empty()) return {};
  const fs::path p = dir / name;
  std::error_code ec;
  return fs::is_regular_file(p, ec) ? p : fs::path();
}

fs::path scratch_dir(const std::string& test_name) {
  const char* build = std::getenv("HM_BUILD_DIR");
  // Without a build directory, one root per working directory (the checkout the tests run
  // from): two checkouts testing at once on one machine must not remove each other's files.
  char tag[32];
  std::snprintf(tag, sizeof tag, "hm-test-%016zx",
                std::hash<std::string>{}(fs::current_path().string()));
  fs::path root = build ? fs::path(build) / "test-scratch" : fs::temp_directory_path() / tag;
  fs::path dir = root / test_name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path hullmesh_exe() {
  const char* build = std::getenv("HM_BUILD_DIR");
  return (build ? fs::path(build) : fs::path("build")) / "src" / "cli" / "hullmesh";
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in, nullptr, false);
}

nlohmann::json quality_json(const fs::path& mesh) {
  const RunResult r = run_hullmesh("quality --json " + q(mesh));
  const std::size_t at = r.out.find('{');
  if (at == std::string::npos) return nlohmann::json::value_t::discarded;
  return nlohmann::json::parse(r.out.substr(at), nullptr, false);
}

int spawn_hullmesh(const std::string& args, const fs::path& log) {
  const std::string to = log.empty() ? std::string("/dev/null") : q(log);
  const std::string cmd = "exec " + q(hullmesh_exe()) + " " + args + " > " + to + " 2>&1";
  const char* argv[] = {"/bin/sh", "-c", cmd.c_str(), nullptr};
  pid_t pid = -1;
  if (posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char**>(argv), environ) != 0) {
    return -1;
  }
  return pid;
}

RunResult run_hullmesh(const std::string& args) {
  RunResult r;
  // Every command in the tests checks the invariants between its stages (issue 10).
  const std::string cmd = "HULLMESH_VALIDATE=1 " + hullmesh_exe().string() + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace hm::test
