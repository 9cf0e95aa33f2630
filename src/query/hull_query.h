// Ray, closest-point and plane-section queries on a hull, answered on its triangulation through
// Embree BVHs and refined onto the exact NURBS patches in double precision.
//
// All positions are in metres in the model frame of the patches. L, the length scale that the
// tolerances below are relative to, is the largest extent of the mesh's bounding box (the hull
// length for a ship).
#pragma once

#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "core/bbox.h"
#include "core/types.h"
#include "core/vec.h"
#include "mesh/surface_mesh.h"
#include "nurbs/patch.h"

namespace hm {

struct Ray {
  Vec3d origin;
  Vec3d dir;  // need not be unit; t is measured in multiples of dir
  double tmax = std::numeric_limits<double>::infinity();
};

// A point on the hull surface. patch is kInvalid when there is none (a ray that misses).
// normal is the unit surface normal oriented by Patch::reversed. on_surface is false only when
// the refinement onto the NURBS did not converge; point is then the triangle's estimate.
struct SurfacePoint {
  PatchId patch = kInvalid;
  Index face = kInvalid;  // the mesh face the BVH found
  Vec2d uv;
  Vec3d point;
  Vec3d normal;
  bool on_surface = false;
  bool valid() const { return patch != kInvalid; }
};

struct RayHit : SurfacePoint {
  double t = 0;  // point = origin + t * dir
};

struct ClosestPoint : SurfacePoint {
  double distance = 0;  // |query - point|, metres
};

struct Plane {
  Vec3d point;
  Vec3d normal;  // need not be unit; must not be zero
};

struct SectionPoint {
  Vec3d point;  // on the patch's NURBS and on the plane to 1e-9 L
  PatchId patch = kInvalid;
  Vec2d uv;
};

// An ordered first-order spline. Closed polylines do not repeat their first point, run
// counter-clockwise about the plane normal (right-hand rule) and start at their lowest point in
// (z, y, x) order. Open ones start at the end with the smaller z; when the two ends' z agree
// within the join tolerance, the smaller y (same tolerance); then the smaller x.
struct SectionPolyline {
  std::vector<SectionPoint> points;
  bool closed = false;
};

// Polylines sorted by their first point in (z, y, x) order, then by point count.
struct Section {
  std::vector<SectionPolyline> polylines;
};

struct SectionOptions {
  // Open pieces whose ends lie within join_tolerance * L are chained into one polyline (patch
  // borders that are not shared mesh edges, small gaps between imported patches).
  double join_tolerance = 1e-6;
  // false: points stay on the triangulation (within its chord error of the surface, (u, v)
  // interpolated), for quick drawings; the NURBS refinement is most of a section's cost.
  bool refine = true;
};

class HullQuery {
 public:
  // mesh: triangles (a quad is used as two triangles split along 0-2) with face_patch indexing
  // patches; vertex_uv and vertex_patch as SurfaceMesh documents (when vertex_uv is empty, the
  // (u, v) of every corner is found by projection). Throws GeometryError on inconsistent input or
  // an Embree failure. The object is immutable afterwards; every query is thread-safe.
  HullQuery(std::span<const Patch> patches, const SurfaceMesh& mesh);
  ~HullQuery();
  HullQuery(HullQuery&&) noexcept;
  HullQuery& operator=(HullQuery&&) noexcept;

  // First surface crossing in (0, tmax]; invalid when the ray misses. A mesh crossing that is not
  // a surface crossing (a ray grazing the hull within the chord error) is passed over; only when
  // several in a row are, the first is returned with on_surface false.
  RayHit first_hit(const Ray& ray) const;
  // Every surface crossing in (0, tmax], sorted by t; crossings closer than 1e-9 L (a ray through
  // a shared edge or a patch border) count once. Grazing mesh crossings are dropped.
  std::vector<RayHit> all_hits(const Ray& ray) const;
  // out[i] = first_hit(rays[i]); out.size() must equal rays.size().
  void first_hits(std::span<const Ray> rays, std::span<RayHit> out) const;

  ClosestPoint closest_point(const Vec3d& q) const;
  // The closest point on the patches numbered first <= p < last whose triangles come within
  // `reach` metres of q (beyond the nearest triangle of all); invalid when none does. For
  // finding where one patch lies on others (overlaps).
  ClosestPoint closest_point_in_range(const Vec3d& q, PatchId first, PatchId last,
                                      double reach) const;
  void closest_points(std::span<const Vec3d> queries, std::span<ClosestPoint> out) const;

  // The hull cut by a plane; empty when the plane misses. The BVH finds the crossed triangles.
  Section section(const Plane& plane, const SectionOptions& options = {}) const;
  // One section per plane, computed in parallel; equal to calling section() for each.
  std::vector<Section> sections(std::span<const Plane> planes,
                                const SectionOptions& options = {}) const;
  // Same answer as section() from a loop over every triangle (tests and benchmarks).
  Section section_brute_force(const Plane& plane, const SectionOptions& options = {}) const;
  // The search alone, the part of a section that the BVH replaces: the mesh faces the plane
  // crosses (grouped by patch, in face order within a patch; a quad is listed once per crossed
  // half), found through the BVH or by the loop over every triangle. Both give the same list.
  std::vector<Index> crossed_faces(const Plane& plane) const;
  std::vector<Index> crossed_faces_brute_force(const Plane& plane) const;

  BBox3d bbox() const;
  double length_scale() const;
  std::size_t triangle_count() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace hm
