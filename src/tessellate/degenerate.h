// Seams of closed patches and edges collapsed to a point: one vertex where the surface has one
// point, so the mesh has no duplicated vertices, no zero-area triangles and no slivers there.
#pragma once

#include <cstddef>

#include "nurbs/nurbs_surface.h"
#include "tessellate/patch_mesh.h"

namespace hm {

struct Closure {
  bool closed_u = false;  // S(u0, v) == S(u1, v) for all v, within tol
  bool closed_v = false;
};

// Samples the opposite domain sides and compares them in 3D (tol in metres).
Closure detect_closure(const NurbsSurface& s, double tol);

// Sides whose 3D length is at most tol (m).
CollapsedSides detect_collapsed(const NurbsSurface& s, double tol);

// On a grid mesh (vertex (i, j) = i + nu * j): the last column is joined to the first when
// closed_u, the last row to the first when closed_v, before refinement so that both sides of the
// seam refine as one. Triangles keep their own corner (u, v) (u1 on one side, u0 on the other).
// Vertices are not removed (call compact_vertices after the joins): ids keep the grid layout.
void join_seams(PatchMesh& m, std::size_t nu, std::size_t nv, const Closure& c);

// On a grid mesh: every vertex of a collapsed side becomes its first vertex (one apex), and the
// triangles left with a repeated corner (zero area) are dropped, before refinement, so the apex
// is one vertex with a proper fan. Triangles keep their own corner (u, v) at the apex.
void join_collapsed(PatchMesh& m, std::size_t nu, std::size_t nv, const CollapsedSides& c);

// After refinement: vertices closer than tol (metres) become one (the lowest index keeps its
// position and (u, v), so it still evaluates exactly), triangles left with a repeated corner are
// dropped and unused vertices removed, order kept.
void merge_coincident(PatchMesh& m, double tol);

// Zero-area triangles with three distinct corners. Next to an apex a corner lies on the opposite
// edge: that (longest) edge is flipped with the neighbour across it. Where no flip gives two
// triangles with area (the edge is on the boundary, or the parametrisation folds a whole region
// onto a curve, which covers no surface) the triangle is dropped. area_fraction: a triangle is
// zero when its area is at most this fraction of its longest edge squared.
void remove_zero_area(PatchMesh& m, double area_fraction);

// Removes unreferenced vertices, keeping the order of the others.
void compact_vertices(PatchMesh& m);

}  // namespace hm
