// Property tests: generated hulls with random proportions, patch counts and defects (seeded, so
// every case can be replayed), each meshed by both meshers with the invariants checked between
// stages. Every mesh must be sound (exit 0 under --validate: manifold, consistently oriented, no
// zero-area panel, within the deviation bound, feature lines kept) and meet every hard panel-code
// rule. The share rules (side, area and normal-angle ratios) are issue 5's and 6's goals; they
// are printed, not asserted.
//
//   HM_PROPERTY_SEED=S    replay the one case with seed S
//   HM_PROPERTY_CASES=N   run N cases (default 8)
//   HM_PROPERTY_FIRST=S   from seed S (default 1000)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "support/test_json.h"
#include "support/test_support.h"

namespace hm {
namespace {

namespace fs = std::filesystem;
using test::is_share_rule;
using test::run_hullmesh;

using test::q;

struct Case {
  std::uint64_t seed = 0;
  std::string generate;  // `hullmesh generate` words, output excluded
  double draft = 0;      // m, the floating draft the meshers are given
  double trim = 0;       // degrees, bow down positive (HM_PROPERTY_WIDE only)
  int panels = 0;
  bool overlap = false;  // patches overlap: the file's exact volume counts the overlaps twice
};

// HM_PROPERTY_WIDE: gaps up to issue 4's 1e-3 L and trims (see random_case).
bool wide_mode() {
  static const bool wide = std::getenv("HM_PROPERTY_WIDE") != nullptr;
  return wide;
}

// Proportions within what ships have (L/B 4..12, B/T 2..4, freeboard up to 60% of T), 1 to 16
// patches, half or full hull, and the import issue's defects (gaps, repeated control points,
// flipped patches), each on or off at random.
Case random_case(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto uniform = [&](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
  };
  auto pick = [&](int n) {
    return static_cast<int>(std::uniform_int_distribution<int>(0, n - 1)(rng));
  };
  const char* kinds[] = {"wigley", "round-bilge", "chine"};
  const double length = uniform(40, 200);
  const double beam = length / uniform(4, 12);
  const double draft = beam / uniform(2, 4);
  const double depth = draft * uniform(1.2, 1.6);
  std::ostringstream g;
  g.precision(6);
  const char* kind = kinds[pick(3)];
  const int patches = 1 + pick(16);
  const bool full = pick(2) != 0;
  // A full hull has a patch a side at least.
  g << kind << " --length " << length << " --beam " << beam << " --draft " << draft << " --depth "
    << depth << " --patches " << (full ? std::max(2, patches) : patches) << " --seed " << seed;
  if (full) g << " --full";
  // Full hulls with gaps are in since 2026-12-04 (evening): until the snap let the two halves
  // meet at a fine stem or forefoot and where the hull is a fin of no thickness, their seam in
  // the centre plane stayed open below the waterline (Merge.FullHullHalvesWithGapsClose*).
  const bool gap = pick(3) == 0;
  // Overlapping patches (5% of a patch). The displacement check below is skipped for them: the
  // volume it compares against, the patches' exact integrals, counts every overlap twice (5-10%
  // off). Left out until 2026-12-04, when the merge and cut still left zero-area faces and an
  // edge with three faces on some of these hulls (now CutAtPlane.CrossingsInABridgedGap*,
  // Merge.CentrePlaneCornerOfAFlippedHalf*). All 32 cases (HM_PROPERTY_CASES=32) pass since
  // the evening of 2026-12-04, and all 64 since that night, when the structured mesher began to
  // split non-convex quads (seed 1063: its forefoot end cap had a quad with three corners on the
  // stem, mirrored onto its twin; SplitNonConvex.*). Of 200 on 2026-12-05, 1 fails: 1133 (the
  // unstructured mesher's two panels back to back at a full Wigley's forefoot, where the halves
  // are tangent, "very close"). 1035 (the structured bow cap open at a fold the merge left where
  // chine and stem meet) passes since Merge.DartHoleAtTheStem*; 9 of 160 failed the night before.
  const bool overlap = pick(3) == 0;
  if (overlap) g << " --overlap 0.05";
  if (pick(3) == 0) g << " --duplicate-points";
  if (pick(3) == 0) g << " --flip-every " << 2 + pick(3);
  Case c;
  c.seed = seed;
  c.overlap = overlap;
  c.draft = draft * uniform(0.6, 1.1);
  c.panels = 300 + 100 * pick(10);
  // HM_PROPERTY_WIDE: gaps up to issue 4's 1e-3 L and a trim of up to 1 degree either way, drawn
  // after everything else so that a seed's other draws stay what they were.
  const bool wide = wide_mode();
  const double gap_width = wide ? uniform(1e-4, 1e-3) * length : 1e-4 * length;
  if (wide && pick(2) == 0) {
    // Within what keeps the deck edge dry at both ends (the generated hulls have no deck: seed
    // 9349 trimmed 0.84 degrees by the stern with 0.75 m of freeboard put its stern's deck edge
    // 0.32 m under water, a true open boundary there).
    const double limit =
        std::atan(0.8 * (depth - c.draft) / (0.5 * length)) * 180 / std::numbers::pi;
    c.trim = uniform(-1, 1) * std::min(1.0, limit);
  }
  if (gap) g << " --gap " << gap_width;
  c.generate = g.str();
  return c;
}

void check_case(const Case& c, const fs::path& dir) {
  // The draft as the meshers are given it (six significant digits), so that the replay line
  // repeats the case by hand.
  std::ostringstream draft;
  draft << c.draft;
  std::ostringstream trim;
  if (c.trim != 0) trim << " --trim " << c.trim;
  const std::string replay = "replay with HM_PROPERTY_SEED=" + std::to_string(c.seed) +
                             (wide_mode() ? " HM_PROPERTY_WIDE=1" : "") + " (generate " +
                             c.generate + ", draft " + draft.str() + trim.str() + ", " +
                             std::to_string(c.panels) + " panels)";
  SCOPED_TRACE(replay);
  const fs::path igs = dir / ("hull_" + std::to_string(c.seed) + ".igs");
  const auto g = run_hullmesh("-q generate " + c.generate + " -o " + q(igs));
  ASSERT_EQ(g.exit_code, 0) << g.out;
  for (const std::string mesher : {"unstructured", "structured"}) {
    const fs::path out = dir / (mesher + "_" + std::to_string(c.seed) + ".obj");
    std::ostringstream args;
    args << "-q --threads 2 " << mesher << " " << q(igs) << " -o " << q(out) << " --panels "
         << c.panels << " --draft " << draft.str() << trim.str();
    const auto r = run_hullmesh(args.str());  // HULLMESH_VALIDATE=1: the invariants
    ASSERT_EQ(r.exit_code, 0) << mesher << ": " << r.out;
    const nlohmann::json record = test::read_json(fs::path(out).replace_extension(".run.json"));
    ASSERT_TRUE(record.is_object()) << mesher;
    const nlohmann::json& quality = record["quality"];
    std::string shares;
    for (const std::string failure : quality["failures"]) {
      EXPECT_TRUE(is_share_rule(failure)) << mesher << ": " << failure;
      if (is_share_rule(failure)) shares += "; " + failure;
    }
    EXPECT_EQ(quality["free_edges_below_waterline"], 0) << mesher;
    // The panels hold the hull's displacement (against the exact NURBS integrals): within 3%
    // (300 panels on L/B 12), or within one and a half times what their chords alone take off,
    // the mean deviation over the wetted area, where that is more. A shallow, wide hull has
    // little volume under much area: seed 1452, a full Wigley at B/T 6 in 300 panels, loses
    // 3.2% to panels a mean 17 mm inside the hull (3.5% of its 133 m^3 over 269 m^2), within
    // the deviation bound, and the structured mesher's 2.0%.
    const nlohmann::json& hydro = record["results"]["hydrostatics"];
    const double volume_error = hydro["volume_error"];
    const double chords = record["results"]["deviation_mean_m"].get<double>() *
                          hydro["wetted_area_m2"].get<double>() / hydro["volume_m3"].get<double>();
    if (!c.overlap) {
      EXPECT_LT(std::abs(volume_error), std::max(0.03, 1.5 * chords)) << mesher;
    }
    std::printf("seed %llu %s: %d panels, volume %+.3f%%%s\n",
                static_cast<unsigned long long>(c.seed), mesher.c_str(),
                quality["panels"].get<int>(), 100 * volume_error, shares.c_str());
  }
}

TEST(Property, RandomHullsWithDefectsMeshSoundlyWithBothMeshers) {
  const fs::path dir = test::scratch_dir("cli_property");
  if (const char* s = std::getenv("HM_PROPERTY_SEED")) {
    check_case(random_case(std::strtoull(s, nullptr, 10)), dir);
    return;
  }
  const char* n = std::getenv("HM_PROPERTY_CASES");
  const int cases = n ? std::atoi(n) : 8;
  const char* f = std::getenv("HM_PROPERTY_FIRST");
  const std::uint64_t first = f ? std::strtoull(f, nullptr, 10) : 1000;
  for (int k = 0; k < cases; ++k) {
    check_case(random_case(first + static_cast<std::uint64_t>(k)), dir);
  }
}

}  // namespace
}  // namespace hm
