// libFuzzer target for every mesh reader behind read_mesh: the first input byte picks the format
// (modulo the number of formats, in mesh_formats() order), the rest is the file. A reader may
// throw hullmesh's typed errors (that is the expected answer to a broken file); anything else,
// a crash, a hang or an unbounded allocation is a finding.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "core/error.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto formats = hm::mesh_formats();
  const std::string ext = formats[data[0] % formats.size()].extension;
  const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  hm::ReadOptions options;
  // Small limits keep each run fast while still exercising every count check.
  options.limits.max_triangles = 100'000;
  options.limits.max_file_bytes = 1 << 20;
  try {
    const hm::MeshFile m = hm::read_mesh_from_memory(bytes, ext, "fuzz" + ext, options);
    // Whatever was read must be a valid mesh: every corner in range, one patch per face.
    for (const hm::Face& f : m.mesh.faces)
      for (int k = 0; k < hm::corner_count(f); ++k)
        if (f[k] >= m.mesh.positions.size()) __builtin_trap();
    if (m.mesh.face_patch.size() != m.mesh.faces.size()) __builtin_trap();
  } catch (const hm::Error&) {
  }
  return 0;
}
