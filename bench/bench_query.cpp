// Hull queries on a generated Wigley hull triangulated on fine grids (the scene is built here, so
// the benchmark does not depend on the tessellator): 1 million random rays, 1 million
// closest-point queries, 1,000 plane sections, and the BVH section against a brute-force loop
// over every triangle, on a ladder of scene sizes, at 1 and 2 threads. Items are rays, queries or
// sections. After the table, a summary checks the goals (BVH > 10x brute force on the
// ~400,000-triangle scene).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "nurbs/generate_hull.h"
#include "query/hull_query.h"

namespace {

using namespace hm;

constexpr int kPatches = 8;  // full Wigley hull, 8 patches

struct BenchScene {
  std::vector<Patch> patches;
  SurfaceMesh mesh;
  std::unique_ptr<HullQuery> query;
};

// Each patch evaluated on an n x n grid of cells, each cell split into two triangles:
// 2 n^2 kPatches triangles (n = 160: 409,600).
const BenchScene& scene(int n) {
  static std::map<int, std::unique_ptr<BenchScene>> cache;
  auto& slot = cache[n];
  if (slot) return *slot;
  slot = std::make_unique<BenchScene>();
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  spec.patches = kPatches;
  spec.full_hull = true;
  slot->patches = generate_hull(spec).patches;
  SurfaceMesh& m = slot->mesh;
  for (PatchId p = 0; p < slot->patches.size(); ++p) {
    const NurbsSurface& s = slot->patches[p].surface;
    const Index base = static_cast<Index>(m.positions.size());
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const Vec2d uv{s.u0 + (s.u1 - s.u0) * i / n, s.v0 + (s.v1 - s.v0) * j / n};
        m.positions.push_back(evaluate(s, uv.x, uv.y));
        m.vertex_uv.push_back(uv);
        m.vertex_patch.push_back(p);
      }
    }
    auto id = [&](int i, int j) { return base + static_cast<Index>(i + (n + 1) * j); };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), kInvalid});
        m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1), kInvalid});
        m.face_patch.insert(m.face_patch.end(), 2, p);
      }
    }
  }
  slot->query = std::make_unique<HullQuery>(slot->patches, slot->mesh);
  return *slot;
}

constexpr int kFine = 160;

std::vector<Ray> random_rays(const BBox3d& box, std::size_t count) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(-1, 1);
  const Vec3d c = box.center(), e = box.extent();
  std::vector<Ray> rays(count);
  for (Ray& r : rays) {
    const Vec3d o = c + Vec3d{e.x * unit(rng), e.y * unit(rng), e.z * unit(rng)};
    const Vec3d to = c + 0.5 * Vec3d{e.x * unit(rng), e.y * unit(rng), e.z * unit(rng)};
    r = {o, to - o};
  }
  return rays;
}

std::vector<Vec3d> random_points(const BBox3d& box, std::size_t count) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> unit(-0.6, 0.6);
  const Vec3d c = box.center(), e = box.extent();
  std::vector<Vec3d> points(count);
  for (Vec3d& p : points) p = c + Vec3d{e.x * unit(rng), e.y * unit(rng), e.z * unit(rng)};
  return points;
}

// Stations, waterlines and buttocks in turn, spread over the hull.
std::vector<Plane> planes(const BBox3d& box, std::size_t count) {
  std::vector<Plane> out;
  for (std::size_t i = 0; i < count; ++i) {
    const double f = (i / 3 + 0.5) / ((count + 2) / 3);
    const Vec3d p = box.lo + f * (box.hi - box.lo);
    const int axis = static_cast<int>(i % 3);
    out.push_back({p, {axis == 0 ? 1.0 : 0.0, axis == 2 ? 0.1 : 0.0, axis == 1 ? 1.0 : 0.05}});
  }
  return out;
}

