// Strips whose two rows start far apart on the surface's boundary: by an immersed open transom
// in trim, one station cuts the bottom from the keel up and the next, aft of the transom's edge,
// only from that edge up. Zipped whole, the longer curve's bottom panels reach across the open
// transom to the shorter's start and pass through the strip's other panels (ship_449_patches at
// 12 m with --trim 3: 9 pairs). The boundary between the two starts is laid as a chain of nodes
// ahead of the later start, so that the strip runs from the one start to the other along it.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {

// bridges[j]: strip j's bridges, at most one per curve. A curve pair is bridged when one start
// lies on the centre plane (|y| <= centre, m) and the other off it, more than two panels across,
// and the surface's boundary joins them inside the strip's slab, at least a third as long as the
// curve from the centre plane. The new nodes are appended to
// mesh and slots (fixed boundary nodes), strip by strip in row order.
std::vector<std::vector<StartBridge>> bridge_starts(
    const SurfaceMesh& surface, const EdgeAdjacency& adj, std::span<const Row> rows,
    std::span<const std::vector<Index>> first_vertex, const Metric& metric, double centre,
    SurfaceMesh& mesh, std::vector<NodeSlot>& slots);

}  // namespace hm::structured
