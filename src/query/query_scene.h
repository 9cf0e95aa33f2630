// The state behind HullQuery: the triangles grouped by patch, their corner (u, v), the Embree
// scene and the plane BVH. Internal to src/query.
//
// Frames: `local` and the Embree buffers are in the local frame (model position minus centre),
// which keeps float coordinates small; every refined answer is in the model frame.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <memory>
#include <vector>

#include "query/embree_device.h"
#include "query/hull_query.h"
#include "query/plane_bvh.h"
#include "query/surface_refine.h"

namespace hm {

struct HullQuery::Impl {
  std::vector<Patch> patches;
  std::vector<query::ParamDomain> domains;  // per patch (set for patches with triangles)
  // Per patch, every patch: net_size of its surface (m), the scale of Newton's tolerances (a
  // closest point may start on a patch with no triangle here, from a corner made on it).
  std::vector<double> nets;

  BBox3d box;                // of the mesh vertices, model frame
  Vec3d centre;              // origin of the local frame
  double length = 1;         // L: largest extent of box (metres)
  double max_deviation = 0;  // largest distance, triangle centroid to surface (metres)

  std::vector<Vec3d> local;                   // per vertex, local frame, double
  std::vector<std::array<float, 4>> local_f;  // per vertex, local frame, Embree copy (x y z pad)

  // Per triangle, numbered patch by patch (patch p owns [patch_first[p], patch_first[p + 1]));
  // Embree's (geomID, primID) is (p, triangle - patch_first[p]).
  std::vector<std::array<Index, 3>> tri;  // vertex indices
  std::vector<Index> tri_face;            // source mesh face
  std::vector<PatchId> tri_patch;
  std::vector<std::array<Vec2d, 3>> tri_uv;  // corner (u, v) on tri_patch, seams unwrapped
  std::vector<Index> patch_first;            // size patches + 1
  // Per vertex, the patch it was made on and its (u, v) there (both empty when the mesh has
  // none): a triangle may reach past its own patch's surface (a merge's stitch across an
  // overlap's cut), and its corners then say which surface lies under it.
  std::vector<PatchId> vertex_patch;
  std::vector<Vec2d> vertex_uv;

  query::ScenePtr scene;
  query::PlaneBvh plane_bvh;

  Impl(std::span<const Patch> patches, const SurfaceMesh& mesh);
  // Fills tri_uv (tri, tri_patch and domains must be set).
  void project_corners(const SurfaceMesh& mesh);
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  Index triangle(unsigned geom_id, unsigned prim_id) const {
    return patch_first[geom_id] + prim_id;
  }
  Vec3d to_model(const Vec3d& local_point) const { return local_point + centre; }
  // (u, v) at barycentric (b1, b2) of triangle t (weights 1 - b1 - b2, b1, b2 on corners 0, 1, 2),
  // mapped into the patch domain.
  Vec2d uv_at(Index t, double b1, double b2) const;
  // The surface normal at (u, v), oriented by Patch::reversed.
  Vec3d oriented_normal(PatchId p, Vec2d uv) const;
  // Newton tolerance: 1e-9 L, the accuracy the issue asks of every refined point.
  double accept_tolerance() const { return 1e-9 * length; }
};

}  // namespace hm

namespace hm::query {

// A patch with a triangle near a point, and the (u, v) of the nearest spot on that triangle.
struct PatchCandidate {
  PatchId patch = kInvalid;
  Index triangle = kInvalid;
  double distance = 0;  // from the point to the triangle, metres
  Vec2d uv;
};

// Up to kMaxCandidates patches whose triangles come within (nearest triangle distance + margin)
// of q (model frame), nearest first; margin is twice how far triangles stray from the surface,
// plus `extra` (metres) for callers that need a wider net.
inline constexpr int kMaxCandidates = 8;
struct PatchCandidates {
  std::array<PatchCandidate, kMaxCandidates> items;
  int count = 0;
};
PatchCandidates patches_near(const HullQuery::Impl& m, const Vec3d& q, double extra);
// The mesh vertex nearest q (model frame) among those made on patch p (vertex_patch), found
// through the triangles that hold them; kInvalid when the mesh has no vertex patches or none.
Index nearest_vertex_on(const HullQuery::Impl& m, const Vec3d& q, PatchId p);

}  // namespace hm::query
