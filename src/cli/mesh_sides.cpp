// Heeled hulls, side by side: frame -> split at the centre plane -> plan the whole hull's stations
// -> mesh each side (starboard as its mirror image, a port side) -> join -> back to the floating
// frame.
#include "cli/mesh_sides.h"

#include <chrono>
#include <memory>
#include <utility>

#include "mesh/adjacency.h"
#include "mesh/snap_centre_plane.h"
#include "quality/hydrostatics.h"
#include "query/hull_query.h"
#include "unstructured/cut_at_plane.h"

namespace hm::cli {
namespace {

// The ship's own frame, trimmed but not heeled: p_G = A (p_F - o), with A = R_trim R^T (R the
// floating rotation, heel then trim) and o the floating image of the ship's origin, which lies in
// its centre plane. There p_G = R_trim p_ship, so the centre plane is y = 0 and the stations are
// the upright hull's at that trim. The waterplane z_F = 0 is dot(up, p_G) = waterline.
struct ShipFrame {
  FloatingTransform to, back;
  Vec3d up;
  double waterline = 0;
};

ShipFrame ship_frame(const Floating& f) {
  const FloatingTransform trim =
      floating_placement(f.draft, f.trim_deg, 0, f.baseline_z, f.pivot_x).transform;
  const auto& rt = trim.rotation;
  const auto& r = f.transform.rotation;
  ShipFrame s;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double a = 0;
      for (int k = 0; k < 3; ++k) a += rt[3 * i + k] * r[3 * j + k];
      s.to.rotation[3 * i + j] = a;
      s.back.rotation[3 * j + i] = a;
    }
  }
  const Vec3d o = f.transform.translation;
  s.to.translation = Vec3d{0, 0, 0} - s.to.rotate(o);
  s.back.translation = o;
  s.up = {s.to.rotation[2], s.to.rotation[5], s.to.rotation[8]};
  s.waterline = -o.z;
  return s;
}

Vec3d mirrored(Vec3d p) {
  p.y = -p.y;
  return p;
}

// The faces of one side of y = 0 (by centroid; port keeps y >= 0), vertices renumbered in order.
// Starboard comes as its mirror image about y = 0, wound the other way, so it is a port side
// whose normals still point out of the hull.
SurfaceMesh side_of(const SurfaceMesh& m, bool port) {
  SurfaceMesh out;
  std::vector<Index> vert_old2new(m.vertex_count(), kInvalid);
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const Face& face = m.faces[f];
    if ((face_centroid(m.positions, face).y >= 0) != port) continue;
    Face g = face;
    for (int c = 0; c < corner_count(face); ++c) {
      Index& v = vert_old2new[face[c]];
      if (v == kInvalid) {
        v = static_cast<Index>(out.positions.size());
        out.positions.push_back(port ? m.positions[face[c]] : mirrored(m.positions[face[c]]));
        out.vertex_patch.push_back(m.vertex_patch[face[c]]);
        out.vertex_uv.push_back(m.vertex_uv[face[c]]);
      }
      g[c] = v;
    }
    if (!port) std::swap(g[1], is_triangle(g) ? g[2] : g[3]);
    out.faces.push_back(g);
    out.face_patch.push_back(m.face_patch[f]);
  }
  return out;
}

// The patches' mirror images about y = 0: the same (u, v) maps to the mirrored point, and the
// flag turns so that the declared normal still points out.
std::vector<Patch> mirrored(std::span<const Patch> patches) {
  std::vector<Patch> out(patches.begin(), patches.end());
  for (Patch& p : out) {
    for (Vec3d& c : p.surface.points) c.y = -c.y;
    p.reversed = !p.reversed;
  }
  return out;
}

void move_hints(std::vector<KnuckleHint>& hints, const FloatingTransform& t, bool mirror) {
  for (KnuckleHint& h : hints) {
    h.plane_point = t(h.plane_point);
    h.plane_normal = t.rotate(h.plane_normal);
    for (Vec3d& p : h.points) p = t(p);
    if (mirror) {
      h.plane_point = mirrored(h.plane_point);
      h.plane_normal = mirrored(h.plane_normal);
      for (Vec3d& p : h.points) p = mirrored(p);
    }
  }
}

// One side as the mesher takes it: its surface, its knuckles and boundaries found again in the
// ship's frame (the waterline leans there, the user's hints moved along), and its query.
struct Side {
  SurfaceMesh surface;
  EdgeAdjacency adjacency;
  FeatureSet features;
  Vec3d up;
  std::unique_ptr<HullQuery> query;
};

