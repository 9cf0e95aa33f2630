// The structured mesher on a heeled hull. Heeled, a hull has no y = 0 symmetry and its stations
// are no longer square to its centre plane, and rows run round the keel from one waterline to the
// other cross each other. So each side is meshed on its own, in the ship's own frame (trimmed,
// not heeled: the centre plane is y = 0 there and the waterplane leans by the heel), on the
// stations of the whole hull, and the two are joined on the centre plane.
#pragma once

#include "cli/prepare_hull.h"
#include "structured/structured.h"

namespace hm::cli {

// hull: prepared afloat and heeled (whole, cut at the waterplane). Returns the panels in the
// floating frame, as mesh_structured would; `join`, when given, gets the seam's counts. Throws
// what mesh_structured throws.
StructuredMesh mesh_heeled_sides(const PreparedHull& hull, StructuredOptions options,
                                 SideJoin* join = nullptr);

}  // namespace hm::cli
