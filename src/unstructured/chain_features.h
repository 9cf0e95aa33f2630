// Corners and knuckle lines: the feature edges (knuckles and boundary edges) as a graph, its
// corners, and the knuckle edges chained between them. Private to src/unstructured.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "unstructured/features.h"

namespace hm::detail {

// Turn between consecutive feature edges (degrees) above which their vertex is a corner.
inline constexpr double kCornerTurnDeg = 60;

struct ChainedFeatures {
  std::vector<FeatureLine> knuckles;  // ordered by (first vertex, second vertex)
  std::vector<VertexFeature> vertex_feature;
  std::vector<Index> corners;  // ascending
};

// A vertex is a corner when its feature degree is 1 or at least 3, when it ends an open
// boundary run (a change of kind), when its two feature edges are one knuckle and one boundary
// edge, or when they turn by more than kCornerTurnDeg. Knuckle lines are maximal chains of
// knuckle edges between corners; a chain that meets no corner, or comes back to the corner it
// left, is closed. Lines are oriented canonically: an open line starts at its lower end vertex,
// a closed one at its lowest vertex towards the lower of that vertex's two neighbours.
ChainedFeatures chain_features(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                               std::span<const std::uint8_t> edge_knuckle,
                               std::span<const BoundaryRun> boundaries);

}  // namespace hm::detail
