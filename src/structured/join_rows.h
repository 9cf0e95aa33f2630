// Strips between rows with different curve counts (a bulb ahead of the stem, a dome or a skeg
// that a station cuts off the hull): each row's curves are joined into one chain through the
// surface's boundary between them, and the two chains are zipped.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {

// strips: the j of each strip (rows j and j + 1) to join, ascending. Appends faces (and fixed
// boundary nodes) to mesh and slots. Returns the strips it closed; a strip whose curve ends do
// not lie on one boundary loop stays open.
std::vector<std::size_t> join_rows(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                                   std::span<const Row> rows, std::span<const RowNodes> nodes,
                                   std::span<const std::vector<Index>> first_vertex,
                                   std::span<const std::size_t> strips, const Metric& metric,
                                   const ZipOptions& zip, SurfaceMesh& mesh,
                                   std::vector<NodeSlot>& slots);

}  // namespace hm::structured
