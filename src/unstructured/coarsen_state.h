// Internal to coarsen: the mutable mesh the collapses work on, and the steps that read and change
// it. Vertices keep their fine index for life (dead ones are flagged), so a vertex id is stable
// across rounds; faces likewise. Positions in metres, model frame.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "kernels/collapse_cost.h"
#include "unstructured/coarsen.h"

namespace hm::coarsen_detail {

// The panel edge wanted at a point: h(x) = h0 * c(x) * s(x), where
//   c(x) = (1 + k(x) R)^(-w3 / 2)   curvature factor; k the larger principal curvature of the
//                                   NURBS (1/m), at most kappa_max, R the curvature length:
//                                   area ~ 1 / k for k R >> 1
//   s(x) = prod_i (size_i / h0)^min(1, w4 phi_i(x))   source factor, where phi_i is 1 within
//          half the radius of source i, then 1 - smoothstep(2 d / radius - 1) down to 0 at the
//          radius; d is the distance to the source (0 inside a box)
// w3 = 0 switches curvature off; w4 = 0 switches the sources off.
struct SizeField {
  double h0 = 0;                // m
  double curvature_length = 0;  // m
  // Curvature beyond this counts as this (1/m): a bend of a smaller radius than the panels can
  // follow (coarsen sets it to 1 / (kTightestRadius h0)).
  double kappa_max = std::numeric_limits<double>::infinity();
  double w_curvature = 1, w_sources = 1;
  std::vector<SizeSource> sources;

  double curvature_factor(double kappa) const;
  double source_factor(const Vec3d& x) const;
};

// Per fine vertex, the larger absolute principal curvature of its patch at its (u, v), 1/m.
std::vector<double> vertex_curvatures(std::span<const Patch> patches, const SurfaceMesh& fine);

struct State;
// Limits how fast a per-vertex size grows along the mesh's edges: afterwards
// h[u] <= h[v] + slope |uv| for every edge.
void grade_sizes(const State& s, double slope, std::vector<double>& h);

// h0 such that equilateral panels of the field's sizes would number about `panels` over the
// fine mesh's area; cfactor is the curvature factor per fine vertex.
double calibrate_panel_size(const SurfaceMesh& fine, std::span<const double> cfactor,
                            SizeField field, std::size_t panels);

enum class Kind : std::uint8_t { kSmooth = 0, kOnLine = 1, kCorner = 2 };

// A panel may not stand more than 60 degrees off the hull's normal at a smooth corner (collapses
// and smoothing moves alike): cos 60.
inline constexpr double kRestNormalCos = 0.5;

inline bool has_corner(const std::array<Index, 3>& t, Index v) {
  return t[0] == v || t[1] == v || t[2] == v;
}

// Where a vertex sits on a fine feature line (for moving it along the line).
struct LineSpot {
  Index line = kInvalid;  // into State::lines
  Index k = kInvalid;     // index into that line's vertices
};

struct FineLine {
  std::vector<Index> vertices;
  std::vector<double> arclength;  // cumulative, from vertices[0]
  bool closed = false;
};

struct State {
  // Read-only inputs.
  std::span<const Patch> patches;
  std::vector<double> patch_net;  // per patch, net_size of its surface (m), for projections
  std::span<const Vec3d> fine_positions;
  std::span<const PatchId> fine_vertex_patch;
  std::span<const Vec2d> fine_uv;
  SizeField field;
  kernel::CollapseWeights weights;
  double bound = 0;  // m: witnesses must stay this close to their panel
  // m: a panel's centroid and edge midpoints must stay this close to the fine mesh (checked
  // where a panel's witnesses come near `bound`; see reassign_witnesses).
  double sample_bound = 0;
  // The fine triangles and, per fine vertex, the fine triangles around it (CSR:
  // fine_vf[fine_vf_begin[v] .. fine_vf_begin[v + 1]]), for the samples' distances.
  std::span<const Face> fine_faces;
  std::vector<Index> fine_vf_begin, fine_vf;
  double cos_normal_change = 0;
  std::vector<double> cfactor;  // per vertex, field.curvature_factor(curvature)
  // Per vertex: the size gate's edge h0 c s, graded so that it grows by at most kGrading per
  // metre (neighbouring panels then differ little in area even where the field jumps), m.
  std::vector<double> gate_h;
  std::vector<Vec3d> rest_normal;  // per vertex: mean normal of its fine faces (unit)

  // The mesh. Per vertex (fine numbering).
  std::vector<Vec3d> position;
  std::vector<Vec2d> uv;
  std::vector<PatchId> vpatch;
  std::vector<Index> source;  // the fine vertex whose place this vertex now holds
  std::vector<std::uint8_t> alive;
  std::vector<std::vector<Index>> vertex_faces;  // live faces around each vertex
  // Per face.
  std::vector<std::array<Index, 3>> faces;
  std::vector<PatchId> face_patch;
  std::vector<std::uint8_t> face_alive;
  std::size_t live_faces = 0;

