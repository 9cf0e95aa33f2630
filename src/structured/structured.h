// The paper's structured path: multi-block panel meshes grown row by row on a hull surface.
//
// Rows are the hull's sections by station planes x = const, refined onto the NURBS. Blocks are
// bounded by cut stations (user planes, or automatic ones), by knuckle lines and lateral cut
// planes (waterlines z = c, buttocks y = c, any plane not normal to x) that split every row, and
// by the hull's own boundaries (keel and centre plane, waterline cut, deck). Border rows are
// meshed first and shared; inside a block each row is grown from the one before it, every node
// walking along the hull in the plane normal to its row until it meets the next station; then
// consecutive rows are zipped into quads, and into triangles where the node counts differ or a
// quad would be twisted.
//
// Frame: the ship frame (x forward, y to port, z up), metres. The surface is the merged hull as
// the unstructured path prepares it (waterplane and centre-plane cuts applied).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"
#include "unstructured/features.h"

namespace hm {

class HullQuery;

// A plane that splits the hull into blocks. A plane normal to x (within 1e-6) is a cut station;
// any other plane splits every row where it crosses it (a lateral border).
struct BlockPlane {
  Vec3d point;
  Vec3d normal;
  std::string name;
};

// Panel sizes wanted inside a box (the paper's "values in these three directions"); the first
// box that holds a row point wins, and the global size applies elsewhere.
struct SizeBox {
  Vec3d lo, hi;  // m
  Vec3d size;    // m along x, y, z; each > 0
  std::string name;
};

struct StructuredOptions {
  // Panel edge lengths along x, y and z (m). Zero: all three from target_panels.
  Vec3d size{0, 0, 0};
  std::size_t target_panels = 2000;  // used when size is zero
  std::vector<BlockPlane> planes;    // user block planes
  std::vector<SizeBox> size_boxes;   // user block sizes
  // Automatic blocks: cut stations where a knuckle or a boundary run starts or ends, at the ends
  // of the parallel middle body, and around regions where the sections change fast.
  bool auto_blocks = true;
  // A quad whose shorter opposite side is below this fraction of the longer one, or whose warp
  // exceeds max_warp (corner distance from the mean plane over the mean diagonal), becomes two
  // triangles (split along its shorter diagonal).
  double min_opposite_ratio = 0.35;
  double max_warp = 0.08;
  int relax_passes = 8;  // constrained smoothing passes (0: none)
  // The paper's three border-panel repairs, chosen per run of distorted border panels by quality,
  // and the collapse of wedge quads into triangles (both only where they mend rule failures).
  bool repair_border_panels = true;
  // Pairs of triangles side by side that make a good quad become it (pair_triangles).
  bool pair_triangles = true;
  // With the sizes from target_panels: mesh again, the sizes scaled by sqrt(count / target),
  // until the count is within kMatchTolerance of the target (at most kMatchPasses in all). The
  // rows add panels where they turn, so one pass overshoots by 0-40%.
  bool match_panels = false;
  // The waterplane's unit normal in the meshing frame, up out of the water: z, but for a heeled
  // hull's side, meshed in the ship's own frame (mesh_sides), where the waterplane leans.
  Vec3d waterplane_normal{0, 0, 1};
  // Stations given instead of planned (ascending x, m; station_border 1 at a cut station): the
  // two sides of a heeled hull are meshed apart on the whole hull's plan, so that their nodes on
  // the centre plane mostly coincide. Stations within a fifth of a panel of this surface's ends,
  // or beyond them, are dropped; the first and last kept are its end stations.
  std::vector<double> station_x;
  std::vector<std::uint8_t> station_border;
};

// What one block became.
struct BlockReport {
  Index id = 0;
  double x0 = 0, x1 = 0;     // station range, m
  std::string lower, upper;  // what bounds it across the rows (keel, knuckle 2, plane "WL1", ...)
  std::size_t rows = 0, quads = 0, triangles = 0;
  double seconds = 0;  // growing its rows and zipping its strips (a strip's time shared by face)
};

struct StructuredReport {
  Vec3d size;  // the panel sizes used, m
  std::size_t stations = 0, cut_stations = 0;
  std::size_t quads = 0, triangles = 0, cap_triangles = 0, cap_quads = 0;
  std::size_t transoms = 0;        // ends capped through a transom's knuckle
  std::size_t rows_joined = 0;     // strips between rows of different curve counts, joined
  std::size_t curve_caps = 0;      // of them, pieces of hull capped inside their strip
  std::size_t border_gaps = 0;     // slivers between row ends and the boundary, filled by fans
  std::size_t split_twisted = 0;   // quads made into two triangles
  std::size_t rows_unmatched = 0;  // strips whose rows could not be paired (left open)
  std::size_t quality_moves = 0;   // node moves kept by the quality-driven relocation
  std::size_t edge_snaps = 0;      // border and knuckle nodes moved onto a patch edge curve
  // Distorted border panels, and how many each repair took (the rest were best left).
  std::size_t border_distorted = 0, border_removed = 0, border_extended = 0, border_split = 0;
  std::size_t nodes_welded = 0;      // nodes on one spot made one (weld_coincident_nodes)
  std::size_t wedges_collapsed = 0;  // wedge quads made triangles by merging a short side's ends
  std::size_t non_convex_split = 0;  // quads left non-convex, split along the reflex diagonal
  std::size_t folds_flipped = 0;     // pairs of triangles folded onto each other, flipped
  std::size_t triangles_paired = 0;  // pairs of triangles side by side made one quad
  std::size_t size_passes = 1;       // meshing passes (more than one with match_panels)
  std::size_t first_pass_faces = 0;  // the first pass's panel count
  std::vector<BlockReport> blocks;
  double seconds_plan = 0, seconds_rows = 0, seconds_grow = 0, seconds_relax = 0;
};

struct StructuredMesh {
  SurfaceMesh mesh;  // quads and triangles; face_patch and face_block filled
  std::vector<std::array<Index, 2>> knuckle_edges;  // panel edges on knuckle lines
  StructuredReport report;
};

// plan -> rows -> grow blocks (in parallel) -> zip -> caps -> relax -> repair border panels ->
// onto the edge curves -> wedges into triangles -> orient. surface: the merged hull (triangles,
// vertex_patch and vertex_uv filled), adjacency and features of it; query: built on the same
// surface. Deterministic and thread-count independent. Throws UsageError for impossible options and
// GeometryError when the hull has no rows to grow.
StructuredMesh mesh_structured(std::span<const Patch> patches, const SurfaceMesh& surface,
                               const EdgeAdjacency& adjacency, const HullQuery& query,
                               const FeatureSet& features, const StructuredOptions& options);

// --match-panels for a mesher of the sizes: mesh_at(size), then again with the sizes scaled by
// sqrt(count / target) until the count is within 3% of options.target_panels (three passes at
// most), when options.match_panels is set and options.size is not. The report counts the passes
// and the first pass's panels; its stage times are of every pass.
StructuredMesh mesh_to_count(const std::function<StructuredMesh(const Vec3d&)>& mesh_at, Vec3d size,
                             const StructuredOptions& options);

// The panel sizes mesh_structured starts from (m along x, y, z): options.size, or one size from
// options.target_panels and the surface's area. Throws as mesh_structured does.
Vec3d structured_sizes(const SurfaceMesh& surface, const StructuredOptions& options);

// The stations mesh_structured would plan for this surface (x ascending, m) and which are border
// stations (cuts and ends), for StructuredOptions::station_x and station_border.
struct StationList {
  std::vector<double> x;
  std::vector<std::uint8_t> border;
};
StationList plan_structured_stations(const SurfaceMesh& surface, const HullQuery& query,
                                     const FeatureSet& features, const StructuredOptions& options);

// Counts of join_sides.
struct SideJoin {
  std::size_t seam_nodes = 0;    // nodes on the centre plane's seam, both sides, before the join
  std::size_t welded = 0;        // pairs of nodes, one of each side, made one
  std::size_t inserted = 0;      // nodes of one side put into a seam edge of the other
  std::size_t back_to_back = 0;  // pairs of panels on the same corners, dropped
  std::size_t holes_filled = 0;  // small holes left in the plane between the sides, filled
};

// Where join_sides looks for the seam: the centre plane y = 0, within centre_tol (m), and the
// waterplane dot(up, p) = waterline, within waterline_tol (m; NaN waterline: none).
struct SeamPlanes {
  double centre_tol = 0;
  Vec3d up{0, 0, 1};
  double waterline = std::numeric_limits<double>::quiet_NaN();
  double waterline_tol = 0;
};

// The two sides of a hull meshed apart, in a frame whose centre plane is y = 0 (a heeled hull's
// port and starboard sides, meshed in the ship's own frame), made one mesh: where both sides'
// open borders run along the plane (edges on the waterline too excepted) a node of one side within
// a quarter of the shorter seam edge beside it of a node of the other is welded to it (the port
// node stays), and any other node goes into the edge of the other side it lies on, whose panel is
// split (a quad into a quad and triangles where its other sides allow, else into triangles by their
// smallest angle). Faces keep their patch; starboard's blocks follow port's, with their names
// and counts. Knuckle edges follow their nodes.
StructuredMesh join_sides(StructuredMesh port, StructuredMesh starboard, const SeamPlanes& planes,
                          SideJoin* counts = nullptr);

}  // namespace hm
