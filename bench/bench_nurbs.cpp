// The batched NURBS kernel: grid evaluation of hull-sized bicubic patches, and a ladder over the
// number of patches. Items are evaluated points (spans for the patch area).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "nurbs/evaluate_grid.h"
#include "nurbs/generate_hull.h"
#include "nurbs/nurbs_surface.h"
#include "nurbs/patch.h"

namespace {

using hm::NurbsSurface;
using hm::Vec3d;

// A smooth bicubic hull-like patch with nu x nv control points (u along the ship, v girthwise),
// uniform clamped knots, mildly rational.
NurbsSurface hull_patch(int nu, int nv, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  NurbsSurface s;
  s.degree_u = 3;
  s.degree_v = 3;
  s.count_u = nu;
  s.count_v = nv;
  auto knots = [](int n) {
    std::vector<double> k(4, 0.0);
    for (int i = 1; i < n - 3; ++i) k.push_back(static_cast<double>(i) / (n - 3));
    k.insert(k.end(), 4, 1.0);
    return k;
  };
  s.knots_u = knots(nu);
  s.knots_v = knots(nv);
  for (int j = 0; j < nv; ++j) {
    const double phi = 1.5 * j / (nv - 1);
    for (int i = 0; i < nu; ++i) {
      const double x = 100.0 * i / (nu - 1);
      const double half_beam = 8.0 * (1 - std::pow(2 * x / 100 - 1, 2)) + 0.5;
      s.points.push_back({x, half_beam * std::sin(phi) + jitter(rng), -6 * std::cos(phi)});
      s.weights.push_back(1.0 + jitter(rng));
    }
  }
  return s;
}

void BM_Grid100x100(benchmark::State& state) {
  const NurbsSurface s =
      hull_patch(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)), 1);
  const bool normals = state.range(2) != 0;
  for (auto _ : state) {
    hm::SurfaceSamples out = hm::evaluate_grid(s, 100, 100, normals);
    benchmark::DoNotOptimize(out.positions.data());
  }
  state.SetItemsProcessed(state.iterations() * 100 * 100);
}
BENCHMARK(BM_Grid100x100)
    ->ArgNames({"nu", "nv", "normals"})
    ->Args({18, 54, 0})
    ->Args({18, 54, 1})
    ->Args({4, 4, 0})
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();

// One point at a time through evaluate(): the baseline the batched grid is measured against.
void BM_SinglePoints100x100(benchmark::State& state) {
  const NurbsSurface s = hull_patch(18, 54, 1);
  for (auto _ : state) {
    Vec3d sum;
    for (int j = 0; j < 100; ++j) {
      for (int i = 0; i < 100; ++i) sum += hm::evaluate(s, i / 99.0, j / 99.0);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * 100 * 100);
}
BENCHMARK(BM_SinglePoints100x100)->Unit(benchmark::kMicrosecond);

// A ladder over the number of patches, 100 x 100 positions on each.
void BM_PatchLadder(benchmark::State& state) {
  std::vector<NurbsSurface> patches;
  for (int k = 0; k < state.range(0); ++k) patches.push_back(hull_patch(18, 54, 7 + k));
  for (auto _ : state) {
    for (const NurbsSurface& s : patches) {
      hm::SurfaceSamples out = hm::evaluate_grid(s, 100, 100, false);
      benchmark::DoNotOptimize(out.positions.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * state.range(0) * 100 * 100);
}
BENCHMARK(BM_PatchLadder)
    ->ArgName("patches")
    ->Arg(1)
    ->Arg(10)
    ->Arg(100)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Generating a full hull of 1 to 1000 exact patches (the test-hull generator's speed).
void BM_GenerateHull(benchmark::State& state) {
  hm::HullSpec spec;
  spec.kind = static_cast<hm::HullKind>(state.range(1));
  spec.patches = static_cast<int>(state.range(0));
  spec.full_hull = spec.patches > 1;
  for (auto _ : state) benchmark::DoNotOptimize(hm::generate_hull(spec));
}
BENCHMARK(BM_GenerateHull)
    ->ArgNames({"patches", "kind"})
    ->ArgsProduct({{1, 100, 1000}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_ClosestPoint(benchmark::State& state) {
  const NurbsSurface s = hull_patch(18, 54, 3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> t(0.0, 1.0);
  std::vector<Vec3d> queries;
  for (int k = 0; k < 256; ++k) {
    const double u = t(rng), v = t(rng);
    queries.push_back(hm::evaluate(s, u, v) + 0.1 * hm::normal(s, u, v));
  }
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(hm::closest_point(s, queries[k++ % queries.size()]));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ClosestPoint)->Unit(benchmark::kMicrosecond);

// The area of an untrimmed 18 x 54 patch (255 knot spans) by adaptive Gauss per span, to the
// estimate's tolerance (the fine mesh's edge from --triangles) and to the exact one. Each span
// evaluates tensor grids of nodes (surface_grid_derivs): items are spans.
void BM_PatchArea(benchmark::State& state) {
  hm::Patch p;
  p.surface = hull_patch(18, 54, 4);
  const double tol = state.range(0) == 0 ? hm::kAreaEstimateTol : hm::kAreaExactTol;
  for (auto _ : state) benchmark::DoNotOptimize(hm::patch_area(p, tol));
  state.SetItemsProcessed(state.iterations() * 15 * 51);
}
BENCHMARK(BM_PatchArea)->ArgName("exact")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
