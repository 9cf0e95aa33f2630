// JSON helpers for the tests that read hullmesh's reports. Apart from test_support.h so that the
// tests that read no JSON do not compile nlohmann/json.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

namespace hm::test {

// A JSON file's value; a discarded value (is_discarded()) when it is missing or not JSON.
nlohmann::json read_json(const std::filesystem::path& path);
// `hullmesh quality --json MESH`'s report; a discarded value when the command printed no JSON.
nlohmann::json quality_json(const std::filesystem::path& mesh);

}  // namespace hm::test
