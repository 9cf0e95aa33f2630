// hullmesh tessellate FILE -o out.vtu: the internal surface representation, written out.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/load_hull.h"
#include "cli/run_record.h"
#include "io/write_mesh.h"
#include "tessellate/tessellate.h"

namespace hm::cli {
namespace {

struct TessellateCommand {
  std::string file;
  std::string output;
  std::string units;
  TessellateOptions options;
  double chord_relative = 0;  // chord tolerance as a fraction of L
  std::size_t triangles = 0;  // target triangle count (sets the edge length)
};

int run_tessellate(const TessellateCommand& c, const GlobalOptions& g) {
  RunRecord& record = *g.record;
  record.log.stage("import");
  const long long t0 = now_ns();
  const ImportResult hull = load_hull(c.file, c.units, g.quiet);
  const double t_import = seconds_since(t0);
  TessellateOptions o = c.options;
  const double length = hull.bbox.empty() ? 0.0 : hull.bbox.extent().x;
  if (c.chord_relative > 0) o.chord_tolerance = c.chord_relative * std::max(length, 1e-12);
  if (c.triangles > 0) o.edge_length = edge_length_for_triangles(hull.patches, c.triangles);
  record.log.stage("tessellate");
  const Tessellation t = tessellate(hull.patches, o, record.log);
  record.log.stage("write");
  const long long t1 = now_ns();
  MeshWriteOptions w;
  w.info.title = "hullmesh tessellation of " + file_name(c.file);
  w.face_fields.push_back({"chord_error", t.chord_error});
  write_mesh(c.output, t.mesh, w);
  const double t_write = seconds_since(t1);
  record.log.finish();
  record.input = c.file;
  record.outputs = {c.output};
  record.results = {{"triangles", t.summary.triangles},
                    {"vertices", t.summary.vertices},
                    {"edge_length_m", t.summary.edge_length},
                    {"chord_tolerance_m", t.summary.chord_tolerance},
                    {"max_chord_error_m", t.summary.max_chord_error}};
  if (!g.quiet) {
    const TessellateSummary& s = t.summary;
    std::printf("%s: %zu patches -> %zu triangles, %zu vertices\n", c.output.c_str(), s.patches,
                s.triangles, s.vertices);
    std::printf(
        "  edge length %.6g m, chord tolerance %.6g m, max chord error %.6g m (%.2f of it)\n",
        s.edge_length, s.chord_tolerance, s.max_chord_error,
        s.chord_tolerance > 0 ? s.max_chord_error / s.chord_tolerance : 0.0);
    std::printf("  time: import %.3f s, tessellate %.3f s, write %.3f s\n", t_import, s.seconds,
                t_write);
  }
  return 0;
}

}  // namespace

void register_tessellate(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto c = std::make_shared<TessellateCommand>();
  CLI::App* cmd = app.add_subcommand(
      "tessellate", "Triangulate every patch within a chord tolerance (the internal surface)");
  cmd->add_option("file", c->file, "IGES file")->required();
  cmd->add_option("-o,--output", c->output, "Output mesh (.vtu, .vtk, .stl, .obj, .msh, ...)")
      ->required();
  cmd->add_option("--edge-length", c->options.edge_length,
                  "Initial grid edge in metres (default L/100)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--triangles", c->triangles, "Aim at about this many triangles (sets the edge)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{50'000'000}));
  auto* chord = cmd->add_option("--chord-tol", c->options.chord_tolerance,
                                "Chord tolerance in metres (default 1e-4 L)")
                    ->check(CLI::PositiveNumber);
  cmd->add_option("--chord-tol-rel", c->chord_relative, "Chord tolerance as a fraction of L")
      ->check(CLI::Range(1e-9, 0.1))
      ->excludes(chord);
  cmd->add_option("--max-area", c->options.max_area, "Refine triangles above this area (m^2)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-levels", c->options.max_refine_levels, "Adaptive refinement levels")
      ->check(CLI::Range(0, 12));
  cmd->add_option("--units", c->units, "Force the file's unit (m, mm, cm, in, ft, km)")
      ->check(CLI::IsMember({"m", "mm", "cm", "in", "ft", "km"}));
  cmd->callback(
      [c, &global, &action] { action = [c, &global] { return run_tessellate(*c, global); }; });
}

}  // namespace hm::cli
