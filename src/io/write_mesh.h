// The one mesh-writer registry every command uses: the format follows the output's extension.
// Every writer goes through write_file_atomically (temporary file, flush, rename), so a failed run
// never leaves a broken file. Conventions (frame, units, normals into the fluid) are in
// io/mesh_file.h; each format's own conventions are at the top of its io/format_*.cpp.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "io/mesh_file.h"
#include "mesh/surface_mesh.h"

namespace hm {

struct MeshWriteOptions {
  // Extra per-face scalars, written as cell data where the format has it (VTK, VTU).
  std::vector<FaceField> face_fields;
  // Title, symmetry, ULEN/GRAV: each written where the format has a place for it. A symmetry the
  // format cannot express is a UsageError (never silently dropped) for the panel-code formats
  // that have a symmetry flag; formats without any flag (STL) ignore it.
  MeshFileInfo info;
  // .stl: ASCII instead of binary.
  bool stl_ascii = false;
  // .pnl: write a HAMS WaterplaneMesh.pnl (the interior waterplane lid, z = 0 exactly). Also
  // chosen when the file is named WaterplaneMesh.pnl.
  bool pnl_waterplane = false;
};

struct MeshFormat {
  const char* extension;  // with the dot, lower case: ".vtu"
  const char* description;
};

// The formats write_mesh and read_mesh know, in the order the help text lists them.
std::span<const MeshFormat> mesh_formats();

// Throws the UsageError write_mesh would for path's extension, so that a command can refuse an
// unknown output format before it does any work.
void check_mesh_output(const std::string& path);

// Writes mesh to path in the format its extension names, atomically. Throws UsageError for an
// unknown extension (naming the known ones) or a symmetry the format cannot carry,
// GeometryError for a non-finite position, and IoError when the file cannot be written.
void write_mesh(const std::string& path, const SurfaceMesh& mesh,
                const MeshWriteOptions& options = {});

// The same, writing to a stream in the named format (".gdf", ...): for tests, fuzz seeds and
// benchmarks. Not atomic.
void write_mesh_to(std::ostream& out, const std::string& extension, const SurfaceMesh& mesh,
                   const MeshWriteOptions& options = {});

}  // namespace hm
