// The open side of a half hull put exactly on the centre plane y = 0. Real files draw a half
// hull's keel and stem a little off the plane (DTMB 5415's transition patch meets it up to 2 mm
// off at model scale), and a panel code reads such a gap as a slot through the hull.
#pragma once

#include <cstddef>

#include "mesh/surface_mesh.h"

namespace hm {

// Sets y = 0 on every vertex of the open boundary (an edge with one face) within tol (metres) of
// the plane, and on the corners of a face along it that lies within tol of the plane and would
// lie back to back with its mirror image (centres within a twentieth of its size: a sliver at a
// fine stem). Returns how many moved. The move is at most tol, so a mesh within a deviation
// bound of its surface stays within that bound plus tol. slivers = false leaves the faces alone
// (a heeled hull's sides, meshed apart: the other side's panels are no mirror image, and two
// panels flattened into the plane would lie across each other).
std::size_t snap_to_centre_plane(SurfaceMesh& mesh, double tol, bool slivers = true);

// Removes the faces whose corners all lie on y = 0 exactly (after snapping): a panel in the
// symmetry plane is no part of a half hull's surface, and its mirror image would lie on it.
// Keeps every per-face array in step; vertices stay. Returns how many went.
std::size_t drop_centre_plane_faces(SurfaceMesh& mesh);

}  // namespace hm
