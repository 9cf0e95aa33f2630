#include "cli/lid_output.h"

#include <cstdio>
#include <filesystem>

#include "core/error.h"

namespace hm::cli {

void add_lid_options(CLI::App* cmd, LidArgs& args) {
  cmd->add_flag("--lid", args.separate,
                "Also write the lid (the waterplane inside the waterline) beside the output: "
                "WaterplaneMesh.pnl for .pnl, else NAME_lid.EXT");
  cmd->add_flag("--lid-in-mesh", args.in_mesh,
                "Append the lid's panels after the hull's in the output itself (WAMIT IRR = 1)");
}

std::string lid_path(const std::string& output) {
  namespace fs = std::filesystem;
  const fs::path p(output);
  std::string ext = p.extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".pnl") return (p.parent_path() / "WaterplaneMesh.pnl").string();
  return (p.parent_path() / (p.stem().string() + "_lid" + p.extension().string())).string();
}

std::optional<Lid> build_lid(const LidArgs& args, const SurfaceMesh& hull, bool floating) {
  if (!args.wanted()) return std::nullopt;
  if (!floating) {
    throw UsageError(
        "--lid needs a waterplane: give --draft, --waterline-z, --drafts, --trim or --heel");
  }
  return make_lid(hull);
}

std::string write_lid_file(const LidArgs& args, const std::string& output, const Lid& lid,
                           MeshWriteOptions options) {
  if (!args.separate) return {};
  const std::string path = lid_path(output);
  if (std::filesystem::path(path) == std::filesystem::path(output)) {
    throw UsageError("--lid: the output is already named " + path +
                     "; name the hull's file otherwise");
  }
  options.info.waterplane_lid = true;
  options.info.title += " (lid)";
  options.face_fields.clear();
  write_mesh(path, lid.mesh, options);
  return path;
}

void print_lid(const Lid& lid, const std::string& where) {
  const LidReport& r = lid.report;
  std::printf(
      "  lid: %zu triangles, %zu vertices (%zu on the waterline, %zu on y = 0), edge %.4g m, "
      "area %.6g m^2, normals up; %s\n",
      lid.mesh.face_count(), lid.mesh.vertex_count(), r.waterline_vertices, r.centre_vertices,
      r.edge_length, r.area, where.c_str());
}

}  // namespace hm::cli
