#include "io/write_mesh.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/mesh_writers.h"

namespace hm {
namespace {

using WriteFn = void (*)(std::ostream&, const SurfaceMesh&, const MeshWriteOptions&);

struct Entry {
  MeshFormat format;
  WriteFn write;
};

constexpr std::array<Entry, 3> kRegistry{{
    {{".vtu", "VTK XML unstructured grid, with patch, block and quality cell data"}, io::write_vtu},
    {{".stl", "binary STL (quads split into two triangles)"}, io::write_stl_binary},
    {{".obj", "Wavefront OBJ (quads kept as quads, one group per patch)"}, io::write_obj},
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

void check_mesh(const SurfaceMesh& m, const MeshWriteOptions& o) {
  for (const Face& f : m.faces)
    for (int k = 0; k < corner_count(f); ++k)
      if (f[k] >= m.positions.size())
        throw InternalError("mesh writer: face refers to vertex " + std::to_string(f[k]) + " of " +
                            std::to_string(m.positions.size()));
  if (!m.face_patch.empty() && m.face_patch.size() != m.faces.size())
    throw InternalError("mesh writer: face_patch size does not match the faces");
  for (const FaceField& field : o.face_fields)
    if (field.values.size() != m.faces.size())
      throw InternalError(std::string("mesh writer: field ") + field.name + " size does not match");
}

}  // namespace

std::span<const MeshFormat> mesh_formats() { return kFormats; }

void write_mesh(const std::string& path, const SurfaceMesh& mesh, const MeshWriteOptions& options) {
  const std::string ext = lower_extension(path);
  const auto it = std::find_if(kRegistry.begin(), kRegistry.end(),
                               [&](const Entry& e) { return ext == e.format.extension; });
  if (it == kRegistry.end()) {
    std::string known;
    for (const Entry& e : kRegistry)
      known += std::string(known.empty() ? "" : ", ") + e.format.extension;
    throw UsageError(path + ": unknown mesh format '" + ext + "' (known: " + known + ")");
  }
  check_mesh(mesh, options);
  write_file_atomically(path, [&](std::ostream& out) { it->write(out, mesh, options); });
}

}  // namespace hm
