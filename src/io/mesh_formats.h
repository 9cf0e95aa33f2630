// Internal to io/: the writer and reader of each format behind write_mesh and read_mesh.
// Writers take a mesh already checked by write_mesh (indices in range, finite positions,
// face_patch empty or one per face). Readers take the file's bytes and a name for messages.
#pragma once

#include <ostream>
#include <string>
#include <string_view>

#include "core/limits.h"
#include "io/mesh_file.h"
#include "io/write_mesh.h"

namespace hm::io {

using WriteFn = void (*)(std::ostream&, const SurfaceMesh&, const MeshWriteOptions&);
using ReadFn = MeshFile (*)(std::string_view bytes, const std::string& name,
                            const ResourceLimits& limits);

void write_gdf(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_gdf(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

void write_nemoh(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_nemoh(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

void write_pnl(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_pnl(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

void write_hst(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_hst(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

void write_msh(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_msh(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

void write_vtk(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_vtk(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

void write_vtu(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_vtu(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

void write_stl(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_stl(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

void write_obj(std::ostream& out, const SurfaceMesh& mesh, const MeshWriteOptions& options);
MeshFile read_obj(std::string_view bytes, const std::string& name, const ResourceLimits& limits);

// Patch of face i, 0 when the mesh has no face_patch.
inline PatchId patch_of(const SurfaceMesh& m, std::size_t i) {
  return m.face_patch.empty() ? 0 : m.face_patch[i];
}

inline void put(std::ostream& out, const std::string& s) {
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

}  // namespace hm::io
