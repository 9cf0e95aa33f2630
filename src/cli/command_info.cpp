// hullmesh info FILE: what an engineer wants to see first about an IGES hull file.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/entity_names.h"
#include "core/parallel.h"
#include "iges/read_iges.h"

namespace hm::cli {
namespace {

struct InfoOptions {
  std::string file;
  std::string units;
  bool json = false;
  bool list_patches = false;
};

// Which side of the centre plane the surfaces occupy, from the bounding box.
std::string hull_side(const BBox3d& box) {
  const double tol = 1e-3 * std::max(box.extent().x, 1e-12);
  if (box.lo.y > -tol && box.hi.y > tol) return "half hull, port side (y >= 0)";
  if (box.hi.y < tol && box.lo.y < -tol) return "half hull, starboard side (y <= 0)";
  return "full hull (both sides of y = 0)";
}

std::string declared_units(const IgesHeader& h) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s (G14 flag %d, G13 scale %g)",
                h.unit_name.empty() ? "?" : h.unit_name.c_str(), h.unit_flag, h.model_scale);
  return buf;
}

nlohmann::json to_json(const ImportResult& r, const std::vector<double>& areas,
                       const std::string& file) {
  using nlohmann::json;
  json j;
  j["file"] = file;
  j["header"] = {{"sending_system", r.header.sending_system},
                 {"file_name", r.header.file_name},
                 {"native_system", r.header.native_system},
                 {"preprocessor", r.header.preprocessor},
                 {"author", r.header.author},
                 {"organisation", r.header.organisation},
                 {"date", r.header.date}};
  j["units"] = {{"declared", r.header.unit_name},
                {"unit_flag", r.header.unit_flag},
                {"model_scale", r.header.model_scale},
                {"declared_to_metres", r.units.declared_to_metres},
                {"applied_to_metres", r.units.applied_to_metres},
                {"forced", r.units.forced},
                {"implausible", r.units.implausible},
                {"suggestion", r.units.suggestion}};
  std::map<std::string, int> by_wrapping, by_type;
  double total_area = 0;
  json patches = json::array();
  for (std::size_t i = 0; i < r.patches.size(); ++i) {
    const Patch& p = r.patches[i];
    by_wrapping[to_string(p.wrapping)] += 1;
    by_type[std::to_string(p.source_type)] += 1;
    total_area += areas[i];
    patches.push_back({{"index", i},
                       {"de", p.de},
                       {"wrapper_de", p.wrapper_de},
                       {"type", p.source_type},
                       {"wrapping", to_string(p.wrapping)},
                       {"name", p.name},
                       {"degree", {p.surface.degree_u, p.surface.degree_v}},
                       {"control_net", {p.surface.count_u, p.surface.count_v}},
                       {"loops", p.loops.size()},
                       {"reversed", p.reversed},
                       {"area_m2", areas[i]}});
  }
  j["patch_count"] = r.patches.size();
  j["patches_by_wrapping"] = by_wrapping;
  j["patches_by_type"] = by_type;
  j["bbox_m"] = {{"min", {r.bbox.lo.x, r.bbox.lo.y, r.bbox.lo.z}},
                 {"max", {r.bbox.hi.x, r.bbox.hi.y, r.bbox.hi.z}}};
  j["hull_side"] = hull_side(r.bbox);
  j["surface_area_m2"] = total_area;
  json groups = json::array();
  for (const IgesGroup& g : r.groups)
    groups.push_back({{"de", g.de}, {"name", g.name}, {"members", g.member_des.size()}});
  j["groups"] = groups;
  json skipped = json::object();
  for (const auto& [type, n] : r.skipped_by_type) skipped[std::to_string(type)] = n;
  j["skipped_by_type"] = skipped;
  json entities = json::object();
  for (const auto& [type, n] : r.entities_by_type) entities[std::to_string(type)] = n;
  j["entities_by_type"] = entities;
  json diags = json::array();
  for (const Diagnostic& d : r.diagnostics.items())
    diags.push_back({{"severity", to_string(d.severity)},
                     {"de", d.de},
                     {"line", d.line},
                     {"type", d.entity_type},
                     {"message", d.message}});
  j["diagnostics"] = diags;
  j["patches"] = patches;
  return j;
}

