// JSON helpers for the tests that read hullmesh's reports. Apart from test_support.h so that the
// tests that read no JSON do not compile nlohmann/json.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace hm::test {

// A JSON file's value; a discarded value (is_discarded()) when it is missing or not JSON.
nlohmann::json read_json(const std::filesystem::path& path);
// `hullmesh quality --json MESH`'s report; a discarded value when the command printed no JSON.
nlohmann::json quality_json(const std::filesystem::path& mesh);

// Whether a line of a run record's quality failures is a share rule ("...: 96.7% pass, need
// 98%") or the warp, which are the meshers' goals; every other line is a hard rule.
inline bool is_share_rule(const std::string& failure) {
  return failure.find("% pass, need") != std::string::npos || failure.rfind("max warp", 0) == 0;
}

}  // namespace hm::test
