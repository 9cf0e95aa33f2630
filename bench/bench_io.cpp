// Mesh writers and readers on a panel ladder (10^3, 10^4, 10^5 panels), in memory: the text
// formatting and parsing cost, without the disk. Arguments: panel count, format index (in
// mesh_formats() order). Then the run record's SHA-256, both ways.
#include <benchmark/benchmark.h>

#include <cmath>
#include <sstream>
#include <string>

#include "io/read_mesh.h"
#include "io/sha256.h"
#include "io/write_mesh.h"

namespace hm {
namespace {

// A half cylinder of quads (every tenth split into two triangles), about `panels` faces, on
// ten patches by station.
SurfaceMesh ladder_mesh(int panels) {
  const int nu = static_cast<int>(std::sqrt(panels * 4.0));
  const int nv = std::max(1, panels / nu);
  SurfaceMesh m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const double a = M_PI * j / nv;
      m.positions.push_back({100.0 * i / nu, 8.0 * std::cos(a), -8.0 * std::sin(a)});
    }
  auto at = [&](int i, int j) { return Index(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const PatchId p = PatchId(10 * i / nu);
      if ((i + j) % 10 == 0) {
        m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), kInvalid});
        m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1), kInvalid});
        m.face_patch.insert(m.face_patch.end(), {p, p});
      } else {
        m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        m.face_patch.push_back(p);
      }
    }
  return m;
}

void BM_Write(benchmark::State& state) {
  const SurfaceMesh m = ladder_mesh(static_cast<int>(state.range(0)));
  const MeshFormat f = mesh_formats()[state.range(1)];
  state.SetLabel(f.extension);
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::ostringstream out;
    write_mesh_to(out, f.extension, m);
    bytes = out.str().size();
    benchmark::DoNotOptimize(bytes);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * m.faces.size()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
}

void BM_Read(benchmark::State& state) {
  const SurfaceMesh m = ladder_mesh(static_cast<int>(state.range(0)));
  const MeshFormat f = mesh_formats()[state.range(1)];
  state.SetLabel(f.extension);
  std::ostringstream out;
  write_mesh_to(out, f.extension, m);
  const std::string text = out.str();
  for (auto _ : state) {
    MeshFile r = read_mesh_from_memory(text, f.extension, "bench");
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * m.faces.size()));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
}

void ladder(benchmark::internal::Benchmark* b) {
  for (int f = 0; f < static_cast<int>(mesh_formats().size()); ++f)
    for (int n : {1000, 10000, 100000}) b->Args({n, f});
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Write)->Apply(ladder);
BENCHMARK(BM_Read)->Apply(ladder);

// SHA-256 of 16 MB, as the run record hashes every input and output: the x86 SHA extensions
// (arg 0, where the processor has them) against the plain C++ rounds (arg 1). Items are bytes.
void BM_Sha256(benchmark::State& state) {
  std::string data(16 << 20, '\0');
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<char>(i * 2654435761u >> 24);
  for (auto _ : state) {
    hm::Sha256 h(state.range(0) != 0);
    h.update(data.data(), data.size());
    benchmark::DoNotOptimize(h.finish());
  }
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(data.size()));
  state.SetLabel(hm::Sha256(state.range(0) != 0).uses_cpu_instructions() ? "SHA extensions"
                                                                         : "plain C++");
}
BENCHMARK(BM_Sha256)->ArgName("portable")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace hm

BENCHMARK_MAIN();