void print_table(const ImportResult& r, const std::vector<double>& areas, const InfoOptions& o,
                 const GlobalOptions& g) {
  const IgesHeader& h = r.header;
  std::printf("%s\n", o.file.c_str());
  auto row = [](const char* key, const std::string& value) {
    std::printf("  %-16s %s\n", key, value.c_str());
  };
  std::string system = h.sending_system;
  if (!h.native_system.empty() && h.native_system != system) system += " / " + h.native_system;
  row("sent by", system.empty() ? "(not stated)" : system);
  if (!h.date.empty()) row("file date", h.date);
  if (!h.author.empty() || !h.organisation.empty())
    row("author", h.author + (h.organisation.empty() ? "" : ", " + h.organisation));
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s; to metres x %g%s", declared_units(h).c_str(),
                r.units.applied_to_metres, r.units.forced ? " (forced by --units)" : "");
  row("units", buf);
  if (r.units.implausible)
    row("",
        "WARNING: extents implausible for a ship in the declared unit" +
            (r.units.suggestion.empty() ? std::string() : "; try --units " + r.units.suggestion));

  std::map<std::string, int> by_wrapping;
  std::map<int, int> by_type;
  for (const Patch& p : r.patches) {
    by_wrapping[to_string(p.wrapping)] += 1;
    by_type[p.source_type] += 1;
  }
  std::string wraps;
  for (const auto& [w, n] : by_wrapping)
    wraps += (wraps.empty() ? "" : ", ") + std::to_string(n) + " " + w;
  std::snprintf(buf, sizeof buf, "%zu (%s)", r.patches.size(), wraps.c_str());
  row("patches", buf);
  std::string types;
  for (const auto& [t, n] : by_type)
    types += (types.empty() ? "" : ", ") + std::to_string(n) + " x " + std::to_string(t) + " " +
             iges_entity_name(t);
  row("surface types", types);
  if (!r.bbox.empty()) {
    std::snprintf(buf, sizeof buf, "x [%.6g, %.6g]  y [%.6g, %.6g]  z [%.6g, %.6g] m", r.bbox.lo.x,
                  r.bbox.hi.x, r.bbox.lo.y, r.bbox.hi.y, r.bbox.lo.z, r.bbox.hi.z);
    row("bounding box", buf);
    const Vec3d e = r.bbox.extent();
    std::snprintf(buf, sizeof buf, "%.6g x %.6g x %.6g m (%s)", e.x, e.y, e.z,
                  hull_side(r.bbox).c_str());
    row("extents", buf);
  }
  double total = 0;
  for (double a : areas) total += a;
  std::snprintf(buf, sizeof buf, "%.6g m^2 (NURBS, inside trims)", total);
  row("surface area", buf);

  std::vector<std::string> names;
  for (const Patch& p : r.patches)
    if (!p.name.empty()) names.push_back(p.name);
  if (!names.empty()) {
    std::string s;
    for (std::size_t i = 0; i < names.size() && i < 8; ++i) s += (i ? ", " : "") + names[i];
    if (names.size() > 8) s += ", ... (" + std::to_string(names.size()) + " named)";
    row("names", s);
  }
  for (const IgesGroup& gr : r.groups) {
    std::snprintf(buf, sizeof buf, "DE %d %s: %zu members", gr.de,
                  gr.name.empty() ? "(unnamed)" : gr.name.c_str(), gr.member_des.size());
    row("group", buf);
  }
  if (!r.skipped_by_type.empty()) {
    std::string s;
    int total_skipped = 0;
    for (const auto& [t, n] : r.skipped_by_type) {
      s += (s.empty() ? "" : ", ") + std::to_string(n) + " x " + std::to_string(t) + " " +
           iges_entity_name(t);
      total_skipped += n;
    }
    row("skipped", std::to_string(total_skipped) + " without a hull surface: " + s);
  }
  const Diagnostics& d = r.diagnostics;
  std::snprintf(buf, sizeof buf, "%zu errors, %zu warnings, %zu notes", d.count(Severity::kError),
                d.count(Severity::kWarning), d.count(Severity::kNote));
  row("diagnostics", buf);
  for (const Diagnostic& di : d.items())
    if (di.severity != Severity::kNote || g.verbose) std::printf("    %s\n", format(di).c_str());

  if (o.list_patches || g.verbose) {
    std::printf("\n  %5s %6s %4s %-9s %7s %9s %5s %4s %12s  %s\n", "patch", "DE", "type",
                "wrapping", "degree", "net", "loops", "rev", "area m^2", "name");
    for (std::size_t i = 0; i < r.patches.size(); ++i) {
      const Patch& p = r.patches[i];
      std::printf("  %5zu %6d %4d %-9s %3d x %-2d %4d x %-4d %5zu %4s %12.6g  %s\n", i, p.de,
                  p.source_type, to_string(p.wrapping), p.surface.degree_u, p.surface.degree_v,
                  p.surface.count_u, p.surface.count_v, p.loops.size(), p.reversed ? "yes" : "",
                  areas[i], p.name.c_str());
    }
  }
}

int run_info(const InfoOptions& o, const GlobalOptions& g) {
  ImportOptions import;
  import.force_units = o.units;
  const ImportResult r = read_iges_file(o.file, import);
  std::vector<double> areas(r.patches.size(), 0.0);
  parallel_for_each_item(r.patches.size(),
                         [&](std::size_t i) { areas[i] = patch_area(r.patches[i]); });
  if (o.json) {
    std::printf("%s\n", to_json(r, areas, o.file).dump(2).c_str());
  } else if (!g.quiet) {
    print_table(r, areas, o, g);
  }
  return 0;
}

}  // namespace

void register_info(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Summarise an IGES hull: sender, units, patches, extents, area, diagnostics");
  cmd->add_option("file", opts->file, "IGES file")->required();
  cmd->add_flag("--json", opts->json, "Print JSON instead of a table");
  cmd->add_flag("--patches", opts->list_patches, "List every patch");
  cmd->add_option("--units", opts->units,
                  "Force the file's unit (m, mm, cm, in, ft, km), overriding G14/G15")
      ->check(CLI::IsMember({"m", "mm", "cm", "in", "ft", "km"}));
  cmd->callback(
      [opts, &global, &action] { action = [opts, &global] { return run_info(*opts, global); }; });
}

}  // namespace hm::cli
