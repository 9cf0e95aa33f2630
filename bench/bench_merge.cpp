// Merging over a size ladder: ship_449_patches.iges (and a generated 100-patch hull when it is
// absent) tessellated to about 40,000 and 400,000 triangles, merged at 1 and 2 threads. After the
// Google Benchmark runs, main() prints the goal in one run: merging should cost no more
// than tessellating the same hull, as the ratio merge time / tessellate time; and the 1 -> 2
// thread speed-up of the merge. Also benchmarks the weld and Morton kernels on their own.
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "cli/tune_allocator.h"
#include "iges/read_iges.h"
#include "kernels/morton.h"
#include "kernels/order_by_key.h"
#include "kernels/weld.h"
#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "tessellate/tessellate.h"
#include "unstructured/merge.h"

namespace hm {
namespace {

struct Source {
  std::string name;
  std::vector<Patch> patches;
};

const Source& source() {
  static const Source s = [] {
    const char* env = std::getenv("HM_SHARED_DIR");
    const std::filesystem::path p =
        std::filesystem::path(env ? env : "../shared") / "data" / "hulls" / "ship_449_patches.iges";
    std::error_code ec;
    if (std::filesystem::is_regular_file(p, ec)) {
      return Source{"ship_449_patches.iges", read_iges_file(p.string()).patches};
    }
    HullSpec spec;
    spec.kind = HullKind::kRoundBilge;
    spec.patches = 100;
    return Source{"generated round-bilge, 100 patches", generate_hull(spec).patches};
  }();
  return s;
}

const Tessellation& tessellated(std::size_t triangles) {
  static std::map<std::size_t, Tessellation> cache;
  auto it = cache.find(triangles);
  if (it != cache.end()) return it->second;
  TessellateOptions o;
  o.edge_length = edge_length_for_triangles(source().patches, triangles);
  return cache.emplace(triangles, tessellate(source().patches, o, silent_progress())).first->second;
}

// Args: target triangles, threads.
void BM_Merge(benchmark::State& state) {
  const Tessellation& t = tessellated(static_cast<std::size_t>(state.range(0)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(state.range(1)));
  for (auto _ : state) {
    MergedSurface m = merge_patches(source().patches, t.mesh, {}, silent_progress());
    benchmark::DoNotOptimize(m);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * t.mesh.face_count()));
  state.counters["triangles"] = static_cast<double>(t.mesh.face_count());
}
BENCHMARK(BM_Merge)
    ->ArgNames({"triangles", "threads"})
    ->ArgsProduct({{40'000, 400'000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The edge adjacency of the merged surface (every merge step and every mesher builds it).
// Args: target triangles, threads.
void BM_EdgeAdjacency(benchmark::State& state) {
  static std::map<std::size_t, MergedSurface> merged;
  const std::size_t triangles = static_cast<std::size_t>(state.range(0));
  if (!merged.count(triangles)) {
    merged.emplace(triangles, merge_patches(source().patches, tessellated(triangles).mesh, {},
                                            silent_progress()));
  }
  const SurfaceMesh& m = merged.at(triangles).mesh;
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(build_edge_adjacency(m.faces, m.vertex_count()));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * m.face_count()));
}
BENCHMARK(BM_EdgeAdjacency)
    ->ArgNames({"triangles", "threads"})
    ->ArgsProduct({{40'000, 400'000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

std::vector<Vec3d> random_points(std::size_t n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 100);
  std::vector<Vec3d> p(n);
  for (Vec3d& x : p) x = {u(rng), u(rng) * 0.1, u(rng) * 0.08};
  return p;
}

void BM_MortonOrder(benchmark::State& state) {
  const std::vector<Vec3d> p = random_points(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(morton_order(p));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_MortonOrder)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

void BM_OrderByKey(benchmark::State& state) {
  std::mt19937_64 rng(3);
  std::vector<std::uint64_t> keys(static_cast<std::size_t>(state.range(0)));
  for (std::uint64_t& k : keys) k = rng() >> 1;  // 63 bits, as Morton codes
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(state.range(1)));
  for (auto _ : state) benchmark::DoNotOptimize(order_by_key(keys));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_OrderByKey)
    ->ArgNames({"keys", "threads"})
    ->ArgsProduct({{100'000, 1'000'000}, {1, 2}})
    ->Unit(benchmark::kMillisecond);

void BM_FindClosePairs(benchmark::State& state) {
  const std::vector<Vec3d> p = random_points(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(find_close_pairs(p, {}, 0.05));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_FindClosePairs)->Arg(100'000)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

// Best wall time of `reps` runs of f at the given thread count.
template <class F>
double best_seconds(int threads, int reps, F&& f) {
  tbb::global_control c(tbb::global_control::max_allowed_parallelism, threads);
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

void print_goals() {
  const Source& s = source();
  std::printf("\nmerge against tessellation, %s (best of 3, wall seconds):\n", s.name.c_str());
  for (std::size_t target : {std::size_t{40'000}, std::size_t{400'000}}) {
    TessellateOptions o;
    o.edge_length = edge_length_for_triangles(s.patches, target);
    // As `hullmesh merge` and the structured mesher tessellate since 2026-12-07: without the
    // final chord measurement, which only `hullmesh tessellate` and the unstructured mesher read.
    o.measure_chord = false;
    const Tessellation& t = tessellated(target);
    for (int threads : {1, 2}) {
      const double tess = best_seconds(threads, 3, [&] {
        benchmark::DoNotOptimize(tessellate(s.patches, o, silent_progress()));
      });
      MergeReport report;
      const double merge = best_seconds(threads, 3, [&] {
        report = merge_patches(s.patches, t.mesh, {}, silent_progress()).report;
      });
      std::printf(
          "  %7zu triangles, %d thread%s: tessellate %.3f s, merge %.3f s, merge / tessellate "
          "%.2f (goal <= 1); %zu boundary loops, %zu non-manifold edges\n",
          t.mesh.face_count(), threads, threads == 1 ? " " : "s", tess, merge, merge / tess,
          report.boundary_loops, report.nonmanifold_edges);
    }
  }
}

}  // namespace
}  // namespace hm

int main(int argc, char** argv) {
  // The allocator the CLI runs with, so that the figures are those users get.
  hm::cli::tune_allocator(argv);
  bool filtered = false;
  for (int i = 1; i < argc; ++i) filtered |= std::string(argv[i]).starts_with("--benchmark_filter");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (!filtered) hm::print_goals();
  return 0;
}