Side prepare_side(std::span<const Patch> patches, SurfaceMesh surface, const ShipFrame& frame,
                  bool port, FeatureOptions fo) {
  Side s;
  s.surface = std::move(surface);
  fo.waterline_z = frame.waterline;
  fo.waterplane_normal = s.up = port ? frame.up : mirrored(frame.up);
  move_hints(fo.add, frame.to, !port);
  move_hints(fo.suppress, frame.to, !port);
  s.adjacency = build_edge_adjacency(s.surface.faces, s.surface.vertex_count());
  s.features = find_features(s.surface, s.adjacency, patches, fo);
  s.query = std::make_unique<HullQuery>(patches, s.surface);
  return s;
}

StructuredMesh mesh_side(std::span<const Patch> patches, const Side& side, bool port,
                         StructuredOptions options) {
  options.waterplane_normal = side.up;
  if (!port) {
    for (BlockPlane& p : options.planes) {
      p.point = mirrored(p.point);
      p.normal = mirrored(p.normal);
    }
  }
  return mesh_structured(patches, side.surface, side.adjacency, *side.query, side.features,
                         options);
}

}  // namespace

StructuredMesh mesh_heeled_sides(const PreparedHull& hull, StructuredOptions options,
                                 SideJoin* join) {
  const ShipFrame frame = ship_frame(*hull.floating);
  const std::vector<Patch> patches = transformed(hull.patches(), frame.to);
  const std::vector<Patch> images = mirrored(patches);
  const SurfaceMesh whole = transformed(hull.fine(), frame.to);
  for (BlockPlane& p : options.planes) {
    p.point = frame.to(p.point);
    p.normal = frame.to.rotate(p.normal);
  }
  // The sizes from the whole hull's count, so that both sides take the same.
  const Vec3d size = structured_sizes(whole, options);
  const HullQuery whole_query(patches, whole);
  PlaneCutOptions co;
  co.axis = 1;
  co.keep_both = true;
  // No vertex moved onto the plane first: a waterline vertex beside a fine stem slid along the
  // waterline onto it and took the stem's top vertex's place, and the corner of the waterline
  // and the stem sank a few centimetres (generated round-bilge hull heeled 8.7 degrees: 4 free
  // edges at the stem's top). The rows are cut from the NURBS: slivers of the fine mesh by the
  // plane cost nothing.
  co.snap_fraction = 0;
  const PlaneCut split = cut_at_plane(patches, whole, co);
  const Side port_side =
      prepare_side(patches, side_of(split.mesh, true), frame, true, hull.feature_options);
  const Side stbd_side =
      prepare_side(images, side_of(split.mesh, false), frame, false, hull.feature_options);

  // One pass at the sizes: the whole hull's stations, each side on them, the join.
  StructuredMesh out = mesh_to_count(
      [&](const Vec3d& sizes) {
        StructuredOptions o = options;
        o.size = sizes;
        const auto t0 = std::chrono::steady_clock::now();
        const StationList stations = plan_structured_stations(whole, whole_query, hull.features, o);
        o.station_x = stations.x;
        o.station_border = stations.border;
        const double seconds_plan =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        StructuredMesh port = mesh_side(patches, port_side, true, o);
        StructuredMesh stbd = mesh_side(images, stbd_side, false, o);
        // The seams onto the plane, as for a half hull, but no sliver beside them: the other
        // side's panels are no mirror image. A panel left lying in the plane stays (an upright
        // half drops it, as its mirror image would lie on it): here it is what joins this side's
        // rows to the other side's seam, unless the other side has the same (join_sides).
        for (StructuredMesh* s : {&port, &stbd})
          snap_to_centre_plane(s->mesh, hull.centre_tol, false);
        // Starboard back from its mirror image.
        for (Vec3d& p : stbd.mesh.positions) p = mirrored(p);
        for (Face& f : stbd.mesh.faces) std::swap(f[1], is_triangle(f) ? f[2] : f[3]);
        SeamPlanes planes;
        planes.centre_tol = hull.centre_tol;
        planes.up = frame.up;
        planes.waterline = frame.waterline;
        // The mesher puts waterline nodes on the plane exactly; the frames round.
        planes.waterline_tol = 1e-9 * hull_length(whole);
        StructuredMesh joined = join_sides(std::move(port), std::move(stbd), planes, join);
        joined.report.seconds_plan += seconds_plan;
        return joined;
      },
      size, options);
  for (Vec3d& p : out.mesh.positions) p = frame.back(p);
  return out;
}

}  // namespace hm::cli
