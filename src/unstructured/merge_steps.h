// The steps of merge_patches, one file each. Internal to src/unstructured.
#pragma once

#include <array>
#include <span>
#include <utility>
#include <vector>

#include "core/progress.h"
#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"
#include "unstructured/merge.h"
#include "unstructured/merge_border.h"

namespace hm::merge {

// The mesh being merged: triangles, and for each face the input triangle it was cut from.
struct Work {
  SurfaceMesh mesh;
  std::vector<Index> face_old;  // per face
  std::vector<Index> vert_old;  // per vertex
};

// Keeps the faces with keep[f] != 0 (in order), with their patches and input triangles.
void compact_faces(Work& w, std::span<const std::uint8_t> keep);
// Appends faces closing a hole. Each takes the patch and input triangle of the face of `around`
// (the faces along the hole, not empty) whose plane it lies most nearly in.
void append_faces(Work& w, std::span<const Face> faces, std::span<const Index> around);

// Per-vertex gap tolerance: options.gap_tolerance, or half the local border edge length.
double vertex_tolerance(const MergeOptions& options, double border_edge_length);

struct OverlapStats {
  std::size_t triangles = 0;
  double area = 0;       // m^2
  bool changed = false;  // faces removed or corners moved: the border must be collected again
  // (patch, patch below it) of every seed covered by a layer whose normal runs the opposite
  // way (as compared: turned by outward_sign, or by the patches' own flags), sorted, each once.
  std::vector<std::pair<PatchId, PatchId>> covered_opposite;
};
// Finds border vertices of one patch that lie inside another patch's surface (closest point
// within a few chord errors, normals compatible, away from that patch's border), grows the
// covered region over the patch, and cuts the patch's faces along the border of the patches
// below it, keeping the part outside them (new vertices where edges leave them; no vertex
// moves). Of two patches covering each other, the higher-numbered one is cut. border is
// collect_border of the mesh as it comes in. outward_sign, when not empty, holds +1 or -1 per
// patch: the side of su x sv the hull's outside lies on, as an earlier merge oriented it (the
// normals of coincident layers are then compared with their patches turned alike); empty, each
// patch's `reversed` flag gives it.
OverlapStats remove_overlaps(std::span<const Patch> patches, Work& w, const Border& border,
                             const MergeOptions& options, double length,
                             std::span<const double> outward_sign, Progress& progress);

// One side of a gap, as the corner sees it: a border vertex (or a point on a border edge), the
// plane its surface ends in, the way into its patch, and the ways its border runs on from it.
struct CornerSide {
  Vec3d p;
  Vec3d n;         // unit surface normal (orientation does not matter); zero: no one plane
  Vec3d in;        // unit, into its patch
  Vec3d along[2];  // unit, along its border edges from p (zero where there is none)
};

// One per border vertex (in border order); local maps mesh vertex -> border index, inward is
// vertex_inward's.
std::vector<CornerSide> corner_sides(const SurfaceMesh& m, const Border& b,
                                     std::span<const Index> local, std::span<const Vec3d> inward);
// The point where the gap between two sides closes (close_at_corner.cpp): their corner when they
// meet at a knuckle, else c (their mean). edge: the border edges' length there, m.
Vec3d close_at_corner(const CornerSide (&side)[2], const Vec3d& c, double edge);

struct SnapStats {
  std::size_t welded = 0;
  std::size_t split = 0;
  std::size_t gaps_closed = 0;
  double widest = 0;  // m
};
// Welds border vertices of different patches and splits border edges at the other patches'
// vertices (T-junctions), so that borders within tolerance meet vertex to vertex. border is
// collect_border of the mesh as it comes in. tol_scale, when not empty, scales each border
// vertex's tolerance (same order as border.vertices).
SnapStats snap_borders(Work& w, const Border& border, const MergeOptions& options, double length,
                       std::span<const double> tol_scale = {});

// Closes boundary loops of 3 or 4 vertices that run along two or more patches (the holes
// pairwise zipping leaves where several patch corners meet), and, up to 16 vertices, pinholes
// smaller than the faces around them and slits no wider on average than the gap tolerance. adj is
// the mesh's current adjacency. Returns the holes filled (when none, adj is still current). The new
// faces take the provenance of a face along the loop (append_faces). left_open, when given, gets
// the edges (vertex pairs) of the holes it would close but cannot: a hole of four vertices whose
// both diagonals are edges already, a slit with no ear free to clip. Both are folds the snap made.
// A hole of four vertices with one diagonal taken, whose other would fold back on itself (a dart
// round the taken diagonal), is closed by collapsing the taken edge instead: its two faces keep a
// repeated corner and the moved vertex is left unused. One with both diagonals taken where one
// face runs along two of its sides (a remnant folded over the patch below) is closed by that
// face's going and the quad's other half taking its place. Both leave work for drop_degenerate.
struct HoleStats {
  std::size_t filled = 0;           // holes closed, these among them
  std::size_t left_degenerate = 0;  // closed by a collapse or a remnant's going
};
HoleStats fill_small_holes(Work& w, const EdgeAdjacency& adj, const MergeOptions& options,
                           std::vector<std::array<Index, 2>>* left_open = nullptr);

// Closes the holes whose vertices all lie on one line (up to 128 of them) by splitting the faces
// along each at its vertices, as fill_small_holes does for the holes it meets. The merge's last
// steps (the zipper, the welds and splits of flat faces) can leave one: a full round-bilge hull
// with 0.1 m gaps at 40,000 triangles kept a slit of 28 vertices, 9.5 cm long, where the two
// halves' transom edges meet at the centre plane. adj is the mesh's current adjacency. Returns
// the holes closed.
std::size_t close_flat_holes(Work& w, const EdgeAdjacency& adj);

// A boundary loop that passes a vertex twice (holes touching at a vertex, or a hole touching the
// hull's outline) cut there into simple cycles: (vertices, edges), edges[i] leaving vertices[i].
std::vector<std::pair<std::vector<Index>, std::vector<Index>>> cycles_of(const BoundaryLoop& loop);

// Zips shut the boundary loops along two or more patches whose mean width (twice the area over
// the perimeter) is at most `widest` metres: gaps wider than the border edges, which the snap
// cannot close vertex to vertex. Each loop's two runs between its ends are joined by triangles
// across the shorter next diagonal; a loop where a diagonal would be an edge already, or longer
// than four times `widest`, is left. adj is the mesh's current adjacency. Returns the loops
// closed. The new faces take the provenance of a face along the loop (append_faces).
std::size_t bridge_gaps(Work& w, const EdgeAdjacency& adj, double widest);

// Faces whose three corners lie on one line (a zipper or fan laid along a straight border) go:
// each one's neighbour across its longest side is split at its third corner, or, where two of
// its corners lie on one spot, those two are welded. Returns the faces removed; a mesh with
// none is untouched. length: the hull's, for drop_degenerate's area floor.
std::size_t split_flat_faces(Work& w, double length);

struct FoldStats {
  std::size_t faces = 0;
  double area = 0;  // m^2
};
// Drops, on each edge with three faces or more, the face of a pair from different patches that
// lie on each other (on the same side of the edge, within 20 degrees): an overlap remnant the
// snap laid there. Of the two, the one with more boundary edges goes, then the higher-numbered
// patch's. adj is the mesh's current adjacency. Vertices stay (drop_degenerate removes the
// unused ones).
FoldStats drop_folded_faces(Work& w, const EdgeAdjacency& adj);

// Drops, of the two faces on each edge both traverse the same way, a remnant: of two faces from
// different patches lying on each other (as drop_folded_faces; round-bilge 100 with every defect,
// x = 34.5 m), the one with more boundary edges, then the higher patch's; else a face whose
// normal is turned against every face across its edges (two at least), a sliver the snap turned
// inside out by welding a corner across its far side (round-bilge 100 with 0.1 m gaps and 5%
// overlaps, x = 9.5 m). adj is the mesh's current adjacency. Vertices stay (drop_degenerate
// removes the unused ones).
FoldStats drop_inconsistent_remnants(Work& w, const EdgeAdjacency& adj);

// Interior edges (two faces, wound consistently) whose two faces lie on each other: both on the
// same side of the edge, within 20 degrees, so that the surface folds back there and the faces
// pass through their neighbours. The overlap cut leaves such a fold of slivers along a chine
// where the cut of two overlapping patches runs along the knuckle (property seed 3553: two
// slivers 0.29 m long on one edge, 2-5 mm wide, their third corners 3 mm apart). Returns, for
// each fold of two slivers (each third corner within kFoldWeldShare of the edge's length of
// the edge) whose third corners lie as near each other, the pair (higher index, lower index)
// to weld: welded, the two faces are the same
// corners wound against each other, a double layer that drop_degenerate removes. A vertex is
// in one pair at most; pairs in edge order.
std::vector<std::pair<Index, Index>> folded_edge_welds(const Work& w, const EdgeAdjacency& adj);

// A flap: a triangle turned against two or more of its neighbours across its edges (turned(f, g)
// says whether g is turned against f); the fold steps differ in how far "turned" is.
template <class Turned>
bool is_flap(const EdgeAdjacency& adj, Index f, const Turned& turned) {
  int against = 0;
  for (int k = 0; k < 3; ++k) {
    const Index g = adj.opposite_face[4 * f + k];
    against += g != kInvalid && turned(f, g);
  }
  return against >= 2;
}

// Flips, pass by pass, each interior edge between two triangles folded against each other
// (normals more than 120 degrees apart) of which one is a flap, turned against two or more of its
// neighbours, where the flip leaves two triangles facing the same way: a fan closing a slit that
// came out folded over the other border. adj is the mesh's current adjacency, and is again on
// return. Returns the flips; a mesh with no flap is untouched.
std::size_t flip_folded_flaps(Work& w, EdgeAdjacency& adj);

// Drops faces with a repeated corner or (near) zero area and vertices no face uses. Returns the
// number of faces dropped.
std::size_t drop_degenerate(Work& w, double length);

// Turns patches wound against their neighbours (by shared-edge votes, largest patch first) and
// then each connected part so that its enclosed volume is positive. Returns the patches whose
// final winding is against their declared orientation (NURBS su x sv, negated for reversed).
// `oriented` gets the adjacency of the oriented mesh.
std::vector<PatchId> orient_faces(std::span<const Patch> patches, Work& w, EdgeAdjacency& oriented);

// A border vertex of an open gap: the distance across to the nearest border edge of another
// patch (metres), beyond its tolerance but within options.gap_report_edges local border edges
// (or `reach` metres, when that is farther).
struct OpenGapVertex {
  Index vertex = kInvalid;  // mesh vertex
  PatchId across = kInvalid;
  double width = 0;
};
// Every such vertex, in ascending vertex order.
std::vector<OpenGapVertex> find_open_gap_vertices(const Work& w, const EdgeAdjacency& adj,
                                                  const MergeOptions& options, double reach = 0);

// Border stretches of two patches that stay apart by more than the tolerance but less than
// options.gap_report_edges local border edges, widest first.
std::vector<OpenGap> find_open_gaps(const Work& w, const EdgeAdjacency& adj,
                                    const MergeOptions& options);

// Reorders vertices and faces in Morton order (faces by centroid), updating the maps.
void reorder_morton(Work& w);

}  // namespace hm::merge
