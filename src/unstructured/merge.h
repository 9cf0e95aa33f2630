// Merge: the patch triangulations of a hull become one watertight, consistently oriented
// triangle mesh with shared vertices.
//
// Steps (one file pair each): collect the patch borders, remove_overlaps (coincident layers,
// found with the Embree closest-point queries), snap_borders (weld border vertices and split
// T-junctions so that borders meet vertex to vertex), orient_faces (consistent winding, normals
// out of the ship), and a Morton reorder for locality. Where a flipped patch overlaps an
// unflipped one, the merge runs a second time with the patches' normals turned as the first
// oriented them. Positions in metres, model frame.
#pragma once

#include <span>
#include <vector>

#include "core/progress.h"
#include "core/types.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"

namespace hm {

struct MergeOptions {
  // Widest gap between patch borders that is closed (metres). <= 0: half the local border edge
  // length at each vertex. A border vertex never moves more than half of this.
  double gap_tolerance = 0;
  // Remove layers where two patches cover the same surface (compatible normals).
  bool remove_overlaps = true;
  // A vertex of one patch within this distance of another patch's surface, with normals within
  // 30 degrees, lies on that patch (metres). <= 0: 1e-4 L.
  double overlap_distance = 0;
  // Gaps wider than the tolerance but narrower than this many local border edge lengths are
  // reported as gaps; farther borders are taken for true boundaries (deck edge, centre plane).
  double gap_report_edges = 2;
  // With the default tolerance: where a gap stays open, snap again with the tolerance widened
  // to the gap measured there (see merge_patches).
  bool widen_to_gaps = true;
  // Zip shut the thin loops along two or more patches that the snap left (gaps wider than the
  // border edges), up to the tolerance (by default 2e-3 L).
  bool bridge_gaps = true;
};

// A stretch of two patch borders that stayed apart.
struct OpenGap {
  PatchId patch_a = kInvalid, patch_b = kInvalid;  // patch_a < patch_b
  Vec3d location;                                  // the border vertex where the gap is widest
  double width = 0;                                // widest distance across, metres
  std::size_t vertices = 0;                        // border vertices of the two patches along it
};

struct MergeReport {
  std::size_t input_triangles = 0;
  std::size_t vertices_welded = 0;   // border vertices joined to another patch's vertex
  std::size_t tjunctions_split = 0;  // border vertices inserted into another patch's edge
  std::size_t gaps_closed = 0;       // welds and splits across a distance above 1e-9 L
  double widest_gap_closed = 0;      // metres
  // Times the snap ran again with a smaller tolerance near edges it had given three faces.
  std::size_t snap_retries = 0;
  // Border vertices whose tolerance was widened to the gap measured there, and the widest
  // tolerance given (metres; see merge_patches).
  std::size_t gap_vertices_widened = 0;
  double widened_to = 0;
  // Gaps still open after that, zipped shut as thin loops (see merge_patches).
  std::size_t gaps_bridged = 0;
  std::vector<OpenGap> open_gaps;  // sorted by width, widest first
  std::size_t overlap_triangles_removed = 0;
  double overlap_area_removed = 0;       // m^2
  std::vector<PatchId> patches_flipped;  // wound against their declared orientation, turned
  // The merge ran twice: a flipped patch and an unflipped one overlapped, and the overlaps were
  // cut again with the patches turned as the first merge had oriented them.
  bool overlaps_cut_oriented = false;
  std::size_t degenerate_faces_dropped = 0;
  // Faces of one patch the snap laid on another's across a shared edge (an edge with three
  // faces), dropped as overlap remnants; their area is in overlap_area_removed.
  std::size_t folded_faces_dropped = 0;
  // Interior edges whose two faces lay on each other (a fold of slivers the overlap cut left
  // along a chine), closed by welding the faces' third corners.
  std::size_t folds_welded = 0;
  // Triangles folded back over their neighbours (a slit's closing fan laid over the far border),
  // flipped flat (flip_folded_flaps).
  std::size_t folds_flipped = 0;
  // Faces with their corners on one line, taken out by splitting a neighbour (split_flat_faces).
  std::size_t flat_faces_split = 0;
  std::size_t holes_filled = 0;  // corner holes of 3-4 vertices between patches, closed
  // The result's topology (from its edge adjacency).
  std::size_t boundary_loops = 0;
  std::size_t nonmanifold_edges = 0;
  std::size_t inconsistent_edges = 0;
  double enclosed_volume = 0;  // m^3, with every boundary loop closed by a fan; > 0: normals out
  double seconds = 0;
};

struct MergedSurface {
  // Triangles with shared vertices; vertex_patch, vertex_uv, face_patch filled. Vertices and faces
  // in Morton order. A vertex the snap moved across a gap (a weld's mean, a split's halfway point)
  // keeps the (u, v) it had on its patch, and may lie off the patch: a caller that evaluates a
  // vertex's (u, v) checks it against the position (see find_knuckles).
  SurfaceMesh mesh;
  // Maps to the input triangulation: the input vertex each vertex came from (for welded vertices,
  // the lowest-numbered one), and the input triangle each face was cut from.
  std::vector<Index> vert_new2old;
  std::vector<Index> face_new2old;
  MergeReport report;
};

// `triangulation` is the output of tessellate() for `patches` (triangles, vertices not shared
// between patches, vertex_patch / vertex_uv / face_patch filled). Deterministic for any thread
// count. Throws GeometryError when the input arrays disagree.
MergedSurface merge_patches(std::span<const Patch> patches, const SurfaceMesh& triangulation,
                            const MergeOptions& options, Progress& progress);

namespace merge {
// Volume enclosed by the mesh with every boundary loop closed by a fan from its centroid, m^3 (the
// report's enclosed_volume; adj is the mesh's).
double enclosed_volume(const SurfaceMesh& mesh, const EdgeAdjacency& adj);
}  // namespace merge

}  // namespace hm
