// Coarsening: the merged fine triangulation becomes a panel mesh by edge collapse under the
// paper's weighted quality criterion (issue 5). Knuckle lines, boundaries and their corners
// survive exactly; every vertex stays on the NURBS; the deviation from the NURBS stays under a
// bound; and the result is identical for any thread count.
//
// Steps (one file each): size_field (the panel size wanted at every point, from the NURBS
// curvature and the user's sources), coarsen_state (the mutable mesh: faces per vertex, feature
// lines, deviation witnesses), score_collapse (the best collapse of a vertex and its index q),
// apply_collapse (validate against the bounds, then collapse), improve_panels (edge flips and
// tangential smoothing on the NURBS). The driver runs rounds of collect -> score -> select
// (independent set) -> apply -> rescore. Positions in metres, model frame.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/progress.h"
#include "core/types.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"
#include "unstructured/features.h"

namespace hm {

// A user source (size below the field) or sink (above): the panel edge `size` is wanted within
// half the radius of the source where the hull is flat; influence falls smoothly to nothing at
// `radius` from it.
struct SizeSource {
  enum class Kind : std::uint8_t { kPoint, kLine, kBox };
  Kind kind = Kind::kPoint;
  Vec3d a;            // the point; the line's first end; the box's lowest corner
  Vec3d b;            // the line's second end; the box's highest corner (unused for a point)
  double radius = 0;  // m, > 0: distance from the source at which it stops acting
  double size = 0;    // m, > 0: panel edge wanted at the source
};

// The weights w_i of the paper's index q = sum_i (w_i q_i) / 4. Each is >= 0. The size weights
// also set how strongly their field acts (coarsen.cpp documents the formulas).
struct CoarsenWeights {
  double shape = 1;       // q1: equilateral triangles
  double area_ratio = 1;  // q2: neighbouring panels of equal area
  double curvature = 1;   // q3: panel area inversely proportional to the NURBS curvature
  double sources = 1;     // q4: the user's source / sink distribution
};

struct CoarsenOptions {
  // Stop rules; coarsening stops at the first one met. With none set, target_panels = 4000.
  std::size_t target_panels = 0;  // faces
  double mean_quality = 0;        // > 0: stop once the mean face index falls to this level
  double min_quality = 0;         // > 0: stop once the smallest face index falls to this level
  // The panel edge on a flat hull away from sources (m). <= 0: chosen so that target_panels
  // (or 4000) equilateral panels of the field's sizes cover the hull.
  double panel_size = 0;
  CoarsenWeights weights;
  std::vector<SizeSource> sources;
  // No point of the panels is farther than this from the NURBS (m). <= 0: 1e-3 L, L the largest
  // bounding-box extent. Must be at least twice fine_chord_error.
  double max_deviation = 0;
  // The fine mesh's own largest distance from the NURBS (TessellateSummary::max_chord_error), m.
  // The collapses keep the fine vertices within max_deviation minus this of the panels.
  // <= 0: 1e-4 L, the tessellation's default tolerance.
  double fine_chord_error = 0;
  // Curvature length R of the curvature criterion (m): a panel on a surface of curvature k gets
  // the edge h / sqrt(1 + k R). <= 0: 0.05 L.
  double curvature_length = 0;
  // A collapse may turn no panel normal by more than this (degrees).
  double max_normal_change_deg = 40;
  // Passes of edge flips and tangential smoothing after the collapses. The smoothing settles
  // slowly (each pass moves about 85% as many vertices as the one before): on kcs.iges at 4,000
  // panels 4 passes leave 93.6% of triangles at 30 degrees or more, 8 leave 96.4%.
  int improve_passes = 8;
  // The reference: one collapse at a time from a serial priority queue (tests compare against
  // it); otherwise batches of independent collapses run in parallel.
  bool serial_reference = false;
};

struct CoarsenReport {
  std::size_t input_faces = 0;
  std::size_t panels = 0;
  std::size_t vertices = 0;
  std::size_t rounds = 0;
  std::size_t collapses = 0;
  std::size_t rejected_deviation = 0;  // collapses refused by the deviation bound
  std::size_t rejected_shape = 0;      // refused at apply time by the fold / sliver filters
  std::size_t flips = 0;
  std::size_t smoothing_moves = 0;
  double panel_size = 0;       // m, the resolved h
  double size_level = 0;       // the size gate reached: panels are about this many times h
  double max_deviation = 0;    // m, the bound used
  double deviation = 0;        // m, largest witness distance to the panels
  double mean_quality = 0;     // mean face index at the end
  double min_quality = 0;      // smallest face index at the end
  bool target_reached = true;  // false: collapses ran out before the panel target
  double seconds_setup = 0, seconds_collapse = 0, seconds_improve = 0;
};

struct CoarsenedMesh {
  // Triangles; face_patch, vertex_patch and vertex_uv filled. Faces keep the patch of the fine
  // face they descend from.
  SurfaceMesh mesh;
  std::vector<Index> vert_new2old;  // the fine vertex each panel vertex descends from
  // Per output vertex: smooth, on a feature line, or a corner (as in the fine features).
  std::vector<VertexFeature> vertex_feature;
  // Output vertex pairs that are knuckle or boundary edges.
  std::vector<std::array<Index, 2>> feature_edges;
  CoarsenReport report;
};

// `fine` is the merged surface (triangles, shared vertices, vertex_patch / vertex_uv /
// face_patch filled, edge-manifold), `adjacency` its edge adjacency and `features` found on it.
// Throws GeometryError when the input arrays disagree or the mesh is not edge-manifold,
// UsageError when an option is out of range.
CoarsenedMesh coarsen(std::span<const Patch> patches, const SurfaceMesh& fine,
                      const EdgeAdjacency& adjacency, const FeatureSet& features,
                      const CoarsenOptions& options, Progress& progress);

}  // namespace hm
