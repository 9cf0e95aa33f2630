// IGES import: parsing real and generated hulls from memory (no disk in the loop).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "iges/read_iges.h"
#include "iges/write_iges.h"
#include "nurbs/evaluate_grid.h"
#include "nurbs/generate_hull.h"

namespace hm {
namespace {

std::string shared_file(const char* name) {
  const char* env = std::getenv("HM_SHARED_DIR");
  const std::filesystem::path p =
      std::filesystem::path(env ? env : "../shared") / "data" / "hulls" / name;
  std::ifstream in(p, std::ios::binary);
  if (!in) return {};
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void parse_text(benchmark::State& state, const std::string& text, const char* name) {
  if (text.empty()) {
    state.SkipWithError("input not present");
    return;
  }
  std::size_t patches = 0;
  for (auto _ : state) {
    ImportResult r = read_iges(text, name);
    patches = r.patches.size();
    benchmark::DoNotOptimize(r);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * patches));
  state.counters["patches"] = static_cast<double>(patches);
}

void BM_ParseShip449(benchmark::State& state) {
  static const std::string text = shared_file("ship_449_patches.iges");
  parse_text(state, text, "ship_449_patches.iges");
}
BENCHMARK(BM_ParseShip449)->Unit(benchmark::kMillisecond);

void BM_ParseKcs(benchmark::State& state) {
  static const std::string text = shared_file("kcs.iges");
  parse_text(state, text, "kcs.iges");
}
BENCHMARK(BM_ParseKcs)->Unit(benchmark::kMillisecond);

// The figure: parse ship_449_patches.iges, then evaluate a 100 x 100 grid on every patch.
void BM_ParseAndGrid449(benchmark::State& state) {
  static const std::string text = shared_file("ship_449_patches.iges");
  if (text.empty()) {
    state.SkipWithError("input not present");
    return;
  }
  std::size_t points = 0;
  for (auto _ : state) {
    const ImportResult r = read_iges(text, "ship_449_patches.iges");
    points = 0;
    for (const Patch& p : r.patches) {
      const SurfaceSamples g = evaluate_grid(p.surface, 100, 100);
      points += g.positions.size();
      benchmark::DoNotOptimize(g.positions.data());
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * points));
  state.counters["points"] = static_cast<double>(points);
}
BENCHMARK(BM_ParseAndGrid449)->Unit(benchmark::kMillisecond)->UseRealTime();

// Ladder: generated round-bilge hulls of 1, 10, 100 and 1000 patches.
void BM_ParseGenerated(benchmark::State& state) {
  HullSpec spec;
  spec.kind = HullKind::kRoundBilge;
  spec.patches = static_cast<int>(state.range(0));
  const std::string text = write_iges(generate_hull(spec).patches);
  parse_text(state, text, "generated");
}
BENCHMARK(BM_ParseGenerated)->Arg(1)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hm

BENCHMARK_MAIN();
