// --lid and --lid-in-mesh, shared by the meshers: the interior free-surface panels for codes that
// remove irregular frequencies, made from the finished wetted mesh (mesh/make_lid).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "io/write_mesh.h"
#include "mesh/make_lid.h"

namespace hm::cli {

struct LidArgs {
  bool separate = false;  // --lid: a lid file beside the output
  bool in_mesh = false;   // --lid-in-mesh: the lid's panels after the hull's, in the output
  bool wanted() const { return separate || in_mesh; }
};

void add_lid_options(CLI::App* cmd, LidArgs& args);

// Where --lid writes: WaterplaneMesh.pnl beside a .pnl output (the name HAMS reads), else
// NAME_lid.EXT beside NAME.EXT.
std::string lid_path(const std::string& output);

// The lid of the wetted mesh `hull`; throws UsageError when a lid is asked for without a
// waterplane (floating false), and the GeometryError of make_lid when the hull cannot have one.
std::optional<Lid> build_lid(const LidArgs& args, const SurfaceMesh& hull, bool floating);

// Writes the separate lid file when asked for (same format options as the hull, with the
// waterplane flag for .pnl), returning its path, or an empty string.
std::string write_lid_file(const LidArgs& args, const std::string& output, const Lid& lid,
                           MeshWriteOptions options);

// The one-line summary printed by the meshers.
void print_lid(const Lid& lid, const std::string& where);

}  // namespace hm::cli
