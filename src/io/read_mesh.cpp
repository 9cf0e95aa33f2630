#include "io/read_mesh.h"

#include <cerrno>
#include <cstring>
#include <fstream>

#include "core/error.h"
#include "io/mesh_registry.h"

namespace hm {

MeshFile read_mesh_from_memory(std::string_view bytes, const std::string& extension,
                               const std::string& name, const ReadOptions& options) {
  const io::FormatEntry& f = io::find_format(extension, name);
  if (bytes.size() > options.limits.max_file_bytes)
    throw LimitError(name + ": " + std::to_string(bytes.size()) + " bytes, over the limit of " +
                     std::to_string(options.limits.max_file_bytes));
  return f.read(bytes, name, options.limits);
}

MeshFile read_mesh(const std::string& path, const ReadOptions& options) {
  const std::string ext = options.format.empty() ? io::lower_extension(path) : options.format;
  io::find_format(ext, path);  // unknown format: UsageError before touching the file
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open (" + std::strerror(errno) + ")");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw IoError(path + ": cannot read its size");
  if (std::uint64_t(size) > options.limits.max_file_bytes)
    throw LimitError(path + ": " + std::to_string(size) + " bytes, over the limit of " +
                     std::to_string(options.limits.max_file_bytes));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (size > 0 && !in.read(bytes.data(), size)) throw IoError(path + ": read failed");
  return read_mesh_from_memory(bytes, ext, path, options);
}

}  // namespace hm
