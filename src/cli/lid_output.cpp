#include "cli/lid_output.h"

#include <cctype>
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

LidOutput write_hull_and_lid(const LidArgs& args, const std::string& output,
                             const SurfaceMesh& hull, const MeshWriteOptions& options) {
  LidOutput out;
  if (!args.wanted()) {
    write_mesh(output, hull, options);
    return out;
  }
  if (args.separate && std::filesystem::path(lid_path(output)) == std::filesystem::path(output)) {
    throw UsageError("--lid: the output is already named " + output +
                     ", the lid's file name; name the hull's file otherwise");
  }
  out.lid = make_lid(hull);
  write_mesh(output, args.in_mesh ? append_lid(hull, *out.lid) : hull, options);
  if (args.separate) {
    out.file = lid_path(output);
    MeshWriteOptions lid_options = options;
    lid_options.info.waterplane_lid = true;
    lid_options.info.title += " (lid)";
    lid_options.face_fields.clear();
    write_mesh(out.file, out.lid->mesh, lid_options);
  }
  return out;
}

void record_lid(const LidOutput& out, const LidArgs& args, RunRecord& record) {
  if (!out.file.empty()) record.outputs.push_back(out.file);
  if (out.lid) {
    record.results["lid"] = {{"panels", out.lid->mesh.face_count()},
                             {"area_m2", out.lid->report.area},
                             {"edge_length_m", out.lid->report.edge_length},
                             {"in_mesh", args.in_mesh}};
  }
}

void print_lid(const LidOutput& out, const LidArgs& args, const std::string& output) {
  if (!out.lid) return;
  std::string where;
  if (args.in_mesh) where = "appended after the hull's panels in " + output;
  if (!out.file.empty()) where += (where.empty() ? "in " : ", and in ") + out.file;
  const LidReport& r = out.lid->report;
  std::printf(
      "  lid: %zu triangles, %zu vertices (%zu on the waterline, %zu on y = 0), edge %.4g m, "
      "area %.6g m^2, normals up; %s\n",
      out.lid->mesh.face_count(), out.lid->mesh.vertex_count(), r.waterline_vertices,
      r.centre_vertices, r.edge_length, r.area, where.c_str());
}

}  // namespace hm::cli
