// Faces of a surface mesh that pass through other faces: two patches that cross each other, an
// appendage that pierces the hull untrimmed, or a mesh folded onto itself. A panel code cannot
// integrate over such a surface, and no mesher should be handed one.
//
// Candidates are the pairs of triangles whose boxes overlap (kernels/box_pairs.h, a uniform grid:
// Embree's rtcCollide took 10 times as long to build and traverse); each candidate pair is then
// decided in double precision, in a local frame.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/surface_mesh.h"

namespace hm {

struct FaceCrossing {
  Index face_a = kInvalid, face_b = kInvalid;  // face_a < face_b
  Vec3d where;  // middle of the segment the two faces share, model frame, m
};

struct SelfIntersections {
  std::size_t count = 0;            // face pairs that cross
  std::vector<FaceCrossing> first;  // the first max_listed pairs by (face_a, face_b)
};

// Quads are tested as the triangles (0, 1, 2) and (0, 2, 3). Faces that share a vertex are not
// tested against each other: they meet at that corner or edge by construction.
//
// Two triangles cross when each has corners more than tol (m) on both sides of the other's plane
// and their chords on the line where the planes meet overlap by more than tol; two coplanar ones
// (every corner within tol of the other's plane) when their interiors overlap by more than tol.
// A touch (a corner on a face, a T-junction) is not a crossing. Nor, therefore, is a surface
// that passes through another exactly along its edges: every face there only touches it.
SelfIntersections find_self_intersections(const SurfaceMesh& mesh, double tol,
                                          std::size_t max_listed = 16);

// The depth (m) below which two faces crossing only round off: 1e-7 of the points' largest extent.
// Every count of crossings (the merge's, the quality report's, the structured repairs') uses it.
double crossing_tolerance(std::span<const Vec3d> positions);

// Whether faces a and b cross by that rule (false when they share a vertex): for a few faces
// under a local edit, where a whole-mesh search would not pay.
bool faces_cross(std::span<const Vec3d> positions, const Face& a, const Face& b, double tol);

}  // namespace hm
