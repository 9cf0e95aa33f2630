// Writing patches as IGES 5.3: 128 surfaces (with 406 form 15 names, 124 is never needed since
// geometry is written in its final frame), optionally wrapped in 144 trimmed surfaces.
#pragma once

#include <string>
#include <vector>

#include "nurbs/patch.h"

namespace hm {

struct IgesWriteOptions {
  std::string author = "hullmesh";
  std::string file_name = "hull.igs";
  // Unit declared in G14/G15. Coordinates are written in metres / unit_to_metres, except when
  // lie_about_units is set: then the numbers stay in metres but the flag says `unit_flag`.
  int unit_flag = 6;  // 6 = metres
  bool lie_about_units = false;
  // Fixed timestamp so that output is reproducible byte for byte.
  std::string timestamp = "20260101.000000";
};

// The IGES text. Numbers are written with 17 significant digits so that reading them back gives
// the same doubles (bit for bit).
std::string write_iges(const std::vector<Patch>& patches, const IgesWriteOptions& options = {});
// Write to a file through a temporary and a rename; throws IoError.
void write_iges_file(const std::string& path, const std::vector<Patch>& patches,
                     const IgesWriteOptions& options = {});

}  // namespace hm
