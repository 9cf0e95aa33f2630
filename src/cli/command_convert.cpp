// hullmesh convert IN OUT: a panel mesh from one format to another, keeping what both formats
// can carry (panels in order, patches, symmetry, title, ULEN/GRAV, VTK cell data). The formats
// follow the extensions; conventions (normals into the fluid) are undone on read and redone on
// write, so a mesh keeps its orientation across formats.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"

namespace hm::cli {
namespace {

struct ConvertOptions {
  std::string input;
  std::string output;
  std::string input_format;
  std::string symmetry;  // empty = keep the input's
  std::string title;
  double ulen = 0, grav = 0;  // 0 = keep
  bool stl_ascii = false;
  bool waterplane = false;
};

int run_convert(const ConvertOptions& o, const GlobalOptions& g) {
  ReadOptions read;
  read.format = o.input_format;
  MeshFile in = read_mesh(o.input, read);
  MeshWriteOptions w;
  w.info = in.info;
  if (!o.symmetry.empty()) {
    w.info.symmetry.about_y0 = o.symmetry == "y" || o.symmetry == "xy";
    w.info.symmetry.about_x0 = o.symmetry == "x" || o.symmetry == "xy";
  }
  if (!o.title.empty()) w.info.title = o.title;
  if (w.info.title.empty()) w.info.title = "hullmesh convert " + file_name(o.input);
  if (o.ulen > 0) w.info.ulen = o.ulen;
  if (o.grav > 0) w.info.grav = o.grav;
  w.stl_ascii = o.stl_ascii;
  w.pnl_waterplane = o.waterplane;
  for (const NamedFaceField& f : in.fields) w.face_fields.push_back({f.name.c_str(), f.values});
  write_mesh(o.output, in.mesh, w);
  if (!g.quiet) {
    std::size_t tris = 0;
    for (const Face& f : in.mesh.faces) tris += is_triangle(f) ? 1 : 0;
    std::printf("%s -> %s: %zu vertices, %zu panels (%zu triangles, %zu quads), symmetry %s\n",
                o.input.c_str(), o.output.c_str(), in.mesh.positions.size(), in.mesh.faces.size(),
                tris, in.mesh.faces.size() - tris,
                w.info.symmetry.about_y0 ? (w.info.symmetry.about_x0 ? "y = 0 and x = 0" : "y = 0")
                                         : (w.info.symmetry.about_x0 ? "x = 0" : "none"));
  }
  return 0;
}

std::string format_list() {
  std::string s;
  for (const MeshFormat& f : mesh_formats())
    s += std::string("\n  ") + f.extension + "  " + f.description;
  return s;
}

}  // namespace

void register_convert(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto o = std::make_shared<ConvertOptions>();
  CLI::App* cmd = app.add_subcommand(
      "convert", "Convert a panel mesh between formats (by extension):" + format_list());
  cmd->add_option("input", o->input, "Mesh to read")->required();
  cmd->add_option("output", o->output, "Mesh to write (written atomically)")->required();
  cmd->add_option("--input-format", o->input_format,
                  "Read the input as this format (an extension such as .dat) whatever its name");
  cmd->add_option("--symmetry", o->symmetry,
                  "Declare the symmetry: none, y (about y = 0), x (about x = 0) or xy")
      ->check(CLI::IsMember({"none", "y", "x", "xy"}));
  cmd->add_option("--title", o->title, "Title for formats with a header line");
  cmd->add_option("--ulen", o->ulen, "WAMIT ULEN (default: the input's, else 1)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--grav", o->grav, "WAMIT GRAV (default: the input's, else 9.80665)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--ascii", o->stl_ascii, "Write STL as ASCII instead of binary");
  cmd->add_flag("--waterplane", o->waterplane,
                "Write a HAMS WaterplaneMesh.pnl (also chosen by that file name)");
  cmd->callback(
      [o, &global, &action] { action = [o, &global] { return run_convert(*o, global); }; });
}

}  // namespace hm::cli
