// Tessellation: the internal surface representation. Every patch becomes a fine triangulation
// whose vertices lie on the exact NURBS, within a chord tolerance of it everywhere.
//
// Steps per patch (one file pair each): initial_grid (structured quads about edge_length in 3D,
// split along the shorter diagonal), trim (constrained triangulation inside the trim loops),
// degenerate (seams and collapsed edges), refine_butterfly (adaptive red-green refinement with the
// modified butterfly as predictor and projection onto the NURBS), chord_error (measurement).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "core/limits.h"
#include "core/progress.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"

namespace hm {

// Lengths in metres. A value <= 0 means "derive from the hull size" (see resolve_options).
struct TessellateOptions {
  double edge_length = 0;      // target 3D edge of the initial grid; default L / 100
  double chord_tolerance = 0;  // max distance flat triangle -> NURBS; default 1e-4 L
  double max_area = 0;         // refine triangles larger than this (m^2); default edge_length^2
  int max_refine_levels = 6;   // adaptive levels after the grid (capped by limits.max_refine_depth)
  double butterfly_tension = 0;  // Zorin's w in the 10-point regular stencil (0: 8-point)
  // Measure every final triangle's chord error (Tessellation::chord_error, max_chord_error).
  // Off, both stay empty and 0: for callers that read neither (the structured mesher, the merge,
  // the hull queries of `quality` and `section`). On a patch whose parameter lines run side by
  // side it is four closest points a triangle, about a third of its tessellation.
  bool measure_chord = true;
  ResourceLimits limits;
};

// Options with every default filled from the patches' bounding box (L = its largest extent).
// Throws UsageError when the patches are empty and a length is left to default.
TessellateOptions resolve_options(std::span<const Patch> patches, const TessellateOptions& o);

// The initial-grid edge length that gives about `triangles` triangles over all patches (an
// estimate from a coarse area integration; refinement adds some).
double edge_length_for_triangles(std::span<const Patch> patches, std::size_t triangles);

struct TessellateSummary {
  std::size_t patches = 0;
  std::size_t triangles = 0;
  std::size_t vertices = 0;
  double max_chord_error = 0;  // m, measured on the NURBS after meshing
  double chord_tolerance = 0;  // m, the resolved request
  double edge_length = 0;      // m, the resolved initial edge
  double seconds = 0;          // wall time of tessellate()
};

struct Tessellation {
  // Triangles only (faces[t][3] == kInvalid); vertex_patch, vertex_uv and face_patch filled.
  // Patches are concatenated in input order; vertices are not shared between patches.
  SurfaceMesh mesh;
  std::vector<double> chord_error;  // per triangle, m: max distance of the NURBS to the triangle
  TessellateSummary summary;
};

// Options are resolved here (resolve_options). Patches run in parallel; the output is identical
// for any thread count. Throws LimitError when the estimated triangle count exceeds
// options.limits.max_triangles, GeometryError when a trimmed patch cannot be triangulated, and
// UsageError("tessellation cancelled") when progress is cancelled (core has no CancelledError).
Tessellation tessellate(std::span<const Patch> patches, const TessellateOptions& options,
                        Progress& progress);

}  // namespace hm
