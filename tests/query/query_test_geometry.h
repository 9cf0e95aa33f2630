// Exact test surfaces and their grid triangulations for the query tests and benchmark.
#pragma once

#include <vector>

#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"

namespace hm::test {

// Rational quadratic quarter cylinder x^2 + y^2 = R^2, x, y >= 0, z in [0, H]; u runs from
// (R, 0) to (0, R), v along z, so su x sv points outwards.
NurbsSurface quarter_cylinder(double radius, double height);
// The whole cylinder as one closed patch (a 9-point rational circle in u: a seam at u = 0, 1).
NurbsSurface full_cylinder(double radius, double height);
// The flat square x = x0, (y, z) in [-h, h]^2 (bilinear); u along y, v along z.
NurbsSurface plate_x(double x0, double half);
// The Wigley half hull y = B/2 (1 - (2x/L)^2)(1 - (z/T)^2), x in [-L/2, L/2], z in [-T, 0], as
// one biquadratic Bezier patch: x linear in u, z = -T v.
NurbsSurface wigley(double length, double beam, double draft);
double wigley_y(double length, double beam, double draft, double x, double z);
// The Bezier surface s split at u = 0.5 by de Casteljau: the halves are exact copies.
std::pair<NurbsSurface, NurbsSurface> split_bezier_u(const NurbsSurface& s);

Patch make_patch(NurbsSurface s, bool reversed = false);

// Appends an (nu x nv)-cell grid of patch p (vertices evaluated on the surface, each quad split
// along its 0-2 diagonal) with vertex_uv, vertex_patch and face_patch.
void add_grid(SurfaceMesh& mesh, const Patch& patch, PatchId p, int nu, int nv);
// Merges vertices closer than tol (the first keeps its patch and uv), as a conforming
// tessellator would share them along patch borders and seams.
void weld(SurfaceMesh& mesh, double tol);

}  // namespace hm::test
