// Knuckle edges of a merged hull surface: score every interior edge by its dihedral angle,
// confirm the candidates on the exact NURBS, then apply the user's hints. Private to
// src/unstructured (find_features is the public entry).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
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

// How each patch's NURBS normal (su x sv) faces against the mesh's faces of that patch: +1 the
// same way, -1 reversed, 0 unknown (no face probed has a corner of the patch lying where its
// (u, v) puts it). Found on first use (thread-safe) from a few faces spread over the patch, by
// majority, so that one folded face does not decide.
class PatchFacing {
 public:
  PatchFacing(const SurfaceMesh& mesh, std::span<const Patch> patches);
  double of(PatchId p) const;

 private:
  static constexpr int kVotes = 5;    // votes that decide
  static constexpr int kProbes = 64;  // faces of a patch looked at, at most
  const SurfaceMesh& mesh_;
  std::span<const Patch> patches_;
  std::vector<Index> face_start_, faces_;  // each patch's faces, ascending
  std::unique_ptr<std::once_flag[]> once_;
  mutable std::vector<double> facing_;
};

// Angle in degrees between the exact surface normals on either side of interior edge e, each
// taken on its face's patch next to the edge midpoint, on the smooth piece holding the face's
// centroid (one-sided, so a knot of full multiplicity inside a patch shows its jump). Each is
// signed by how its patch faces the mesh (patches may be reversed), not by its own face (a
// sliver standing on its edge at a seam has a normal square to the surface, a folded face one
// backwards); like its face where that is unknown, or where the two faces are wound against
// each other. Negative when no normal can be had.
double nurbs_normal_jump_deg(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                             std::span<const Patch> patches, std::span<const SmoothPieces> pieces,
                             const PatchFacing& facing, Index e);

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
