// Border gaps: where two consecutive rows end on the surface's boundary at places the boundary
// does not join straight (the stem between a row ending on the waterline and one ending on the
// centre plane; an open transom's edge), the panel edge between the two ends cuts a sliver off
// the hull. The sliver is filled with a fan to the boundary path, resampled at the panel size.
// Where the path turns the corner of the centre plane and the waterline, on such an edge or on
// an end cap's (a transom immersed a few hundredths of a panel, whose corner the cap's
// resampling drops), the two sides of the corner are zipped against each other instead.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {

struct GapCounts {
  std::size_t gaps = 0, triangles = 0;
};

// row_end: per vertex of mesh, 1 for a row curve's end node. up: the waterplane's unit normal.
// Appends triangles (and fixed boundary nodes) to mesh and slots.
GapCounts close_border_gaps(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                            std::span<const std::uint8_t> row_end, const Vec3d& up,
                            const Metric& metric, SurfaceMesh& mesh, std::vector<NodeSlot>& slots);

}  // namespace hm::structured
