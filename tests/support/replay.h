// Replays of property-test cases (tests/cli/property_test.cpp) where a mesher broke a hard
// panel-code rule: each hull is generated again, meshed at its floating draft under --validate,
// and must come out closed below the waterline and break no hard rule (the share rules are
// issues 5 and 6's goals, not asserted here).
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "support/test_json.h"
#include "support/test_support.h"

namespace hm::test {

struct Replay {
  const char* name;
  const char* generate;  // `hullmesh generate` arguments
  const char* draft;     // m
  int panels;
  const char* position = "";  // more floating options (a trim)
};

// `mesher` is the subcommand (structured or unstructured); `scratch` names the scratch folder.
inline void expect_replays_break_no_hard_rule(const std::string& mesher,
                                              std::span<const Replay> cases,
                                              const std::string& scratch) {
  namespace fs = std::filesystem;
  const fs::path dir = scratch_dir(scratch);
  for (const Replay& c : cases) {
    const fs::path igs = dir / "hull.igs", out = dir / "panels.obj";
    ASSERT_EQ(run_hullmesh(std::string("-q generate ") + c.generate + " -o " + q(igs)).exit_code, 0)
        << c.name;
    const auto r =
        run_hullmesh("-q --validate " + mesher + " " + q(igs) + " -o " + q(out) + " --panels " +
                     std::to_string(c.panels) + " --draft " + c.draft + " " + c.position);
    ASSERT_EQ(r.exit_code, 0) << c.name << ": " << r.out;
    const nlohmann::json record = read_json(fs::path(out).replace_extension(".run.json"));
    ASSERT_TRUE(record.is_object()) << c.name;
    EXPECT_EQ(record["quality"]["free_edges_below_waterline"], 0) << c.name;
    for (const std::string failure : record["quality"]["failures"]) {
      EXPECT_TRUE(is_share_rule(failure)) << c.name << ": " << failure;
    }
  }
}

}  // namespace hm::test
