// Strips between rows with different curve counts (a bulb ahead of the stem, a dome, a skeg or a
// propeller boss that a station cuts off the hull): curves joined through the surface's boundary
// where it lies inside the strip, matched across it, and a piece of hull that ends inside the
// strip capped against the boundary around its end.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {

struct JoinCounts {
  std::vector<std::size_t> closed;  // the strips closed
  std::size_t caps = 0;             // groups of curves capped inside their strip
  std::size_t ends_closed = 0;      // of the open ends, those closed by groups
};

// strips: the j of each strip (rows j and j + 1) to join, ascending. Appends faces (and fixed
// boundary nodes) to mesh and slots. A strip whose curve ends do not lie on one boundary loop
// stays open. open_ends: the aft and forward ends cap_ends left open; each is tried the same way,
// its row's curves grouped through the boundary beyond it and every group capped.
JoinCounts join_rows(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                     std::span<const Row> rows, std::span<const RowNodes> nodes,
                     std::span<const std::vector<Index>> first_vertex,
                     std::span<const std::size_t> strips, const Metric& metric,
                     const ZipOptions& zip, std::array<bool, 2> open_ends, SurfaceMesh& mesh,
                     std::vector<NodeSlot>& slots);

}  // namespace hm::structured
