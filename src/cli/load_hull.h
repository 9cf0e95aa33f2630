// Shared by the meshing commands: import an IGES hull and tell the user what went wrong with it.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "iges/read_iges.h"
#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"
#include "query/find_self_intersections.h"

namespace hm::cli {

// Reads the file (units forced when `units` is not empty) and prints every warning and error
// diagnostic to stderr unless quiet. Throws what read_iges_file throws.
ImportResult load_hull(const std::string& path, const std::string& units, bool quiet);

// Throws GeometryError naming how many edges of the merged surface have more than two faces and
// where the first lies, then `hint` (what the user can do), when there are any.
void check_merged_manifold(const std::string& file, const SurfaceMesh& mesh,
                           const EdgeAdjacency& adjacency, const std::string& hint);

// Faces of `mesh` that pass through each other. Crossings shallower than 1e-7 of the mesh's
// largest extent are not counted (rounding in the fine mesh).
SelfIntersections measure_crossings(const SurfaceMesh& mesh);

// "" when there are none. Otherwise one line for the user: "FILE: WHAT passes through itself:
// N pairs of faces cross, the first of patch 3 'name' (DE 7) and patch 9 (DE 19) near x, y,
// z m".
std::string describe_crossings(const std::string& file, std::span<const Patch> patches,
                               const SurfaceMesh& mesh, const SelfIntersections& crossings,
                               const std::string& what);

// The comma-separated numbers of an option value ("1,2.5,3"): exactly `count` finite ones, or a
// UsageError naming the option, the value and the fault.
std::vector<double> parse_numbers(const std::string& text, std::size_t count,
                                  const std::string& option);
// The same, with `where` leading every message in place of "OPTION TEXT" (for a value that is
// one part of a longer option value).
std::vector<double> parse_numbers_in(const std::string& text, std::size_t count,
                                     const std::string& where);

// Seconds since `start` (steady clock), for the per-stage timings the commands print.
double seconds_since(long long start_ns);
long long now_ns();

}  // namespace hm::cli
