// The steps of mesh_structured and the data they pass along. Private to src/structured.
//
// A row is the hull cut by one station plane x = const: one or more curves, each an ordered
// polyline on the NURBS running up from its lower end (keel or centre plane) to its upper end
// (waterline or deck). Breakpoints split a curve where a knuckle line or a lateral block plane
// crosses it; they and the curve's ends become nodes of every row, so blocks meet node to node.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "query/hull_query.h"
#include "structured/structured.h"

namespace hm::structured {

// How fast a size box's panel size blends into the global size outside the box (m of size per m
// of distance from the box).
inline constexpr double kBoxGrading = 0.2;

// Lengths measured in panel sizes: |d|_M = |(dx / size.x, dy / size.y, dz / size.z)|.
struct Metric {
  Vec3d size{1, 1, 1};
  std::vector<SizeBox> boxes;
  // The sizes that apply at p: the first box holding p; else, within a box's transition zone,
  // its size blended towards the global one (kBoxGrading); else the global size.
  Vec3d size_at(const Vec3d& p) const;
  double length(const Vec3d& a, const Vec3d& b) const;
};

// What a breakpoint is: a curve's lower or upper end, a knuckle (index into
// FeatureSet::knuckles) or a lateral block plane (index into StructuredOptions::planes).
enum class BreakKind : std::uint8_t { kLow, kKnuckle, kPlane, kHigh };
struct BreakLabel {
  BreakKind kind = BreakKind::kLow;
  Index id = 0;
  bool operator==(const BreakLabel&) const = default;
};
std::string to_string(const BreakLabel& b);

struct Breakpoint {
  double s = 0;     // metric arc length along the curve
  Index point = 0;  // the curve point it sits on
  BreakLabel label;
};

struct RowCurve {
  std::vector<Vec3d> points;  // on the NURBS and on the station plane
  std::vector<PatchId> patch;
  std::vector<Vec2d> uv;
  std::vector<double> s;           // metric arc length from points[0], ascending
  std::vector<Breakpoint> breaks;  // ascending in s; the two ends included
  double z_min = 0, z_max = 0;     // of its points, m
  double length() const { return s.empty() ? 0 : s.back(); }
  // Position, patch and (u, v) at arc length t (clamped), linear between points.
  Vec3d at(double t) const;
  void locate(double t, std::size_t& seg, double& frac) const;
  // Arc length of the first crossing of the plane (p, n) by the curve, searching from near t0;
  // NaN when the curve does not cross it.
  double crossing(const Vec3d& p, const Vec3d& n, double t0) const;
};

struct Row {
  double x = 0;
  bool border = false;  // a cut station or an end: meshed first, shared by two columns
  std::vector<RowCurve> curves;
};

// Nodes on a row: per curve, ascending arc lengths (both ends and every breakpoint included).
struct RowNodes {
  std::vector<std::vector<double>> s;
};

// --- plan ---------------------------------------------------------------------------------
struct StationPlan {
  std::vector<double> x;             // ascending
  std::vector<std::uint8_t> border;  // 1 at cut stations and at both ends
  std::size_t cuts = 0;
};
// Where a boundary turns back in x, so that on the `side` of x a station plane cuts the hull in
// two pieces, and on the other passes the boundary's corner within a hair:
// - an open transom's edge (DTMB 5415's runs forward from the keel to the bilge, then aft to the
//   deck): the interior vertex of a transom-edge run with its least (side +1) or greatest (side
//   -1) x;
// - the centre-plane profile of a half hull (a stem's notch above a bulb or a sonar dome: side
//   -1): a vertex of a centre-plane run, not at the run's least or greatest x, where x runs
//   towards `side` along both branches.
// Both branches must run at least a fifth of the panel length hx away in x. `clear` is the share
// of their spacing that stations keep from the turn (keep_clear_of_turns).
struct BoundaryTurn {
  double x = 0;
  int side = 1;
  double clear = 0.4;
};
std::vector<BoundaryTurn> transom_turns(const SurfaceMesh& surface, const FeatureSet& features,
                                        double hx);
std::vector<BoundaryTurn> centre_plane_turns(const SurfaceMesh& surface, const FeatureSet& features,
                                             double hx);
// The centre-plane turns of one profile polyline (points in order; closed: the last joins the
// first), each branch reaching at least `need` (m of x).
std::vector<BoundaryTurn> profile_turns(std::span<const Vec3d> points, bool closed, double need);
// Moves each station that is no border off the turns, to `clear` of its spacing from each: a
// station just on the split side cuts the hull with a sliver of a gap, whose ends' panels are a
// fraction of the others' area (DTMB 5415, --panels 2000 --match-panels: a station 0.2 mm aft of
// the transom's turn, a 1 mm gap, 23 panels over the area rule round it); one just on the other
// side passes the boundary's corner within a hair. A station moves by under its spacing, so the
// order stays.
void keep_clear_of_turns(std::span<const BoundaryTurn> turns, StationPlan& plan);

// Stations from the aft end to the forward end: spaced so that a node walking the panel size
// along the hull, normal to its row, reaches the next station; cut stations included. They keep
// clear of the boundary's turns (keep_clear_of_turns).
StationPlan plan_stations(const HullQuery& query, const FeatureSet& features,
                          const SurfaceMesh& surface, const Metric& metric,
                          const StructuredOptions& options);

// --- rows ---------------------------------------------------------------------------------
// The hull's sections at the planned stations, refined on the NURBS, split at knuckles and
// lateral planes. Parallel over stations.
std::vector<Row> extract_rows(const HullQuery& query, const SurfaceMesh& surface,
                              const EdgeAdjacency& adj, const FeatureSet& features,
                              std::span<const BlockPlane> planes, const StationPlan& plan,
                              const Metric& metric);

// --- grow ---------------------------------------------------------------------------------
// Places the nodes of every row. Border rows get evenly spaced nodes between their breakpoints;
// each row after a border row is grown from the one before: its nodes walk along the hull in
// the plane normal to their row until they meet the next station, then nodes are merged or
// added where the row is shorter or longer than the count it needs, and blended towards even
// spacing. Columns (runs between border rows) grow in parallel.
// row_seconds, when given, gets the time each row took to place (for the per-block times).
std::vector<RowNodes> grow_rows(std::span<const Row> rows,
                                std::vector<double>* row_seconds = nullptr);

// --- zip ----------------------------------------------------------------------------------
// One strip of panels between two node chains a and b (global vertex ids, with arc-length
// fractions in [0, 1] along each), a running along the aft row and b along the forward one.
// Faces are (a_i, a_i+1, b_k+1, b_k) quads, or triangles where one side advances alone.
struct ZipOptions {
  double min_opposite_ratio = 0.35;
  double max_warp = 0.08;
};
struct ZipCounts {
  std::size_t quads = 0, triangles = 0, split = 0;
};
ZipCounts zip_chains(std::span<const Index> a, std::span<const double> fa, std::span<const Index> b,
                     std::span<const double> fb, std::span<const Vec3d> positions,
                     const ZipOptions& options, std::vector<Face>& faces);
// The zip's quad tests on corners a, b, c, d in order: the corner distance from the best plane
// over the mean diagonal (the warp the quality report uses), and the smaller of the two ratios
// of opposite sides (shorter over longer).
double quad_warp(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);
double opposite_ratio(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);
// A triangle's smallest corner angle, radians (0 when degenerate).
double min_angle(const Vec3d& a, const Vec3d& b, const Vec3d& c);

// --- nodes -------------------------------------------------------------------------------
// Where each vertex came from: its row, curve and arc length (row kInvalid for boundary nodes
// the caps, joins and gap fans add).
struct NodeSlot {
  Index row = kInvalid, curve = 0;
  double s = 0;
  bool fixed = true;      // relocation leaves it (border rows, breakpoints, cap nodes)
  bool on_break = false;  // a curve end, knuckle or plane crossing: exact as it stands
  bool bridge = false;    // on the boundary between two rows' starts (bridge_starts)
};
struct NodeLayout {
  std::vector<NodeSlot> slots;                   // one per vertex
  std::vector<std::vector<Index>> first_vertex;  // [row][curve]: its first node's vertex
};
// Appends every row node to mesh (position on its curve, patch and (u, v)), row by row, curve by
// curve, node by node.
NodeLayout place_nodes(std::span<const Row> rows, std::span<const RowNodes> nodes,
                       SurfaceMesh& mesh);
// Row nodes back onto the exact NURBS, still on their station plane (breakpoints and boundary
// nodes stay). tol: the Newton residual accepted, m.
void refine_nodes(std::span<const Patch> patches, std::span<const Row> rows,
                  std::span<const NodeSlot> slots, double tol, const Metric& metric,
                  SurfaceMesh& mesh);

// The paper's three repairs of distorted border panels (quads on a block border that break the
// side-ratio or area-ratio rule), for each run of them side by side along a border, whichever
// leaves the fewest panels failing: remove them and extend their inner neighbours (the inner
// sides' free nodes merge into the border's), extend them and shrink the neighbours (those nodes
// move towards the neighbours' far side, onto the NURBS), or split them into triangles. Serial
// in face order. Removed faces are dropped; merged nodes stay in the arrays, used by no face.
struct BorderRepairCounts {
  std::size_t distorted = 0, removed = 0, extended = 0, split = 0;
};
BorderRepairCounts repair_border_panels(const HullQuery& query, std::span<const NodeSlot> slots,
                                        std::span<const std::array<Index, 2>> knuckle_edges,
                                        SurfaceMesh& mesh);

// The paper's quad-to-triangle rule where nodes have converged: a quad breaking the side rule
// whose shortest side is under min_opposite_ratio of its opposite side (a wedge) becomes a
// triangle by merging one end of that side into the other (a free node, or a row's end node on a
// straight stretch of the boundary), kept when it leaves fewer panels failing nearby or as many
// and a milder worst. Nothing moves. Serial in face order. Removed faces are dropped; merged
// nodes stay in the arrays, used by no face. Returns the number of wedges collapsed.
std::size_t collapse_wedges(std::span<const NodeSlot> slots,
                            std::span<const std::array<Index, 2>> knuckle_edges,
                            double min_opposite_ratio, SurfaceMesh& mesh);

// Nodes on one spot (a panel side no longer than 1e-8 of the panel's longest side) become one,
// the later merging into the earlier, where the panels around stay manifold; knuckle edges follow
// and a panel that loses a corner becomes a triangle or goes. Nothing moves. Serial in face
// order. Returns the nodes merged.
std::size_t weld_coincident_nodes(std::vector<std::array<Index, 2>>& knuckle_edges,
                                  SurfaceMesh& mesh);

// Quads left with a reflex or flat corner become two triangles along the diagonal through it
// (the split whose triangles both keep the quad's orientation). Nothing moves. Serial in face
// order: the first triangle takes the quad's place, the second goes to the end with its block.
// Returns the quads split.
std::size_t split_non_convex(SurfaceMesh& mesh);

// Pairs of triangles whose normals turn by more than 120 degrees across their shared edge (off a
// knuckle) are flipped to the pair's other diagonal, when the new triangles face the same way and
// the new edge is not there already. Nothing moves. Serial in edge order. Returns the pairs
// flipped.
std::size_t unfold_triangles(std::span<const std::array<Index, 2>> knuckle_edges,
                             SurfaceMesh& mesh);

// Two triangles side by side that make a good quad become that quad (Gmsh's recombination, on
// what the zips, caps and repairs left): same block, their shared side off every knuckle, the
// quad convex with a margin and passing the zip's tests (options) and the side rule, no more
// panels failing a rule nearby, and no more panels crossing nearby on either of the quad's
// splits. Best quads first (by side ratio, then face order); nothing moves. Serial, so
// deterministic. The quad takes the first triangle's place; the second is dropped. Returns the
// pairs made quads.
std::size_t pair_triangles(std::span<const std::array<Index, 2>> knuckle_edges,
                           const ZipOptions& options, SurfaceMesh& mesh);

// Boundary compliance on the exact curves: every node on the panel mesh's open border or on a
// knuckle edge that lies on a fine boundary or knuckle segment running along an edge of a
// patch's parameter domain moves onto that NURBS edge curve (a row node where the curve crosses
// its station plane, a waterline node where it crosses the waterplane, any other node at the
// nearest point). up: the waterplane's unit normal. Returns the number of nodes moved. Parallel
// over nodes; deterministic.
std::size_t snap_to_edge_curves(std::span<const Patch> patches, const SurfaceMesh& surface,
                                const FeatureSet& features, std::span<const Row> rows,
                                std::span<const NodeSlot> slots,
                                std::span<const std::array<Index, 2>> knuckle_edges,
                                double length_scale, const Vec3d& up, const Metric& metric,
                                SurfaceMesh& mesh);

// Vertices no face or knuckle edge uses leave the arrays; faces and knuckle edges are renumbered
// (vert_old2new), in order.
void drop_unused_vertices(StructuredMesh& out);

// --- strips ------------------------------------------------------------------------------
struct StripFaces {
  std::vector<Face> faces;
  std::vector<std::uint32_t> block_key;  // (column << 16) | (curve << 8) | segment
  std::vector<std::array<Index, 2>> knuckle_edges;
  std::map<std::uint32_t, std::array<std::string, 2>> block_names;
  ZipCounts counts;
  bool unmatched = false;  // the rows' curve counts differ (left to join_rows)
  double seconds = 0;      // growing its forward row and zipping it
};
// A chain laid ahead of one row's first curve node in a strip (bridge_starts.h).
struct StartBridge {
  std::size_t curve = 0;
  bool forward = false;      // it leads row j + 1's curve (else row j's)
  std::vector<Index> nodes;  // the other row's first node, then new boundary nodes
  std::vector<double> at;    // metric arc length of each node from the first
  double length = 0;         // metric arc length from the first node to the led curve's start
};
// Strip j joins rows j and j + 1, zipped segment by segment between the labels both carry.
// bridges[j]: the chains laid ahead of strip j's curves (empty: none).
std::vector<StripFaces> zip_strips(std::span<const Row> rows, std::span<const RowNodes> nodes,
                                   std::span<const std::vector<Index>> first_vertex,
                                   std::span<const std::vector<StartBridge>> bridges,
                                   std::span<const Vec3d> positions, const ZipOptions& zo,
                                   std::span<const double> row_seconds);
// Appends the strips' faces in row order, numbers the blocks (a column's share between two labels
// every row of it carries) and fills their reports.
void commit_strips(std::span<const Row> rows, std::span<const StripFaces> strips,
                   StructuredMesh& out);

// --- relax --------------------------------------------------------------------------------
// The relocation's and the border repairs' yardsticks for the panel rules (quad side ratio 4,
// neighbour area ratio 2): a little inside the limits, so that a panel sitting exactly on one
// (a count-change triangle has half its neighbour quad's area) is pushed in.
inline constexpr double kSideTarget = 3.8, kAreaTarget = 1.9;
// A face is flat when its area is under kFlatArea of its longest side squared (a corner of about
// 1e-4 degree): three corners on one line, as a merge or a split along a straight boundary can
// leave them.
inline constexpr double kFlatArea = 1e-6;
bool flat_face(std::span<const Vec3d> positions, const Face& f);
// Longest over shortest side of face f; infinite for a side of zero length.
double side_ratio(std::span<const Vec3d> positions, const Face& f);

// Point relocation: every free node (not a breakpoint, not on a border row) moves along its row
// curve towards the mean of its mesh neighbours. rows/nodes give each vertex's curve.
void relax_nodes(std::span<const Row> rows, std::span<NodeSlot> slots, std::span<const Face> faces,
                 std::vector<Vec3d>& positions, int passes);

// Relocation with quality as the objective (improve_nodes.cpp): each free node in turn tries a
// few moves along its row and keeps the one that leaves the fewest rule values over their
// targets around it (quad side ratio, neighbour area ratio), then the mildest worst one, and
// makes no more panels cross around it. Then the corners of panels left crossing each other try
// wider moves that part them. Gauss-Seidel in vertex order, so deterministic. Returns the number
// of moves kept.
std::size_t improve_nodes(std::span<const Row> rows, std::span<NodeSlot> slots,
                          std::span<const Face> faces, std::vector<Vec3d>& positions, int passes);

}  // namespace hm::structured
