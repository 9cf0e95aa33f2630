// Hull queries on a generated Wigley hull triangulated on fine grids (the scene is built here, so
// the benchmark does not depend on the tessellator): 1 million random rays, 1 million
// closest-point queries, 1,000 plane sections, the BVH section against a brute-force loop over
// every triangle, and the search for faces through faces, on a ladder of scene sizes, at 1 and 2
// threads. Items are rays, queries or
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
#include "query/find_self_intersections.h"
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

// Faces through other faces (query/find_self_intersections.h, which every meshing command runs on
// the merged surface and on its panels): the box-pair kernel's grid and the exact decisions,
// on the same ladder. Items are triangles.
void BM_SelfIntersections(benchmark::State& state) {
  const BenchScene& s = scene(static_cast<int>(state.range(0)));
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, state.range(1));
  const double tol = 1e-7 * s.query->bbox().extent().x;
  for (auto _ : state) benchmark::DoNotOptimize(find_self_intersections(s.mesh, tol));
  state.SetItemsProcessed(state.iterations() * s.mesh.faces.size());
  state.counters["triangles"] = static_cast<double>(s.mesh.faces.size());
}
BENCHMARK(BM_SelfIntersections)
    ->ArgNames({"grid", "threads"})
    ->ArgsProduct({{20, 40, 80, 160}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The goal, measured directly: one thread, the fine scene, per plane, the BVH and the loop
// timed alternately (5 rounds, best of each, so that the machine's noise hits both alike). Three
// figures: the search alone, which is what the BVH replaces (the crossed triangles, in triangle
// order); the whole mesh section (plus chaining and joining, the same work either way); and the
// section refined onto the NURBS (plus a few Newton steps per point, the same work either way).
void print_goals() {
  const BenchScene& s = scene(kFine);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const std::vector<Plane> cuts = planes(s.query->bbox(), 99);
  using Clock = std::chrono::steady_clock;
  auto time_ms = [&](auto&& run) {
    const auto t0 = Clock::now();
    for (const Plane& p : cuts) run(p);
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / cuts.size();
  };
  std::printf("\nplanes through %zu triangles, 1 thread, ms per plane (best of 5 alternating):\n",
              s.query->triangle_count());
  for (int mode = 0; mode < 3; ++mode) {
    SectionOptions options;
    options.refine = mode == 2;
    double bvh = 1e300, brute = 1e300;
    for (int round = 0; round < 5; ++round) {
      bvh = std::min(bvh, time_ms([&](const Plane& p) {
                       if (mode == 0) {
                         benchmark::DoNotOptimize(s.query->crossed_faces(p));
                       } else {
                         benchmark::DoNotOptimize(s.query->section(p, options));
                       }
                     }));
      brute = std::min(brute, time_ms([&](const Plane& p) {
                         if (mode == 0) {
                           benchmark::DoNotOptimize(s.query->crossed_faces_brute_force(p));
                         } else {
                           benchmark::DoNotOptimize(s.query->section_brute_force(p, options));
                         }
                       }));
    }
    const char* what[] = {
        "search (crossed triangles):", "mesh section (no refining):", "refined onto the NURBS:"};
    std::printf("  %-28s BVH %7.3f  brute force %7.3f  BVH %5.1fx faster\n", what[mode], bvh, brute,
                brute / bvh);
  }
  std::printf(
      "  goal: the BVH more than 10x faster than the loop over all triangles on the ~400,000-"
      "triangle scene\n");
}

}  // namespace

int main(int argc, char** argv) {
  // The goal summary runs after the full table only, not after a filtered run; --goals_only runs
  // the summary alone.
  bool filtered = false, goals_only = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    filtered |= arg.starts_with("--benchmark_filter");
    goals_only |= arg == "--goals_only";
  }
  if (goals_only) {
    print_goals();
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  if (!filtered) print_goals();
  benchmark::Shutdown();
  return 0;
}
