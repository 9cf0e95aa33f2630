// Adaptive refinement of a patch triangulation until every triangle meets the area and chord
// criteria. Red (1 -> 4) splits with hanging nodes kept 1-irregular between levels, then one
// green (1 -> 2) closure, so the result is conforming. New vertices are predicted by the modified
// butterfly and projected onto the NURBS, so every vertex lies on the exact surface.
#pragma once

#include <cstddef>

#include "nurbs/nurbs_surface.h"
#include "tessellate/chord_error.h"
#include "tessellate/patch_mesh.h"

namespace hm {

struct RefineOptions {
  double chord_tolerance = 0;     // m: edge-midpoint and centroid distance to the NURBS
  double max_area = 0;            // m^2; <= 0 turns the area criterion off
  int max_levels = 6;             // red levels above the initial mesh
  double tension = 0;             // Zorin's w
  double collapse_tolerance = 0;  // m: edges this short are collapsed (merged later)
  CollapsedSides collapsed;       // sides of the domain the surface collapses to a point
  ChordSampling chord_sampling = ChordSampling::kParametric;
};

struct RefineStats {
  int levels = 0;         // levels that split something
  std::size_t red = 0;    // triangles split 1 -> 4
  std::size_t green = 0;  // triangles split 1 -> 2 by the closure
};

// Criteria, per triangle of level < max_levels: 3D area above max_area, or the distance between
// an edge's 3D midpoint and the surface at the edge's middle (u, v), or between the centroid and
// the surface at the centroid's (u, v), above chord_tolerance. The mesh is refined in place;
// vertices keep their order and new ones are appended, so the result is deterministic.
RefineStats refine_butterfly(const NurbsSurface& s, PatchMesh& m, const RefineOptions& o);

}  // namespace hm
