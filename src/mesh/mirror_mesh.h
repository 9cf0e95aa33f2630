// A half hull mirrored about the centre plane y = 0 into the full hull, for panel codes (or runs)
// that take no symmetry flag.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/types.h"
#include "mesh/surface_mesh.h"

namespace hm {

struct MirroredMesh {
  SurfaceMesh mesh;                 // the half first, then its mirror image
  std::vector<Index> vert_new2old;  // the half's vertex each vertex comes from
  std::vector<Index> face_new2old;  // the half's face each face comes from
};

// True when no vertex lies beyond tol (metres) on one of the two sides of y = 0.
bool is_half_hull(const SurfaceMesh& mesh, double tol);

// Vertices of the open boundary within on_plane_tol (metres) of y = 0 are set to y = 0 and shared
// by both halves; the others are repeated with y negated. Mirrored faces run in reverse order (a
// reflection turns the winding, and reversing it keeps every normal pointing into the fluid). Faces
// keep their patch and block. A quad with three corners shared (folded against the plane) is
// split into two triangles that both take its fourth corner, in both halves: its image would lie
// on it. Throws GeometryError when vertices lie on both sides of y = 0 beyond the tolerance (not a
// half hull).
MirroredMesh mirror_half_hull(const SurfaceMesh& half, double on_plane_tol);

// The mirror images of edges of the half (vertex pairs), for a mesh mirror_half_hull made from a
// half with half_vertices vertices. A vertex on y = 0 is its own image.
std::vector<std::array<Index, 2>> mirrored_edges(const MirroredMesh& m, std::size_t half_vertices,
                                                 std::span<const std::array<Index, 2>> edges);

}  // namespace hm
