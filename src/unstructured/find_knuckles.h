// Knuckle edges of a merged hull surface: score every interior edge by its dihedral angle,
// confirm the candidates on the exact NURBS, then apply the user's hints. Private to
// src/unstructured (find_features is the public entry).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"
#include "unstructured/features.h"

namespace hm::detail {

// The two faces of an interior edge (uses == 2) and whether the second is flipped against the
// first (so its normal must be negated before comparing).
struct EdgeFaces {
  Index f0 = kInvalid, f1 = kInvalid;
  bool flipped = false;
};
EdgeFaces edge_faces(const EdgeAdjacency& adjacency, Index e);

// Angle in degrees between the two face normals of an interior edge (0: flat).
double dihedral_angle_deg(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency, Index e);

// Parameters of a patch between which its surface is smooth (C1 or better): the domain ends
// and the knots of multiplicity >= degree, ascending, per direction.
struct SmoothPieces {
  std::vector<double> u, v;
};
std::vector<SmoothPieces> smooth_pieces(std::span<const Patch> patches);

// Angle in degrees between the exact surface normals on either side of interior edge e, each
// taken on its face's patch next to the edge midpoint, on the smooth piece holding the face's
// centroid (one-sided, so a knot of full multiplicity inside a patch shows its jump), and signed
// like its face normal (patches may be reversed). Negative when no normal can be had.
double nurbs_normal_jump_deg(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                             std::span<const Patch> patches, std::span<const SmoothPieces> pieces,
                             Index e);

struct KnuckleEdges {
  std::vector<std::uint8_t> edge_knuckle;  // per undirected edge: 1 if a knuckle
  std::size_t candidates = 0;              // interior edges over the dihedral threshold
  std::size_t rejected_by_nurbs = 0;       // candidates the NURBS check turned down
};

// Knuckle edges, in order:
//   1. candidates: interior edges whose dihedral angle exceeds options.knuckle_angle_deg;
//   2. with options.confirm_on_nurbs, a candidate stays when its NURBS normals jump by at least
//      half that angle (or when no normal can be had there);
//   3. with options.confirm_on_nurbs, each line end is followed on along the interior edge that
//      continues it best (turn < 30 degrees) while that edge's NURBS jump is at least a quarter
//      of the angle, whatever its dihedral (a chine fading out towards the stem);
//   4. edges matching an `add` hint are knuckles, edges matching a `suppress` hint are not
//      (suppress wins, also over step 3). Only interior edges can be knuckles.
// `length` is L (largest bounding-box extent, m). Parallel over edges, deterministic.
KnuckleEdges find_knuckles(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                           std::span<const Patch> patches, const FeatureOptions& options,
                           double length);

}  // namespace hm::detail
