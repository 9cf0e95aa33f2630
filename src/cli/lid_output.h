// --lid and --lid-in-mesh, shared by the meshers: the interior free-surface panels for codes that
// remove irregular frequencies, made from the finished wetted mesh (mesh/make_lid).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "cli/run_record.h"
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

struct LidOutput {
  std::optional<Lid> lid;  // empty when none was asked for
  std::string file;        // the separate lid file, or empty
};

// Writes the hull's panels to `output` (with the lid's panels after them for --lid-in-mesh) and,
// for --lid, the lid file beside it (same format options, with the waterplane flag for .pnl).
// make_lid's GeometryError stops the command before anything is written.
LidOutput write_hull_and_lid(const LidArgs& args, const std::string& output,
                             const SurfaceMesh& hull, const MeshWriteOptions& options);

// The lid file among the record's outputs, and results.lid (after the results are set).
void record_lid(const LidOutput& out, const LidArgs& args, RunRecord& record);

// The one-line summary the meshers print.
void print_lid(const LidOutput& out, const LidArgs& args, const std::string& output);

}  // namespace hm::cli
