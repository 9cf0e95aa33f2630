// The second half of a plane section: refined open pieces joined across gaps, oriented and put
// in a fixed order. Internal to src/query; no Embree here.
#pragma once

#include <vector>

#include "core/vec.h"
#include "query/hull_query.h"

namespace hm::query {

// Open pieces whose ends lie within join_tol (metres) are chained; the closest pairs of ends go
// first. Pieces already closed pass through. Then every polyline is oriented (see
// SectionPolyline) and the list sorted (see Section), with ties in z, y decided at join_tol.
Section assemble_section(std::vector<SectionPolyline> pieces, const Vec3d& plane_normal,
                         double join_tol);

// Drops consecutive points closer than tol (and, for a closed polyline, a last point equal to
// the first); a plane through a mesh vertex gives the same point from several edges.
void drop_repeated_points(SectionPolyline& line, double tol);

}  // namespace hm::query
