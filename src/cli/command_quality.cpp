// hullmesh quality MESH: the panel-code rules, topology, wave resolution and hydrostatics of a
// mesh (any format read_mesh knows, so meshes of other tools are judged by the same rules), its
// minimum-angle distribution and, with --iges, its deviation from the hull's NURBS.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/load_hull.h"
#include "cli/prepare_hull.h"
#include "core/bbox.h"
#include "core/error.h"
#include "core/progress.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "quality/hydrostatics.h"
#include "quality/quality_report.h"
#include "query/hull_query.h"
#include "tessellate/tessellate.h"
#include "unstructured/measure_deviation.h"

namespace hm::cli {
namespace {

struct QualityCliOptions {
  std::string file;
  bool json = false;
  std::optional<double> speed, froude, length, waterline_z;
  bool half = false;
  bool uncut = false;
  std::string vtu;
  std::string iges;  // --iges: the hull the mesh was made from, for the deviation
};

// The mesh against the NURBS of the IGES hull it was made from: the distance of every panel
// centroid and edge midpoint to the surface (measure_deviation). L is the largest extent of the
// IGES hull's box. Both must be in metres and in the same frame; a full-hull mesh of a half-hull
// file is measured against the file's patches and their mirror image about y = 0.
struct NurbsDeviation {
  DeviationMeasure measure;
  double length = 0;      // m
  bool mirrored = false;  // the patches' mirror image was added
};

// A mesh further than this share of L from the hull is not of this hull in this frame.
constexpr double kFarFromHull = 0.05;

NurbsDeviation deviation_from_nurbs(const std::string& iges, const SurfaceMesh& mesh, bool quiet) {
  ImportResult hull = load_hull(iges, "", quiet);
  if (hull.patches.empty()) throw InputError(iges + ": no surface to measure the deviation from");
  NurbsDeviation d;
  const Vec3d e = hull.bbox.extent();
  d.length = std::max({e.x, e.y, e.z});
  BBox3d box;
  for (const Vec3d& p : mesh.positions) box.add(p);
  const double tol = 1e-3 * d.length;
  if (hull.bbox.lo.y > -tol && box.lo.y < -tol) {
    add_mirror_image(hull);
    d.mirrored = true;
  }
  // The default tessellation suffices: the closest points are refined on the NURBS.
  TessellateOptions to;
  to.measure_chord = false;
  const Tessellation t = tessellate(hull.patches, to, silent_progress());
  const HullQuery query(hull.patches, t.mesh);
  d.measure = measure_deviation(query, mesh);
  return d;
}

void print_deviation(const std::string& iges, const NurbsDeviation& d) {
  const DeviationMeasure& m = d.measure;
  std::printf("\n  deviation from the NURBS of %s%s\n", iges.c_str(),
              d.mirrored ? " and its mirror image" : "");
  if (m.samples == 0) {
    std::printf("  %-30s n/a: no sample found a closest point\n", "max, mean");
    return;
  }
  std::printf("  %-30s %.4g m (%.3g L) at (%.4g, %.4g, %.4g) m\n", "max", m.max, m.max / d.length,
              m.where.x, m.where.y, m.where.z);
  std::printf("  %-30s %.4g m (%.3g L), %zu samples, L = %.4g m\n", "mean", m.mean,
              m.mean / d.length, m.samples, d.length);
}

nlohmann::json deviation_json(const std::string& iges, const NurbsDeviation& d) {
  const DeviationMeasure& m = d.measure;
  if (m.samples == 0) return {{"iges", iges}, {"samples", 0}, {"max_m", nullptr}};
  return {{"iges", iges},
          {"length_m", d.length},
          {"mirrored", d.mirrored},
          {"samples", m.samples},
          {"max_m", m.max},
          {"mean_m", m.mean},
          {"max_rel", m.max / d.length},
          {"mean_rel", m.mean / d.length},
          {"max_where_m", {m.where.x, m.where.y, m.where.z}},
          {"far_from_hull", m.max > kFarFromHull * d.length}};
}

void print_mesh_hydrostatics(const Hydrostatics& h) {
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
  q.uncut = o.uncut;
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
  const AngleDistribution& angles = report.min_angle;
  std::optional<NurbsDeviation> deviation;
  if (!o.iges.empty()) deviation = deviation_from_nurbs(o.iges, file.mesh, g.quiet || o.json);

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
    j["min_angle_deg"] = {{"share_20", angles.share_20}, {"share_30", angles.share_30},
                          {"share_40", angles.share_40}, {"p05", angles.p05},
                          {"p50", angles.p50},           {"p95", angles.p95}};
    if (deviation) j["deviation"] = deviation_json(o.iges, *deviation);
    std::printf("%s\n", j.dump(2).c_str());
  } else if (!g.quiet) {
    std::printf("%s\n%s", o.file.c_str(), format_table(report, q.rules).c_str());
    std::printf(
        "\n  %-30s >= 20: %.1f%%, >= 30: %.1f%%, >= 40: %.1f%%; 5%% / 50%% / 95%%: %.3g / %.3g / "
        "%.3g deg\n",
        "panel min angle", 100 * angles.share_20, 100 * angles.share_30, 100 * angles.share_40,
        angles.p05, angles.p50, angles.p95);
    print_mesh_hydrostatics(hydro);
    if (deviation) print_deviation(o.iges, *deviation);
  }
  std::fflush(stdout);  // the warnings below go after the report, also when both go to one pipe
  if (deviation && deviation->measure.samples == 0)
    std::fprintf(stderr, "hullmesh: warning: no point of %s found a closest point on %s\n",
                 o.file.c_str(), o.iges.c_str());
  if (deviation && deviation->measure.max > kFarFromHull * deviation->length)
    std::fprintf(stderr,
                 "hullmesh: warning: %s lies up to %.4g m (%.3g L) from the hull of %s: a mesh "
                 "of another hull, in other units or in another frame (a floating one)?\n",
                 o.file.c_str(), deviation->measure.max, deviation->measure.max / deviation->length,
                 o.iges.c_str());
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
  cmd->add_flag("--uncut", opts->uncut,
                "The mesh is not cut at a waterline: it ends at the hull's deck edge or sheer "
                "line, and a boundary that reaches the top of the mesh is that edge, not a hole");
  cmd->add_flag("--half", opts->half, "The mesh is a half hull (y >= 0), symmetric about y = 0");
  cmd->add_option("-o,--output", opts->vtu, "Write the per-panel measures as cell data (.vtu)");
  cmd->add_option("--iges", opts->iges,
                  "The IGES hull the mesh was made from (same frame, metres): adds the deviation "
                  "of panel centroids and edge midpoints from its NURBS");
  cmd->callback([opts, &global, &action] {
    action = [opts, &global] { return run_quality(*opts, global); };
  });
}

}  // namespace hm::cli
