// The ends of the hull beyond the first and last stations (the stem and the stern or transom):
// each is zipped between its end row and the surface's boundary path beyond it.
#pragma once

#include <array>
#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {

struct CapCounts {
  std::size_t quads = 0, triangles = 0;
  std::array<bool, 2> open{false, false};  // the aft and the forward end left open
  std::size_t transoms = 0;  // ends closed through a transverse knuckle (a transom's edge)
  std::vector<std::array<Index, 2>> knuckle_edges;  // panel edges along those knuckles
};

// Appends the cap faces (and the new boundary nodes, fixed) to mesh and slots. Where a knuckle
// crosses the end region from one side of its boundary to the other (a transom's edge), the cap
// is two strips: row to knuckle, and knuckle to the boundary beyond, so no panel straddles it.
// An end whose row has more than one curve, or whose ends do not lie on one boundary loop of the
// surface, is left open and flagged in open (join_rows then tries it by groups).
CapCounts cap_ends(const SurfaceMesh& surface, const EdgeAdjacency& adj, const FeatureSet& features,
                   std::span<const Row> rows, std::span<const RowNodes> nodes,
                   std::span<const std::vector<Index>> first_vertex, const Metric& metric,
                   const ZipOptions& zip_options, SurfaceMesh& mesh, std::vector<NodeSlot>& slots);

}  // namespace hm::structured
