// Tessellation over a size ladder: generated hulls of 1, 10, 100 and 1000 patches and the shared
// ship_449_patches.iges, each to about 40,000 and 400,000 triangles, at 1 and 2 threads. After the
// Google Benchmark runs, main() prints the goals side by side in one run: the time to
// 40,000 triangles, the speed-up from 1 to 2 threads, and Gmsh meshing the same IGES surfaces at
// the same edge length (when gmsh is on the PATH; HM_BENCH_GMSH=0 skips it).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "cli/tune_allocator.h"
#include "iges/read_iges.h"
#include "nurbs/generate_hull.h"
#include "tessellate/tessellate.h"

namespace hm {
namespace {

std::filesystem::path shared_path(const char* name) {
  const char* env = std::getenv("HM_SHARED_DIR");
  const std::filesystem::path p =
      std::filesystem::path(env ? env : "../shared") / "data" / "hulls" / name;
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec) ? p : std::filesystem::path();
}

// Source 0..3: generated round-bilge hulls of 1, 10, 100, 1000 patches; 4: ship_449.
constexpr int kShip449 = 4;
constexpr int kLadder[] = {1, 10, 100, 1000};

const std::vector<Patch>& source(int k) {
  static std::map<int, std::vector<Patch>> cache;
  auto it = cache.find(k);
  if (it != cache.end()) return it->second;
  std::vector<Patch> patches;
  if (k == kShip449) {
    const std::filesystem::path p = shared_path("ship_449_patches.iges");
    if (!p.empty()) patches = read_iges_file(p.string()).patches;
  } else {
    HullSpec spec;
    spec.kind = HullKind::kRoundBilge;
    spec.patches = kLadder[k];
    patches = generate_hull(spec).patches;
  }
  return cache.emplace(k, std::move(patches)).first->second;
}

TessellateOptions options_for(const std::vector<Patch>& patches, std::size_t triangles) {
  TessellateOptions o;
  o.edge_length = edge_length_for_triangles(patches, triangles);
  return o;
}

// Args: source, target triangles, threads.
void BM_Tessellate(benchmark::State& state) {
  const std::vector<Patch>& patches = source(static_cast<int>(state.range(0)));
  if (patches.empty()) {
    state.SkipWithError("ship_449_patches.iges not present");
    return;
  }
  const TessellateOptions o = options_for(patches, static_cast<std::size_t>(state.range(1)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(state.range(2)));
  TessellateSummary summary;
  for (auto _ : state) {
    Tessellation t = tessellate(patches, o, silent_progress());
    summary = t.summary;
    benchmark::DoNotOptimize(t);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * summary.triangles));
  state.counters["patches"] = static_cast<double>(patches.size());
  state.counters["triangles"] = static_cast<double>(summary.triangles);
  state.counters["chord/tol"] = summary.max_chord_error / summary.chord_tolerance;
}

void ladder(benchmark::internal::Benchmark* b) {
  for (int src = 0; src <= kShip449; ++src)
    for (int tris : {40'000, 400'000})
      for (int threads : {1, 2}) b->Args({src, tris, threads});
}
BENCHMARK(BM_Tessellate)->Apply(ladder)->Unit(benchmark::kMillisecond)->UseRealTime();

// Best wall time of `reps` runs at the given thread count.
double best_seconds(const std::vector<Patch>& patches, const TessellateOptions& o, int threads,
                    int reps, std::size_t& triangles) {
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    Tessellation t = tessellate(patches, o, silent_progress());
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    triangles = t.summary.triangles;
  }
  return best;
}

// Gmsh on the same file at the same edge length: wall seconds and triangles, or negative.
constexpr int kGmshTimeoutSeconds = 120;

double gmsh_seconds(const std::filesystem::path& iges, double h, std::size_t& triangles) {
  const char* skip = std::getenv("HM_BENCH_GMSH");
  if ((skip && std::string(skip) == "0") || std::system("command -v gmsh >/dev/null 2>&1") != 0)
    return -1;
  const std::filesystem::path out = std::filesystem::temp_directory_path() / "hm_bench_gmsh.msh";
  // Gmsh may run for many minutes on hundreds of patches: cap it, and report a timeout as such.
  const std::string cmd = "timeout " + std::to_string(kGmshTimeoutSeconds) + " gmsh '" +
                          iges.string() + "' -2 -nt 1 -clmin " + std::to_string(h) + " -clmax " +
                          std::to_string(h) + " -format msh2 -o '" + out.string() +
                          "' >/dev/null 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = std::system(cmd.c_str());
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0) return -1;
  // msh2 elements: "id type ntags ..."; type 2 is a 3-node triangle.
  std::ifstream in(out);
  std::string line;
  bool elements = false;
  triangles = 0;
  while (std::getline(in, line)) {
    if (line == "$Elements") {
      elements = true;
      std::getline(in, line);
      continue;
    }
    if (line == "$EndElements") break;
    int id = 0, type = 0;
    if (elements && std::sscanf(line.c_str(), "%d %d", &id, &type) == 2 && type == 2) ++triangles;
  }
  std::filesystem::remove(out);
  return s;
}

void print_goals() {
  const std::filesystem::path ship = shared_path("ship_449_patches.iges");
  const bool real = !ship.empty();
  const std::vector<Patch>& patches = source(real ? kShip449 : 2);
  const char* name = real ? "ship_449_patches.iges" : "generated hull, 100 patches";
  const TessellateOptions o = options_for(patches, 40'000);
  std::size_t tris1 = 0, tris2 = 0;
  const double t1 = best_seconds(patches, o, 1, 5, tris1);
  const double t2 = best_seconds(patches, o, 2, 5, tris2);
  std::printf("\n== tessellation goals (%s, %zu patches) ==\n", name, patches.size());
  std::printf(
      "  40k target: %zu triangles, 1 thread %.4f s, 2 threads %.4f s (goal: well under 1 s)\n",
      tris2, t1, t2);
  std::printf("  speed-up 1 -> 2 threads: %.2fx (goal >= 1.7x)%s\n", t1 / t2,
              t1 / t2 >= 1.7 ? "" : "  ** below goal **");
  if (!real) return;
  std::size_t gmsh_tris = 0;
  const double g = gmsh_seconds(ship, o.edge_length, gmsh_tris);
  if (g < 0) {
    std::printf("  gmsh: no result (not on PATH, failed, over %d s, or HM_BENCH_GMSH=0)\n",
                kGmshTimeoutSeconds);
    return;
  }
  std::printf("  gmsh -2 at the same edge length: %zu triangles in %.3f s\n", gmsh_tris, g);
  // Compare rates, since the two triangle counts differ somewhat.
  const double ratio = (double(tris2) / t2) / (double(gmsh_tris) / g);
  std::printf("  hullmesh (2 threads) vs gmsh, triangles per second: %.1fx (goal >= 10x)\n", ratio);
}

}  // namespace
}  // namespace hm

int main(int argc, char** argv) {
  // The allocator the CLI runs with, so that the figures are those users get.
  hm::cli::tune_allocator(argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  hm::print_goals();
  return 0;
}