void BM_Rays(benchmark::State& state) {
  const BenchScene& s = scene(kFine);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(0));
  const std::vector<Ray> rays = random_rays(s.query->bbox(), 1'000'000);
  std::vector<RayHit> hits(rays.size());
  for (auto _ : state) {
    s.query->first_hits(rays, hits);
    benchmark::DoNotOptimize(hits.data());
  }
  state.SetItemsProcessed(state.iterations() * rays.size());
}
BENCHMARK(BM_Rays)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Iterations(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_ClosestPoints(benchmark::State& state) {
  const BenchScene& s = scene(kFine);
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(0));
  const std::vector<Vec3d> points = random_points(s.query->bbox(), 1'000'000);
  std::vector<ClosestPoint> out(points.size());
  for (auto _ : state) {
    s.query->closest_points(points, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * points.size());
}
BENCHMARK(BM_ClosestPoints)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// 1,000 sections at once (sections() runs them in parallel), on a ladder of scene sizes, with
// and without the refinement onto the NURBS.
void BM_Sections(benchmark::State& state) {
  const BenchScene& s = scene(static_cast<int>(state.range(0)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  const std::vector<Plane> cuts = planes(s.query->bbox(), 1000);
  SectionOptions options;
  options.refine = state.range(2) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.query->sections(cuts, options));
  state.SetItemsProcessed(state.iterations() * cuts.size());
  state.counters["triangles"] = static_cast<double>(s.query->triangle_count());
}
BENCHMARK(BM_Sections)
    ->ArgNames({"grid", "threads", "refine"})
    ->ArgsProduct({{20, 40, 80, 160}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The same sections by a loop over every triangle (100 planes: it is slow), in parallel over
// planes like sections().
void BM_SectionsBruteForce(benchmark::State& state) {
  const BenchScene& s = scene(static_cast<int>(state.range(0)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  const std::vector<Plane> cuts = planes(s.query->bbox(), 100);
  SectionOptions options;
  options.refine = state.range(2) != 0;
  std::vector<Section> out(cuts.size());
  for (auto _ : state) {
    parallel_for_each_item(cuts.size(), [&](std::size_t i) {
      out[i] = s.query->section_brute_force(cuts[i], options);
    });
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * cuts.size());
  state.counters["triangles"] = static_cast<double>(s.query->triangle_count());
}
BENCHMARK(BM_SectionsBruteForce)
    ->ArgNames({"grid", "threads", "refine"})
    ->ArgsProduct({{20, 40, 80, 160}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The goal, measured directly: one thread, the fine scene, per section. The triangle
// search is what the BVH replaces; chaining and the refinement onto the NURBS (a few Newton
// steps per point) are the same work either way, so the ratio is given with and without the
// refinement. Wall-clock time: run it on a quiet machine.
void print_goals() {
  const BenchScene& s = scene(kFine);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const std::vector<Plane> cuts = planes(s.query->bbox(), 100);
  auto per_section = [&](bool brute, bool refine) {
    SectionOptions options;
    options.refine = refine;
    const auto t0 = std::chrono::steady_clock::now();
    for (const Plane& p : cuts) {
      benchmark::DoNotOptimize(brute ? s.query->section_brute_force(p, options)
                                     : s.query->section(p, options));
    }
    const auto t1 = std::chrono::steady_clock::now();
    return std::chrono::duration<double, std::milli>(t1 - t0).count() / cuts.size();
  };
  std::printf("\nsections of %zu triangles, 1 thread, ms per section:\n",
              s.query->triangle_count());
  for (bool refine : {false, true}) {
    const double bvh = per_section(false, refine), brute = per_section(true, refine);
    std::printf("  %-28s BVH %7.3f  brute force %7.3f  BVH %5.1fx faster\n",
                refine ? "refined onto the NURBS:" : "mesh section (no refining):", bvh, brute,
                brute / bvh);
  }
  std::printf("  goal: BVH more than 10x faster than brute force on the ~400,000-triangle scene\n");
}

}  // namespace

int main(int argc, char** argv) {
  // The goal summary runs after the full table only, not after a filtered run.
  bool filtered = false;
  for (int i = 1; i < argc; ++i) filtered |= std::string(argv[i]).starts_with("--benchmark_filter");
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  if (!filtered) print_goals();
  benchmark::Shutdown();
  return 0;
}
