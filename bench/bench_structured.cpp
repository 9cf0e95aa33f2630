// The structured mesher over a size ladder: a generated 48-patch round-bilge half hull cut at its
// design draft, and (when ../shared/data/hulls holds them; HM_SHARED_DIR overrides ../shared)
// ship_449_patches.iges and dtmb5415.iges cut at z = 0, meshed by mesh_structured with automatic
// blocks to about 2,000, 8,000 and 32,000 panels at 1 and 2 threads (items/s: output panels per
// second). Each surface is prepared once per size, untimed, as `hullmesh structured` prepares it:
// 10 fine triangles per panel (20,000 to 1,000,000), tessellated, merged, cut at the waterline,
// its features found and a HullQuery built on it. Then one strip zip (zip_chains) on its own.
// After the runs, main() prints, from the runs just made, the 1 -> 2 thread speed-up per hull and
// size and whether both thread counts gave the same mesh (they must: the mesher is documented as
// thread-count independent).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli/prepare_hull.h"
#include "cli/tune_allocator.h"
#include "iges/read_iges.h"
#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "query/hull_query.h"
#include "structured/structured.h"
#include "structured/structured_steps.h"
#include "tessellate/tessellate.h"
#include "unstructured/cut_at_plane.h"
#include "unstructured/features.h"
#include "unstructured/merge.h"

