// Shared by the meshing commands: import an IGES hull and tell the user what went wrong with it.
#pragma once

#include <string>

#include "iges/read_iges.h"

namespace hm::cli {

// Reads the file (units forced when `units` is not empty) and prints every warning and error
// diagnostic to stderr unless quiet. Throws what read_iges_file throws.
ImportResult load_hull(const std::string& path, const std::string& units, bool quiet);

// Seconds since `start` (steady clock), for the per-stage timings the commands print.
double seconds_since(long long start_ns);
long long now_ns();

}  // namespace hm::cli
