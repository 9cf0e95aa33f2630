#include "cli/run_record.h"

#include <filesystem>

#include "cli/tune_allocator.h"
#include "io/atomic_file.h"
#include "io/sha256.h"

namespace hm::cli {
namespace {

using nlohmann::ordered_json;
namespace fs = std::filesystem;

// One option value as JSON: numbers as numbers when the option takes a number.
ordered_json value_json(const std::string& text, bool numeric) {
  if (numeric && !text.empty() && ordered_json::accept(text)) {
    ordered_json v = ordered_json::parse(text);
    if (v.is_number()) return v;
  }
  return text;
}

}  // namespace

ordered_json file_record(const std::string& path) {
  std::error_code ec;
  const auto bytes = fs::file_size(path, ec);
  return {{"path", path}, {"bytes", ec ? 0 : bytes}, {"sha256", sha256_file(path)}};
}

bool option_takes_number(const CLI::Option& opt) {
  // The type name carries the validators after a colon: "UINT:INT in [4 - 10000000]".
  const std::string type = opt.get_type_name();
  for (const char* t : {"FLOAT", "INT", "UINT", "NUMBER"}) {
    if (type == t || type.rfind(std::string(t) + ":", 0) == 0) return true;
  }
  return false;
}

ordered_json effective_options(const CLI::App& command) {
  ordered_json j = ordered_json::object();
  for (const CLI::Option* opt : command.get_options()) {
    const std::string name = opt->get_single_name();
    if (name == "help" || name == "h") continue;
    if (opt->get_expected_min() == 0) {  // a flag
      j[name] = opt->count() > 0;
      continue;
    }
    const bool numeric = option_takes_number(*opt);
    const bool many = opt->get_items_expected_max() > 1;
    if (opt->count() > 0) {
      const std::vector<std::string>& given = opt->results();
      if (many) {
        ordered_json a = ordered_json::array();
        for (const std::string& s : given) a.push_back(value_json(s, numeric));
        j[name] = a;
      } else {
        j[name] = value_json(given.back(), numeric);
      }
    } else {
      const std::string def = opt->get_default_str();
      j[name] = def.empty() ? ordered_json(nullptr) : value_json(def, numeric);
    }
  }
  return j;
}

ordered_json quality_summary(const QualityReport& r, const QualityRules& rules) {
  const TopologyFacts& t = r.topology;
  return {{"passes", r.passes(rules)},
          {"failures", r.failures(rules)},
          {"panels", r.faces},
          {"quads", r.quads},
          {"triangles", r.triangles},
          {"vertices", r.vertices},
          {"half_hull", r.half_hull},
          {"side_ratio_share", r.side_ratio_share},
          {"max_side_ratio", r.max_side_ratio},
          {"area_ratio_share", r.area_ratio_share},
          {"area_ratio_pair_share", r.area_ratio_pair_share},
          {"max_area_ratio", r.max_area_ratio},
          {"normal_angle_share", r.normal_angle_share},
          {"max_normal_angle_deg", r.max_normal_angle_deg},
          {"min_triangle_angle_deg", r.min_triangle_angle_deg},
          {"max_warp", r.max_warp},
          {"boundary_loops", t.boundary_loops},
          {"free_edges_below_waterline", t.free_edges_below},
          {"nonmanifold_edges", t.nonmanifold_edges},
          {"orientation_consistent", t.orientation_consistent},
          {"crossing_pairs", r.crossing_pairs ? ordered_json(*r.crossing_pairs) : nullptr}};
}

ordered_json hydrostatics_summary(const Hydrostatics& mesh, const Hydrostatics* exact) {
  ordered_json j = {{"volume_m3", mesh.volume},
                    {"wetted_area_m2", mesh.wetted_area},
                    {"waterplane_area_m2", mesh.waterplane_area},
                    {"lcb_m", mesh.buoyancy_centre.x}};
  if (exact) {
    auto rel = [](double a, double b) { return b != 0 ? (a - b) / b : 0.0; };
    j["volume_error"] = rel(mesh.volume, exact->volume);
    j["wetted_area_error"] = rel(mesh.wetted_area, exact->wetted_area);
    j["waterplane_area_error"] = rel(mesh.waterplane_area, exact->waterplane_area);
  }
  return j;
}

std::string record_path_for(const std::string& output) {
  fs::path p(output);
  p.replace_extension(".run.json");
  return p.string();
}

ordered_json record_json(const RunRecord& r) {
  ordered_json j;
  j["hullmesh"] = HULLMESH_VERSION;
  j["command"] = r.command;
  j["allocator"] = allocator_setting();
  if (!r.input.empty()) j["input"] = file_record(r.input);
  j["parameters"] = r.parameters;
  ordered_json outputs = ordered_json::array();
  for (const std::string& o : r.outputs) outputs.push_back(file_record(o));
  j["outputs"] = outputs;
  ordered_json stages = ordered_json::array();
  double total = 0;
  for (const auto& [name, seconds] : r.log.stages()) {
    stages.push_back({{"name", name}, {"seconds", seconds}});
    total += seconds;
  }
  j["stages"] = stages;
  j["seconds"] = total;
  j["results"] = r.results;
  j["quality"] = r.quality;
  return j;
}

void write_run_record(const RunRecord& r, const ordered_json& built) {
  if (r.outputs.empty()) return;
  write_file_atomically(record_path_for(r.outputs.front()),
                        [&](std::ostream& out) { out << built.dump(2) << '\n'; });
}

}  // namespace hm::cli