namespace hm {
namespace {

// A hull to mesh: its patches and the waterline it is cut at (m, its own frame).
struct Source {
  std::string name;
  std::vector<Patch> patches;
  double waterline_z = 0;
};

// Index 0: the generated hull; then the shared hulls that are present.
const std::vector<Source>& sources() {
  static const std::vector<Source> s = [] {
    std::vector<Source> out;
    HullSpec spec;
    spec.kind = HullKind::kRoundBilge;
    spec.patches = 48;
    out.push_back({"generated round-bilge (48 patches)", generate_hull(spec).patches, spec.draft});
    const char* env = std::getenv("HM_SHARED_DIR");
    const std::filesystem::path dir =
        std::filesystem::path(env ? env : "../shared") / "data" / "hulls";
    for (const char* name : {"ship_449_patches.iges", "dtmb5415.iges"}) {
      std::error_code ec;
      const std::filesystem::path p = dir / name;
      if (std::filesystem::is_regular_file(p, ec)) {
        out.push_back({name, read_iges_file(p.string()).patches, 0.0});
      }
    }
    return out;
  }();
  return s;
}

// The wetted half hull, in metres, in the source's frame (cut at its waterline).
struct Wetted {
  PlaneCut cut;
  EdgeAdjacency adj;  // of cut.mesh
  FeatureSet features;
  std::unique_ptr<HullQuery> query;
};

// Prepared once per source and panel count, at the machine's full parallelism.
const Wetted& wetted(std::size_t source, std::size_t panels) {
  static std::map<std::pair<std::size_t, std::size_t>, std::unique_ptr<Wetted>> cache;
  auto it = cache.find({source, panels});
  if (it != cache.end()) return *it->second;
  const Source& src = sources()[source];
  auto w = std::make_unique<Wetted>();
  TessellateOptions o;
  // As `hullmesh structured` sizes its internal surface.
  o.edge_length = edge_length_for_triangles(src.patches, cli::structured_fine_triangles(panels));
  const Tessellation t = tessellate(src.patches, o, silent_progress());
  const MergedSurface merged = merge_patches(src.patches, t.mesh, {}, silent_progress());
  PlaneCutOptions co;
  co.value = src.waterline_z;
  w->cut = cut_at_plane(src.patches, merged.mesh, co);
  w->adj = build_edge_adjacency(w->cut.mesh.faces, w->cut.mesh.vertex_count());
  FeatureOptions fo;
  fo.waterline_z = src.waterline_z;
  w->features = find_features(w->cut.mesh, w->adj, src.patches, fo);
  w->query = std::make_unique<HullQuery>(src.patches, w->cut.mesh);
  return *cache.emplace(std::make_pair(source, panels), std::move(w)).first->second;
}

StructuredMesh run(const Source& src, const Wetted& w, std::size_t panels) {
  StructuredOptions o;
  o.target_panels = panels;
  return mesh_structured(src.patches, w.cut.mesh, w.adj, *w.query, w.features, o);
}

// What each (panels, threads) run gave, for the summary: best wall time and the last mesh.
struct Seen {
  double best_s = 1e300;
  SurfaceMesh mesh;
};
// Keyed by (source, target panels, threads).
std::map<std::tuple<std::size_t, std::size_t, int>, Seen>& seen() {
  static std::map<std::tuple<std::size_t, std::size_t, int>, Seen> s;
  return s;
}

// Args: source (0 generated, then the shared hulls present), target panels, threads.
void BM_MeshStructured(benchmark::State& state) {
  const std::size_t source = static_cast<std::size_t>(state.range(0));
  const std::size_t target = static_cast<std::size_t>(state.range(1));
  const int threads = static_cast<int>(state.range(2));
  if (source >= sources().size()) {
    state.SkipWithError("shared hull not present");
    return;
  }
  const Source& src = sources()[source];
  const Wetted& w = wetted(source, target);
  state.SetLabel(src.name);
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(threads));
  Seen& s = seen()[{source, target, threads}];
  StructuredMesh m;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    m = run(src, w, target);
    s.best_s = std::min(
        s.best_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  const std::size_t panels = m.mesh.face_count();
  state.counters["panels"] = static_cast<double>(panels);
  state.counters["quads"] = static_cast<double>(m.report.quads + m.report.cap_quads);
  state.counters["stations"] = static_cast<double>(m.report.stations);
  state.counters["fine_triangles"] = static_cast<double>(w.cut.mesh.face_count());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(panels));
  s.mesh = std::move(m.mesh);
}
BENCHMARK(BM_MeshStructured)
    ->ArgNames({"hull", "panels", "threads"})
    ->ArgsProduct({{0, 1, 2}, {2'000, 8'000, 32'000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// One strip: a chain of n + 1 nodes zipped against one of n + n / 10 + 1 (a row that grew by a
// tenth), both straight and parallel, one panel apart. Items: faces made.
void BM_ZipChains(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), m = n + n / 10;
  std::vector<Vec3d> pos;
  std::vector<Index> a, b;
  std::vector<double> fa, fb;
  for (int i = 0; i <= n; ++i) {
    a.push_back(static_cast<Index>(pos.size()));
    fa.push_back(double(i) / n);
    pos.push_back({0, double(i), 0});
  }
  for (int k = 0; k <= m; ++k) {
    b.push_back(static_cast<Index>(pos.size()));
    fb.push_back(double(k) / m);
    pos.push_back({1, double(k) * n / m, 0});
  }
  std::vector<Face> faces;
  for (auto _ : state) {
    faces.clear();
    benchmark::DoNotOptimize(structured::zip_chains(a, fa, b, fb, pos, {}, faces));
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(faces.size()));
}
BENCHMARK(BM_ZipChains)->Arg(100)->Arg(10'000);

void print_summary() {
  std::printf("\nmesh_structured at the waterline, automatic blocks, best wall time:\n");
  std::printf("  %-36s %8s %8s %10s %10s %9s %12s\n", "hull", "target", "panels", "1 thread",
              "2 threads", "speed-up", "same mesh");
  for (std::size_t source = 0; source < sources().size(); ++source) {
    for (std::size_t target : {2'000u, 8'000u, 32'000u}) {
      auto one = seen().find({source, target, 1}), two = seen().find({source, target, 2});
      if (one == seen().end() || two == seen().end()) continue;
      const SurfaceMesh &m1 = one->second.mesh, &m2 = two->second.mesh;
      const bool same = m1.faces == m2.faces && m1.positions == m2.positions;
      std::printf("  %-36s %8zu %8zu %9.3fs %9.3fs %8.2fx %12s\n", sources()[source].name.c_str(),
                  target, m1.face_count(), one->second.best_s, two->second.best_s,
                  one->second.best_s / two->second.best_s,
                  same ? "yes" : ("NO (" + std::to_string(m2.face_count()) + " panels)").c_str());
    }
  }
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
  hm::print_summary();
  return 0;
}
