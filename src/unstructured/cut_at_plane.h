// The merged fine surface cut at a plane before it is coarsened: the waterplane (keep the wetted
// part below it) or the centre plane (keep one half of a full hull). The cut line is then a mesh
// border from the start, so the panels made from the mesh end exactly on it (a finished mesh is
// never clipped). The cut comes after the merge: on the merged surface an edge at a patch border
// is one edge, so both patches share its new vertex and the cut line stays one conforming line
// across patch borders.
//
// Frame: the caller's (for the waterplane, the floating frame: the patches already placed at
// their draft, trim and heel), metres. Every vertex the cut makes lies on the NURBS (refined in
// double precision) and on the plane exactly (its coordinate set to the plane's value).
#pragma once

#include <span>
#include <vector>

#include "core/types.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"

namespace hm {

struct PlaneCutOptions {
  // The plane x[axis] = value (axis 0, 1, 2 for x, y, z); the part kept is below the value
  // (keep_below) or above it.
  int axis = 2;
  double value = 0;
  bool keep_below = true;
  // Split only: both sides are kept and the plane becomes a line of mesh edges inside the surface
  // (the waterline of a hull meshed above the waterplane too). keep_below then only orients
  // side() and does not drop anything.
  bool keep_both = false;
  // A vertex closer to the plane than this fraction of its shortest edge is moved onto it first,
  // so that the cut leaves no sliver (the move is at most half that edge, so no triangle folds).
  // A vertex inside one smooth patch moves along the patch; a vertex on a line (the mesh
  // boundary, a patch border, a knuckle) slides along the line to where it crosses the plane, so
  // the line stays where it is. 0: no snapping.
  double snap_fraction = 0.3;
};

struct PlaneCutReport {
  std::size_t faces_in = 0, faces_kept = 0, faces_split = 0;
  std::size_t vertices_snapped = 0;  // moved onto the plane along their patch or line
  std::size_t edges_cut = 0;         // new vertices on the cut line
  std::size_t unconverged = 0;       // new vertices whose refinement missed its tolerance
  double seconds = 0;
};

struct PlaneCut {
  SurfaceMesh mesh;                 // triangles; vertex_patch and vertex_uv kept and extended
  std::vector<Index> face_new2old;  // the input face each output face comes from
  PlaneCutReport report;
};

// mesh: a surface over `patches` with each vertex's patch and (u, v) (the merged surface, or a
// tessellation); quads are cut as triangles 0-1-2 and 0-2-3. Faces keep their patch. Throws
// GeometryError when the mesh lacks vertex (u, v) or the axis is not 0, 1 or 2.
PlaneCut cut_at_plane(std::span<const Patch> patches, const SurfaceMesh& mesh,
                      const PlaneCutOptions& options);

}  // namespace hm
