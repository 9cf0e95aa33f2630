// Internal to io/: the table of formats shared by write_mesh and read_mesh.
#pragma once

#include <string>

#include "io/mesh_formats.h"

namespace hm::io {

struct FormatEntry {
  MeshFormat format;
  WriteFn write;
  ReadFn read;
};

// The entry for an extension (".gdf" or "gdf", any case); UsageError naming path and the known
// extensions when there is none.
const FormatEntry& find_format(const std::string& extension, const std::string& path);
std::string lower_extension(const std::string& path);

}  // namespace hm::io
