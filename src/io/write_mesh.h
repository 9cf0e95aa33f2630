// The one mesh-writer registry every command uses: the format follows the output's extension.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace hm {

struct MeshWriteOptions {
  // Extra per-face scalars, written as cell data where the format has it (VTU).
  std::vector<FaceField> face_fields;
  // Free text for the header line of formats that have one.
  std::string title = "hullmesh";
};

struct MeshFormat {
  const char* extension;  // with the dot, lower case: ".vtu"
  const char* description;
};

// The formats write_mesh knows, in the order the help text lists them.
std::span<const MeshFormat> mesh_formats();

// Writes mesh to path in the format its extension names, atomically. Throws UsageError for an
// unknown extension (naming the known ones) and IoError when the file cannot be written.
void write_mesh(const std::string& path, const SurfaceMesh& mesh,
                const MeshWriteOptions& options = {});

}  // namespace hm
