// --add-knuckle / --suppress-knuckle: the user's knuckle hints on the command line. A spec is
// one of
//   plane:X,Y,Z,NX,NY,NZ[@D]   edges whose midpoint lies within D m of the plane through (X, Y, Z)
//                              with normal (NX, NY, NZ)
//   points:X,Y,Z;X,Y,Z;...[@D] edges with both ends within D m of the polyline through the points
//   patches:A,B                edges between patches A and B (indices as `hullmesh info -v` lists)
//   de:A,B                     edges between the surfaces of IGES DE numbers A and B (every patch
//                              of each, a mirrored image's too)
// D defaults to 1e-3 L. Coordinates are metres in the file's frame (after --units); a hull placed
// afloat has its hints placed with it.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "nurbs/patch.h"
#include "quality/hydrostatics.h"
#include "unstructured/features.h"

namespace CLI {
class App;
}

namespace hm::cli {

// The option values as given.
struct KnuckleHintArgs {
  std::vector<std::string> add, suppress;
};
// --add-knuckle and --suppress-knuckle (repeatable) on `cmd`.
void add_knuckle_hint_options(CLI::App* cmd, KnuckleHintArgs& args);

// One parsed spec: de_a, de_b are DE numbers still to be matched to patches (de: specs).
struct KnuckleHintSpec {
  KnuckleHint hint;
  int de_a = 0, de_b = 0;
};
struct KnuckleHintSpecs {
  std::vector<KnuckleHintSpec> add, suppress;
};
// Checked before any work: throws UsageError naming the option, the spec and what is wrong.
KnuckleHintSpecs parse_knuckle_hints(const KnuckleHintArgs& args);

// Adds the hints to `features` for these patches (as meshed; `placed` maps the file frame to
// theirs, or is null). Throws UsageError naming `file` when a patch index or DE number names no
// patch.
void apply_knuckle_hints(const KnuckleHintSpecs& specs, std::span<const Patch> patches,
                         const FloatingTransform* placed, const std::string& file,
                         FeatureOptions& features);

}  // namespace hm::cli
