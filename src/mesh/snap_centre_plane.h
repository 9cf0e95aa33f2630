// The open side of a half hull put exactly on the centre plane y = 0. Real files draw a half
// hull's keel and stem a little off the plane (DTMB 5415's transition patch meets it up to 2 mm
// off at model scale), and a panel code reads such a gap as a slot through the hull.
#pragma once

#include <cstddef>

#include "mesh/surface_mesh.h"

namespace hm {

// Sets y = 0 on every vertex of the open boundary (an edge with one face) within tol (metres) of
// the plane. Returns how many moved. The move is at most tol, so a mesh within a deviation bound
// of its surface stays within that bound plus tol.
std::size_t snap_to_centre_plane(SurfaceMesh& mesh, double tol);

}  // namespace hm
