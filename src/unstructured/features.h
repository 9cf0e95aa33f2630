// Features of a merged hull surface that every mesher must keep: knuckle lines (sharp edges where
// the surface normal jumps), classified boundary runs, and the corners where they meet.
//
// Frame: the ship frame of the generator (x forward, y to port, z up) is assumed for boundary
// kinds; lengths in metres. Input is a merged, edge-manifold triangle mesh with shared vertices
// (face_patch, vertex_patch and vertex_uv filled), consistently oriented.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"

namespace hm {

// Where a user adds or suppresses knuckles. An edge matches a hint when its midpoint lies within
// `distance` of the plane (kPlane), when its two faces come from the two patches (kPatchPair), or
// when both its vertices lie within `distance` of the polyline through `points` (kPoints).
struct KnuckleHint {
  enum class Kind : std::uint8_t { kPlane, kPatchPair, kPoints };
  Kind kind = Kind::kPlane;
  Vec3d plane_point, plane_normal;                 // kPlane
  PatchId patch_a = kInvalid, patch_b = kInvalid;  // kPatchPair (order does not matter)
  std::vector<Vec3d> points;                       // kPoints
  double distance = 0;                             // m; <= 0: 1e-3 L
};

// Knuckle rules (find_knuckles.h has the details): an interior edge is a candidate when the angle
// between its two face normals exceeds knuckle_angle_deg; with confirm_on_nurbs it stays only
// when the exact NURBS normals, taken on either side next to the edge (one-sided at knots of
// full multiplicity), differ by at least half that angle, and a confirmed line is followed on
// past its end while the NURBS jump stays above a quarter of it (a chine fading into the stem).
// Then `add` hints force edges in and `suppress` hints take them out.
struct FeatureOptions {
  double knuckle_angle_deg = 25;      // dihedral angle between face normals that marks a candidate
  bool confirm_on_nurbs = true;       // keep a candidate only if the NURBS normals jump there too
  std::vector<KnuckleHint> add;       // edges forced to be knuckles (no NURBS check)
  std::vector<KnuckleHint> suppress;  // edges never knuckles (wins over add)
  // The waterline cut: the plane dot(waterplane_normal, p) = waterline_z (boundary edges on it
  // are kWaterline); NaN: none. The normal is a unit vector, up out of the water: z but for a
  // heeled hull's side, meshed in the ship's own frame, where the waterplane leans.
  double waterline_z = std::numeric_limits<double>::quiet_NaN();
  Vec3d waterplane_normal{0, 0, 1};
  // The surface goes on above the waterline (it was split at waterline_z, not cut): its interior
  // edges on the plane are knuckles whatever the angle or the hints say, so that every mesher
  // ends its panels on the waterline.
  bool waterline_inside = false;
};

// The waterline's and the centre plane's tolerance, as a share of L (the largest bounding-box
// extent): a boundary edge within it is on the plane, and the CLI puts mesh nodes within it of
// y = 0 onto the centre plane.
inline constexpr double kPlaneTolerance = 2e-4;

// Rules per boundary edge, first match wins (tolerances relative to L, the largest bounding-box
// extent; either x end may be the bow, a half hull may lie on either side of y = 0):
//   kWaterline   both ends within 2e-4 L of waterline_z;
//   kCentrePlane both ends within 2e-4 L of y = 0;
//   kTransomEdge in a run of edges within 30 degrees of the y-z plane whose faces do not face
//                along x (|n_x| < 0.7), lying within 0.25 L of an x end and spanning >= 0.01 L;
//   kDeckEdge    its face lies below it and the edge is at the top of the surface in its x slab
//                (within 5% of the z extent);
//   kHole        anything else.
enum class BoundaryKind : std::uint8_t {
  kDeckEdge,     // top edge of the hull surface
  kTransomEdge,  // edge of an open transom (aft, in a plane of nearly constant x)
  kCentrePlane,  // on y = 0 (the open side of a half hull)
  kWaterline,    // on the waterline cut (FeatureOptions::waterline_z)
  kHole,         // anything else: a genuine hole, reported
};
const char* to_string(BoundaryKind k);

// A chain of mesh vertices along feature edges. closed: last joins first (not repeated).
struct FeatureLine {
  std::vector<Index> vertices;
  bool closed = false;
  double length = 0;  // m, along the mesh edges
};

struct BoundaryRun : FeatureLine {
  BoundaryKind kind = BoundaryKind::kHole;
};

enum class VertexFeature : std::uint8_t { kSmooth = 0, kOnLine = 1, kCorner = 2 };

struct FeatureSet {
  // Per undirected edge of the adjacency passed in (same numbering): 1 if a knuckle edge.
  std::vector<std::uint8_t> edge_knuckle;
  std::vector<FeatureLine> knuckles;    // ordered by their first vertex
  std::vector<BoundaryRun> boundaries;  // maximal runs of one kind along each boundary loop
  // Per vertex: smooth, on one feature line (knuckle or boundary) through it, or a corner
  // (a line end, a junction of three or more feature edges, a change of boundary kind, or a sharp
  // turn of a feature line).
  std::vector<VertexFeature> vertex_feature;
  std::vector<Index> corners;                    // ascending
  std::size_t candidates_rejected_by_nurbs = 0;  // candidates the NURBS check turned down
  double knuckle_length() const;
};

// Deterministic and thread-count independent. Throws GeometryError when the mesh is not
// edge-manifold or its arrays disagree.
FeatureSet find_features(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                         std::span<const Patch> patches, const FeatureOptions& options);

}  // namespace hm
