// hullmesh quality MESH: the panel-code rules, topology, wave resolution and hydrostatics of a
// mesh (any format read_mesh knows, so meshes of other tools are judged by the same rules).
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "cli/load_hull.h"
#include "core/error.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "quality/hydrostatics.h"
#include "quality/quality_report.h"

namespace hm::cli {
namespace {

struct QualityCliOptions {
  std::string file;
  bool json = false;
  std::optional<double> speed, froude, length, waterline_z;
  bool half = false;
  std::string vtu;
};

void print_hydrostatics(const Hydrostatics& h) {
  std::printf("\n  hydrostatics at the waterline (mesh)\n");
  std::printf("  %-30s %.6g m^3\n", "displaced volume", h.volume);
  std::printf("  %-30s %.6g m^2\n", "wetted area", h.wetted_area);
  std::printf("  %-30s %.6g m^2\n", "waterplane area", h.waterplane_area);
  std::printf("  %-30s (%.6g, %.6g, %.6g) m\n", "centre of buoyancy", h.buoyancy_centre.x,
              h.buoyancy_centre.y, h.buoyancy_centre.z);
  std::printf("  %-30s (%.6g, %.6g) m\n", "centre of flotation", h.flotation_centre.x,
              h.flotation_centre.y);
  std::printf("  %-30s I_T %.6g m^4, I_L %.6g m^4\n", "waterplane moments", h.i_transverse,
              h.i_longitudinal);
  std::printf("  %-30s BM_T %.6g m, BM_L %.6g m\n", "metacentric radii", h.bm_transverse,
              h.bm_longitudinal);
}

int run_quality(const QualityCliOptions& o, const GlobalOptions& g) {
  if (o.froude && !o.length)
    std::fprintf(stderr,
                 "hullmesh: note: no --length; the Froude number uses the waterline "
                 "length of the mesh\n");
  const MeshFile file = read_mesh(o.file);
  QualityOptions q;
  q.waterline_z = o.waterline_z;
  // --half or the file's own symmetry flag; otherwise detected from the vertices.
  if (o.half || file.info.symmetry.about_y0) q.half_hull = true;
  q.waves.speed = o.speed;
  q.waves.froude = o.froude;
  q.waves.length = o.length;
  const SelfIntersections crossings = measure_crossings(file.mesh);
  q.crossing_pairs = crossings.count;
  if (crossings.count > 0) q.crossing_where = crossings.first.front().where;
  const QualityReport report = assess_quality(file.mesh, q);
  FloatingPosition position;
  position.waterline_z = report.topology.waterline_z;
  position.half_hull = report.half_hull;
  const Hydrostatics hydro = hydrostatics_mesh(file.mesh, position);

  if (o.json) {
    nlohmann::json j = nlohmann::json::parse(to_json(report, q.rules));
    j["file"] = o.file;
    j["hydrostatics"] = {
        {"volume_m3", hydro.volume},
        {"wetted_area_m2", hydro.wetted_area},
        {"waterplane_area_m2", hydro.waterplane_area},
        {"buoyancy_centre_m",
         {hydro.buoyancy_centre.x, hydro.buoyancy_centre.y, hydro.buoyancy_centre.z}},
        {"flotation_centre_m", {hydro.flotation_centre.x, hydro.flotation_centre.y}},
        {"i_transverse_m4", hydro.i_transverse},
        {"i_longitudinal_m4", hydro.i_longitudinal},
        {"bm_transverse_m", hydro.bm_transverse},
        {"bm_longitudinal_m", hydro.bm_longitudinal}};
    std::printf("%s\n", j.dump(2).c_str());
  } else if (!g.quiet) {
    std::printf("%s\n%s", o.file.c_str(), format_table(report, q.rules).c_str());
    print_hydrostatics(hydro);
  }
  if (report.waves.warn && !o.json)
    std::fprintf(stderr, "hullmesh: warning: %.3g panels per wavelength (under 10)\n",
                 report.waves.panels_per_wavelength);
  if (!o.vtu.empty()) {
    MeshWriteOptions w;
    w.face_fields = face_fields(report);
    w.info.title = "hullmesh quality " + file_name(o.file);
    write_mesh(o.vtu, file.mesh, w);
  }
  return report.passes(q.rules) ? static_cast<int>(ExitCode::kOk)
                                : static_cast<int>(ExitCode::kQualityGate);
}

}  // namespace

void register_quality(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto opts = std::make_shared<QualityCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "quality", "Judge a panel mesh by the panel-code rules; exit code 7 when it fails them");
  cmd->add_option("mesh", opts->file, "Mesh file (any format hullmesh reads)")->required();
  cmd->add_flag("--json", opts->json, "Print JSON instead of a table");
  auto* speed =
      cmd->add_option("--speed", opts->speed, "Ship speed U, m/s")->check(CLI::PositiveNumber);
  auto* froude = cmd->add_option("--froude", opts->froude, "Froude number Fn = U / sqrt(g L)")
                     ->check(CLI::PositiveNumber);
  speed->excludes(froude);
  cmd->add_option("--length", opts->length, "Length L for the Froude number, m")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--waterline-z", opts->waterline_z,
                  "Waterplane z in the mesh frame, m (default: the top of the mesh)");
  cmd->add_flag("--half", opts->half, "The mesh is a half hull (y >= 0), symmetric about y = 0");
  cmd->add_option("-o,--output", opts->vtu, "Write the per-panel measures as cell data (.vtu)");
  cmd->callback([opts, &global, &action] {
    action = [opts, &global] { return run_quality(*opts, global); };
  });
}

}  // namespace hm::cli
