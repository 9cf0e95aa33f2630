// The structured start of every patch: parameter lines placed so that grid edges are about a
// given length in 3D, each quad split into two triangles along its shorter diagonal.
#pragma once

#include <vector>

#include "core/limits.h"
#include "nurbs/nurbs_surface.h"
#include "tessellate/patch_mesh.h"

namespace hm {

// Parameter values of the grid lines in each direction (first = u0/v0, last = u1/v1, knot span
// boundaries always included). speed_* is the largest 3D length per parameter unit met along a
// parameter line (m per unit), mean_speed_* the mean one: they turn metres into parameter units.
struct GridLines {
  std::vector<double> u, v;
  double speed_u = 0, speed_v = 0;
  double mean_speed_u = 0, mean_speed_v = 0;
};

// Each knot span is divided uniformly into ceil(l / edge_length) cells, l being the longest
// parameter line over that span (measured as a polyline on the NURBS). min_cells_* forces at least
// that many cells per direction (3 for a closed direction, so a seam never joins a cell to itself).
// Throws LimitError when the grid would exceed limits.max_triangles.
GridLines grid_lines(const NurbsSurface& s, double edge_length, const ResourceLimits& limits,
                     int min_cells_u = 1, int min_cells_v = 1);

// The grid as a mesh: vertex (i, j) is index i + nu * j (u fastest), two triangles per cell,
// counter-clockwise in (u, v), cells in row order. Points are evaluated in parallel.
PatchMesh grid_mesh(const NurbsSurface& s, const GridLines& lines);

// 3D length of the iso-parameter polyline at fixed v from u = a to u = b (n segments), or at fixed
// u from v = a to v = b when along_u is false.
double iso_line_length(const NurbsSurface& s, bool along_u, double fixed, double a, double b,
                       int n);

}  // namespace hm