  // Features: kind per vertex; for on-line vertices the neighbours along the line (prev, next in
  // the fine line's order); feature edges joining two corners (sorted pairs).
  std::vector<Kind> kind;
  std::vector<std::array<Index, 2>> line_nbr;
  std::vector<std::array<Index, 2>> corner_edges;
  std::vector<FineLine> lines;
  std::vector<LineSpot> spot;  // per vertex

  // Deviation witnesses: fine vertices that collapses removed, each held by the panel it is
  // nearest to; singly linked lists threaded through witness_next.
  std::vector<Index> face_witness;       // head per face, kInvalid when none
  std::vector<Index> witness_next;       // per fine vertex
  std::vector<std::uint8_t> is_witness;  // per fine vertex: in some face's list
  double max_witness_distance = 0;       // m, largest accepted
};

// Builds the state from the fine mesh and its features. Throws GeometryError on a non-manifold
// or inconsistent input.
void build_state(std::span<const Patch> patches, const SurfaceMesh& fine,
                 const EdgeAdjacency& adjacency, const FeatureSet& features, State& s);

bool is_feature_edge(const State& s, Index a, Index b);

// The best collapse of vertex v into one of its neighbours, by the index q. target is kInvalid
// when no collapse of v is valid.
struct Candidate {
  Index target = kInvalid;
  double q = 0;  // the weighted index
  double r = 0;  // largest panel edge over the field's edge among the panels it makes
  std::uint8_t faces_removed = 0;
};
Candidate score_vertex(const State& s, Index v);
// The same checks and index for one given target (kInvalid target when invalid).
Candidate score_collapse(const State& s, Index v, Index t);

// Outcome of trying one collapse.
enum class Applied : std::uint8_t { kDone, kRejectedShape, kRejectedDeviation };
// Re-checks v -> t against the current mesh and the deviation bound, then collapses. Reads and
// writes only v, t, the vertices around them and their faces: collapses whose regions
// (collapse_region) are disjoint may run concurrently. Returns the largest witness distance in
// `deviation`; when the collapse joins two corners by a feature edge, that edge (sorted) in
// `joined_corners` for the caller to add to corner_edges.
Applied apply_collapse(State& s, Index v, Index t, double& deviation,
                       std::array<Index, 2>& joined_corners);
// The vertices a collapse v -> t reads or writes: v, t and both rings, as every corner of v's and
// t's faces (with repeats): region_size(s, v, t) entries, written to out.
Index region_size(const State& s, Index v, Index t);
void collapse_region(const State& s, Index v, Index t, std::span<Index> out);

// Witnesses of the given faces plus `extra` (a fine vertex no longer held by a mesh vertex, or
// kInvalid; ignored when it is a witness already), assigned to the
// nearest of `targets` (faces with final corners). False when one lies farther than the bound,
// or when a new panel (a target that is also in `from`) whose witnesses come near the bound has
// its centroid or an edge midpoint farther than sample_bound from the fine mesh; nothing is
// written then. On success the lists of `from` are emptied and `targets` receive
// them; the largest distance goes to `deviation`.
bool reassign_witnesses(State& s, std::span<const Index> from, Index extra,
                        std::span<const Index> targets, double& deviation);

// Two triangles (corner triples) lying back to back: facing opposite ways, with centres closer
// than the panel codes' close-centre share (kCloseCentreFraction, 0.05) of the
// square root of the smaller one's area. Such pairs form where the hull's two halves are
// tangent, as a full Wigley's are where its stem meets its keel: a panel whose corners all lie on
// the stem and the keel lies in the centre plane on both sides.
bool back_to_back(const State& s, const std::array<Index, 3>& a, const std::array<Index, 3>& b);
// True when triangle `corners` lies back to back with a live face across one of its edges, other
// than the faces in `skip`; the faces are found in the corners' current lists.
bool back_to_back_across(const State& s, const std::array<Index, 3>& corners,
                         std::span<const Index> skip);

// The index on v's fine line of w, v's line neighbour before (or after) it; kInvalid when w is
// not found on that line. v must be on a line.
Index line_index(const State& s, Index v, Index w, bool before);
// True when every fine line vertex strictly between indices ka and kb (going forward, around a
// closed line) lies within the bound of the segment [pa, pb]: the panels' edge along a knuckle
// or boundary stays on it, which the witnesses (nearest panel, either side) cannot tell.
bool line_chord_ok(const State& s, Index line, Index ka, Index kb, const Vec3d& pa,
                   const Vec3d& pb);

// Face index of one live face (for the stop rules and the report): the weighted index of its own
// shape, its area against its edge neighbours', and its size against the field.
double face_index(const State& s, Index f);

// Edge flips and tangential smoothing on the NURBS and along the feature lines, each move kept
// only when it improves the panels and respects the bounds.
struct ImproveCounts {
  std::size_t flips = 0, moves = 0;
};
ImproveCounts improve_panels(State& s, int passes);

}  // namespace hm::coarsen_detail
