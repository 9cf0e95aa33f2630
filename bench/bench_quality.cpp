// The quality report and the hydrostatics over a ladder of panel counts (a closed sphere of quads
// and pole triangles, about 1k to 1M panels). Items are panels.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "quality/hydrostatics.h"
#include "quality/quality_report.h"

namespace {

using hm::Index;
using hm::Vec3d;

// UV sphere of radius 1 with n x n/2 cells; the poles are single vertices (fans of triangles).
hm::SurfaceMesh sphere(int n) {
  const int nv = n / 2;
  hm::SurfaceMesh m;
  m.positions.push_back({0, 0, -1});
  for (int j = 1; j < nv; ++j)
    for (int i = 0; i < n; ++i) {
      const double phi = 2 * std::numbers::pi * i / n, th = std::numbers::pi * (1 - double(j) / nv);
      m.positions.push_back(
          {std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th)});
    }
  const Index north = static_cast<Index>(m.positions.size());
  m.positions.push_back({0, 0, 1});
  auto id = [n](int i, int j) { return static_cast<Index>(1 + (i % n) + n * (j - 1)); };
  for (int i = 0; i < n; ++i) m.faces.push_back({0, id(i + 1, 1), id(i, 1), hm::kInvalid});
  for (int j = 1; j + 1 < nv; ++j)
    for (int i = 0; i < n; ++i)
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  for (int i = 0; i < n; ++i)
    m.faces.push_back({id(i, nv - 1), id(i + 1, nv - 1), north, hm::kInvalid});
  m.face_patch.assign(m.faces.size(), 0);
  return m;
}

void BM_AssessQuality(benchmark::State& state) {
  const hm::SurfaceMesh m = sphere(static_cast<int>(state.range(0)));
  hm::QualityOptions o;
  o.waterline_z = 0.0;
  o.waves.speed = 5.0;
  for (auto _ : state) {
    hm::QualityReport r = hm::assess_quality(m, o);
    benchmark::DoNotOptimize(r.faces);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(m.face_count()));
  state.counters["panels"] = static_cast<double>(m.face_count());
}
BENCHMARK(BM_AssessQuality)->Arg(44)->Arg(140)->Arg(448)->Arg(1414)->Unit(benchmark::kMillisecond);

void BM_HydrostaticsMesh(benchmark::State& state) {
  const hm::SurfaceMesh m = sphere(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    hm::Hydrostatics h = hm::hydrostatics_mesh(m, {0.0, false});
    benchmark::DoNotOptimize(h.volume);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(m.face_count()));
  state.counters["panels"] = static_cast<double>(m.face_count());
}
BENCHMARK(BM_HydrostaticsMesh)
    ->Arg(44)
    ->Arg(140)
    ->Arg(448)
    ->Arg(1414)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
