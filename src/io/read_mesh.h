// The one mesh-reader registry: the format follows the input's extension (or ReadOptions::format).
// Readers treat every file as hostile: each declared count is checked against ResourceLimits and
// against what the file's size could hold before anything is allocated; every number is checked
// (finite, in range). A malformed file throws InputError naming the file, the line (or, for
// binary STL, the triangle and byte offset) and what is wrong; a count over a limit throws
// LimitError. Readers never crash, hang or allocate without bound.
#pragma once

#include <string>
#include <string_view>

#include "core/limits.h"
#include "io/mesh_file.h"

namespace hm {

struct ReadOptions {
  ResourceLimits limits;
  // Format to read, as an extension (".gdf"); empty = from the file name.
  std::string format;
};

// Reads a mesh file. The returned mesh follows io/mesh_file.h (metres, normals into the fluid);
// face_patch has one entry per face: the group / physical tag where the format carries one,
// else 0. Throws UsageError for an unknown extension, IoError when the file cannot be read,
// InputError for a malformed file and LimitError for one over the limits.
MeshFile read_mesh(const std::string& path, const ReadOptions& options = {});

// The same on bytes in memory (fuzzing, tests); name is used in messages only.
MeshFile read_mesh_from_memory(std::string_view bytes, const std::string& extension,
                               const std::string& name, const ReadOptions& options = {});

}  // namespace hm
