// Boundary runs of a merged hull surface: every boundary edge gets a BoundaryKind, and each
// boundary loop is cut into maximal runs of one kind. Private to src/unstructured.
//
// Frame: x along the ship (either end may be the bow), y athwartships with the centre plane at
// y = 0 (a half hull may be either side), z up. L is the largest bounding-box extent. Rules, per
// boundary edge, first match wins:
//   1. kWaterline   both ends within 2e-4 L of options.waterline_z (when not NaN);
//   2. kCentrePlane both ends within 2e-4 L of y = 0;
//   3. kTransomEdge part of a run of consecutive boundary edges, each running within 30 degrees of
//                   the y-z plane (|dx| <= |edge| / 2) with its face not itself facing along x
//                   (|n_x| < 0.7: the hull ends at the edge, it is not the top of a modelled
//                   transom), the run within 0.25 L of either x end of the surface and spanning
//                   at least 0.01 L;
//   4. kDeckEdge    its face lies below it (the face centroid below the edge's line, square to
//                   the edge) and nothing of the surface stands more than 5% of the z extent
//                   above the edge's top end over the edge's own x range (faces clipped to it,
//                   the range shrunk by 1e-6 L at each end): the sheer line, whatever its rise,
//                   up to where a raised side begins, and the top of a modelled transom;
//   5. kHole        everything else (a gap the merger left open, a lower rim, ...).
#pragma once

#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "unstructured/features.h"

namespace hm::detail {

// Kind of every boundary edge listed in adjacency.boundary_loops, indexed by edge id (entries of
// other edges are unspecified).
std::vector<BoundaryKind> classify_boundary_edges(const SurfaceMesh& mesh,
                                                  const EdgeAdjacency& adjacency,
                                                  const FeatureOptions& options, double length);

// Each loop cut into maximal runs of one kind, loops in adjacency order, runs in loop order. A
// closed loop of one kind gives one closed run; otherwise a closed loop's runs start at a change
// of kind. Run ends are the vertices where the kind changes (or an open loop ends).
std::vector<BoundaryRun> boundary_runs(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                                       std::span<const BoundaryKind> edge_kind);

}  // namespace hm::detail
