#include "io/write_mesh.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/mesh_formats.h"
#include "io/mesh_registry.h"

namespace hm {
namespace io {

// One table for both directions, in the order the help text lists them.
constexpr std::array<FormatEntry, 9> kRegistry{{
    {{".gdf", "WAMIT low-order geometry (ULEN, GRAV, ISX/ISY symmetry)"}, write_gdf, read_gdf},
    {{".dat", "NEMOH mesh (symmetry about y = 0); Capytaine reads it too"},
     write_nemoh,
     read_nemoh},
    {{".pnl", "HAMS HullMesh.pnl, or WaterplaneMesh.pnl for the lid"}, write_pnl, read_pnl},
    {{".hst", "Hydrostar mesh (single body, symmetry 0/1/2)"}, write_hst, read_hst},
    {{".msh", "Gmsh MSH 4.1 ASCII, one surface entity and physical group per patch"},
     write_msh,
     read_msh},
    {{".vtk", "VTK legacy POLYDATA with patch, block and field cell data"}, write_vtk, read_vtk},
    {{".vtu", "VTK XML unstructured grid, with patch, block and quality cell data"},
     write_vtu,
     read_vtu},
    {{".stl", "STL, binary (ASCII on request); quads split into two triangles"},
     write_stl,
     read_stl},
    {{".obj", "Wavefront OBJ (quads kept as quads, one group per patch)"}, write_obj, read_obj},
}};

constexpr std::array<MeshFormat, kRegistry.size()> kFormats = [] {
  std::array<MeshFormat, kRegistry.size()> f{};
  for (std::size_t i = 0; i < kRegistry.size(); ++i) f[i] = kRegistry[i].format;
  return f;
}();

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

const FormatEntry& find_format(const std::string& ext, const std::string& path) {
  std::string e = ext;
  std::transform(e.begin(), e.end(), e.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!e.empty() && e[0] != '.') e = "." + e;
  const auto it = std::find_if(kRegistry.begin(), kRegistry.end(),
                               [&](const FormatEntry& f) { return e == f.format.extension; });
  if (it == kRegistry.end()) {
    std::string known;
    for (const FormatEntry& f : kRegistry)
      known += std::string(known.empty() ? "" : ", ") + f.format.extension;
    throw UsageError(path + ": unknown mesh format '" + e + "' (known: " + known + ")");
  }
  return *it;
}

}  // namespace io

namespace {

void check_mesh(const SurfaceMesh& m, const MeshWriteOptions& o) {
  for (const Face& f : m.faces)
    for (int k = 0; k < corner_count(f); ++k)
      if (f[k] >= m.positions.size())
        throw InternalError("mesh writer: face refers to vertex " + std::to_string(f[k]) + " of " +
                            std::to_string(m.positions.size()));
  if (!m.face_patch.empty() && m.face_patch.size() != m.faces.size())
    throw InternalError("mesh writer: face_patch size does not match the faces");
  if (!m.face_block.empty() && m.face_block.size() != m.faces.size())
    throw InternalError("mesh writer: face_block size does not match the faces");
  for (const FaceField& field : o.face_fields)
    if (field.values.size() != m.faces.size())
      throw InternalError(std::string("mesh writer: field ") + field.name + " size does not match");
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    if (!is_finite(m.positions[i]))
      throw GeometryError("mesh writer: vertex " + std::to_string(i) + " is not finite");
}

}  // namespace

std::span<const MeshFormat> mesh_formats() { return io::kFormats; }

void write_mesh_to(std::ostream& out, const std::string& extension, const SurfaceMesh& mesh,
                   const MeshWriteOptions& options) {
  const io::FormatEntry& f = io::find_format(extension, "(stream)");
  check_mesh(mesh, options);
  f.write(out, mesh, options);
}

void check_mesh_output(const std::string& path) {
  io::find_format(io::lower_extension(path), path);
}

void write_mesh(const std::string& path, const SurfaceMesh& mesh, const MeshWriteOptions& options) {
  const io::FormatEntry& f = io::find_format(io::lower_extension(path), path);
  check_mesh(mesh, options);
  MeshWriteOptions o = options;
  std::string file = std::filesystem::path(path).filename().string();
  std::transform(file.begin(), file.end(), file.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (file == "waterplanemesh.pnl") o.pnl_waterplane = true;
  try {
    write_file_atomically(path, [&](std::ostream& out) { f.write(out, mesh, o); });
  } catch (const UsageError& e) {
    throw UsageError(path + ": " + e.what());
  } catch (const GeometryError& e) {
    throw GeometryError(path + ": " + e.what());
  }
}

}  // namespace hm
