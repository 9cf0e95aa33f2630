// Paths along the surface's boundary, shared by the end caps and the border-gap closing.
#pragma once

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {

// A place on the surface's boundary: the loop, the loop edge (joining vertices[edge] and
// vertices[edge + 1]) and the distance from the query point (m).
struct LoopSpot {
  std::size_t loop = 0, edge = 0;
  double distance = std::numeric_limits<double>::infinity();
};

LoopSpot nearest_boundary_edge(const SurfaceMesh& s, const EdgeAdjacency& adj, const Vec3d& q);

// The loop vertices strictly between spots on loop edges ea and eb, walking forwards or
// backwards; empty when both lie on one edge.
std::vector<Index> loop_path(const std::vector<Index>& v, std::size_t ea, std::size_t eb,
                             bool forward);

// The surface's boundary from a to b (points on it, within tol of a boundary edge of one loop),
// the shorter way round in the metric, as a polyline from a to b; empty when a and b do not lie
// on one loop within tol.
// With x_lo and x_hi, only a way round that stays between the planes x = x_lo and x = x_hi (the
// slab between two stations) counts.
std::vector<Vec3d> shortest_border_path(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                                        const Vec3d& a, const Vec3d& b, const Metric& metric,
                                        double tol,
                                        double x_lo = -std::numeric_limits<double>::infinity(),
                                        double x_hi = std::numeric_limits<double>::infinity());

// A strip's slab reaches this far beyond its two stations (panel lengths along x): the boundary
// between two rows' curves crosses a station plane a little where it is refined on the NURBS.
// The joins and the bridges between rows read boundary paths within it.
inline constexpr double kSlabMargin = 0.25;

// Metric arc-length fractions (0 to 1) of a chain of mesh nodes.
std::vector<double> chain_fractions(std::span<const Index> ids, const SurfaceMesh& mesh,
                                    const Metric& metric);

// Resamples the polyline pts at about one panel per metric unit, keeping its corners (turns over
// 40 degrees); returns the interior points (the two ends excluded), none nearer than a quarter
// panel to the one before or to the last end.
std::vector<Vec3d> resample(const std::vector<Vec3d>& pts, const Metric& metric);

}  // namespace hm::structured
