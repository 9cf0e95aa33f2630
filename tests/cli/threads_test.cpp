// Thread stress: every command that runs parallel code writes the same bytes with 1, 2 and 8
// threads. 8 is more threads than CI's cores (`--threads` sizes the task arena, not only the
// limit), so tasks interleave and steal in ways that 2 threads on 2 cores rarely show. Under
// `scripts/test --tsan` the same runs are the race search of every parallel stage. Small hulls,
// so that the TSan run stays in minutes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_support.h"

namespace {

namespace fs = std::filesystem;
namespace test = hm::test;

using test::q;

// The file's bytes; for IGES, without the global section, which names the file itself.
std::string read_bytes(const fs::path& p) {
  if (p.extension() != ".igs") return test::file_bytes(p);
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  for (std::string line; std::getline(in, line);) {
    if (line.size() < 73 || line[72] != 'G') s << line << '\n';
  }
  return s.str();
}

// A small full (two-sided) hull with a knuckle and a transom: 8 patches, so the patch loops,
// the merge seams and the centre-plane handling all have work. Written into `dir`.
fs::path hull(const fs::path& dir) {
  const fs::path igs = dir / "chine.igs";
  const auto g =
      test::run_hullmesh("-q generate chine --length 40 --patches 8 --full -o " + q(igs));
  EXPECT_EQ(g.exit_code, 0) << g.out;
  return igs;
}

// Runs `hullmesh --threads T ARGS` for T in 1, 2, 8, each writing into its own folder (ARGS names
// it as {dir}), and expects every file in `outputs` to have the same bytes as with 1 thread.
void expect_same_bytes(const std::string& name, const std::string& args,
                       const std::vector<std::string>& outputs, int exit_code = 0) {
  const fs::path root = test::scratch_dir("threads_run_" + name);
  std::vector<std::string> first(outputs.size());
  for (int threads : test::kThreadCounts) {
    const fs::path dir = root / std::to_string(threads);
    fs::create_directories(dir);
    std::string cmd = args;
    for (std::size_t at; (at = cmd.find("{dir}")) != std::string::npos;) {
      cmd.replace(at, 5, dir.string());
    }
    const auto r =
        test::run_hullmesh("-q --no-run-json --threads " + std::to_string(threads) + " " + cmd);
    ASSERT_EQ(r.exit_code, exit_code) << name << " with " << threads << " threads:\n" << r.out;
    for (std::size_t k = 0; k < outputs.size(); ++k) {
      const std::string bytes = read_bytes(dir / outputs[k]);
      ASSERT_FALSE(bytes.empty()) << outputs[k] << " with " << threads << " threads";
      if (threads == 1) {
        first[k] = bytes;
      } else {
        EXPECT_TRUE(bytes == first[k])
            << name << ": " << outputs[k] << " differs between 1 and " << threads << " threads";
      }
    }
  }
}

TEST(Threads, GenerateAndTessellate) {
  const fs::path src = hull(test::scratch_dir("threads_hull_tessellate"));
  expect_same_bytes("generate", "generate round-bilge --patches 12 -o {dir}/g.igs", {"g.igs"});
  expect_same_bytes("tessellate", "tessellate " + q(src) + " --triangles 20000 -o {dir}/t.vtu",
                    {"t.vtu"});
}

TEST(Threads, SectionAndMerge) {
  const fs::path src = hull(test::scratch_dir("threads_hull_merge"));
  expect_same_bytes("section", "section " + q(src) + " --stations 16 --waterlines 4 -o {dir}/s.csv",
                    {"s.csv"});
  expect_same_bytes("merge",
                    "merge " + q(src) + " --triangles 20000 -o {dir}/m.vtu --waterline-z 2",
                    {"m.vtu", "m_knuckles.vtk", "m_boundaries.vtk"});
}

TEST(Threads, Unstructured) {
  const fs::path src = hull(test::scratch_dir("threads_hull_unstructured"));
  expect_same_bytes("unstructured",
                    "unstructured " + q(src) +
                        " --panels 500 --triangles 12000 --draft 2 --trim 1 --lid -o {dir}/u.gdf",
                    {"u.gdf", "u_lid.gdf"});
}

TEST(Threads, Structured) {
  const fs::path src = hull(test::scratch_dir("threads_hull_structured"));
  expect_same_bytes("structured",
                    "structured " + q(src) + " --panels 500 --draft 2 --trim 1 -o {dir}/s.gdf",
                    {"s.gdf"});
}

TEST(Threads, QualityAndRender) {
  const fs::path dir = test::scratch_dir("threads_hull_quality");
  const fs::path src = hull(dir);
  const fs::path mesh = dir / "panels.obj";
  const auto m = test::run_hullmesh("-q --no-run-json unstructured " + q(src) +
                                    " --panels 400 --triangles 8000 --draft 2 -o " + q(mesh));
  ASSERT_EQ(m.exit_code, 0) << m.out;
  // Exit 7: a 400-panel hull fails the panel-code rules at this speed; the report is written.
  const auto gate = test::run_hullmesh("-q quality " + q(mesh) + " --froude 0.3");
  ASSERT_TRUE(gate.exit_code == 0 || gate.exit_code == 7) << gate.out;
  expect_same_bytes("quality", "quality " + q(mesh) + " --froude 0.3 -o {dir}/q.vtu", {"q.vtu"},
                    gate.exit_code);
  expect_same_bytes(
      "render", "render " + q(mesh) + " --view iso --width 200 --color side_ratio -o {dir}/r.png",
      {"r.png"});
}

TEST(Threads, Batch) {
  const fs::path dir = test::scratch_dir("threads_batch");
  const fs::path src = hull(dir);
  {
    std::ofstream m(dir / "sweep.json");
    m << R"({"hulls": [{"name": "chine", "file": ")" << src.string() << R"("}],
             "grid": {"mesher": ["unstructured", "structured"], "draft": [1.5, 2.5],
                      "panels": [200]},
             "options": {"triangles": 6000}})";
  }
  // Four jobs at once with 8 threads: the jobs and the loops inside them share the arena.
  const std::vector<std::string> outputs = {
      "chine_unstructured_draft-1.5_panels-200.gdf", "chine_unstructured_draft-2.5_panels-200.gdf",
      "chine_structured_draft-1.5_panels-200.gdf", "chine_structured_draft-2.5_panels-200.gdf"};
  expect_same_bytes("batch", "batch " + q(dir / "sweep.json") + " --out {dir}", outputs);
}

}  // namespace
