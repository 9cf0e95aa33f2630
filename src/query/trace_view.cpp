// Orthographic cameras for the four views, and one Embree ray per pixel.
#include "query/trace_view.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"
#include "query/embree_device.h"

namespace hm {
namespace {

void check_mesh(const SurfaceMesh& mesh) {
  if (mesh.faces.empty()) throw GeometryError("render: the mesh has no faces");
  const std::size_t nv = mesh.positions.size();
  for (const Vec3d& p : mesh.positions) {
    if (!is_finite(p)) throw GeometryError("render: a vertex position is not finite");
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < corner_count(mesh.faces[f]); ++k) {
      if (mesh.faces[f][k] >= nv) {
        throw GeometryError("render: face " + std::to_string(f) +
                            " has a vertex index out of range");
      }
    }
  }
}

// Box of the vertices that faces use (a file may carry unused vertices).
BBox3d face_box(const SurfaceMesh& mesh) {
  BBox3d box;
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < corner_count(f); ++k) box.add(mesh.positions[f[k]]);
  }
  return box;
}

// The side of the centre plane a view looks at: +1 port (y >= 0), -1 starboard, chosen as the
// side the mesh reaches farther into (a port half hull, a starboard half hull, a full hull).
double shown_side(const BBox3d& box) { return box.hi.y >= -box.lo.y ? 1.0 : -1.0; }

std::uint32_t picture_height(double extent, double pixel, std::uint32_t max_height,
                             std::uint32_t width) {
  const double h = std::ceil(extent / pixel - 1e-9);
  if (!(h <= max_height)) {
    throw UsageError("render: the picture would be " + std::to_string(width) + " x " +
                     (std::isfinite(h) ? std::to_string(static_cast<long long>(h)) : "inf") +
                     " pixels (at most " + std::to_string(max_height) +
                     " rows); use a smaller --width");
  }
  return std::max<std::uint32_t>(1, static_cast<std::uint32_t>(h));
}

// Profile, plan and iso: one pane. right, up and dir are orthonormal; the plan's triple is
// left-handed on purpose (seen from below, drawn with y up, as a plan is read).
ViewCamera fit_single(const SurfaceMesh& mesh, const BBox3d& box, Vec3d right, Vec3d up, Vec3d dir,
                      std::uint32_t width, double margin, std::uint32_t max_height) {
  double u0 = std::numeric_limits<double>::infinity(), u1 = -u0, v0 = u0, v1 = -u0, w0 = u0,
         w1 = -u0;
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < corner_count(f); ++k) {
      const Vec3d p = mesh.positions[f[k]] - box.center();
      u0 = std::min(u0, dot(p, right));
      u1 = std::max(u1, dot(p, right));
      v0 = std::min(v0, dot(p, up));
      v1 = std::max(v1, dot(p, up));
      w0 = std::min(w0, dot(p, dir));
      w1 = std::max(w1, dot(p, dir));
    }
  }
  const double eu = u1 - u0, ev = v1 - v0;
  const double m = margin * std::max(eu, ev);
  // A mesh seen edge-on across the picture (a plate in the view direction) still gets a width.
  const double span_u = std::max(eu, 0.2 * ev) + 2 * m;
  if (!(span_u > 0)) throw GeometryError("render: the mesh has zero extent in the picture plane");
  ViewCamera cam;
  cam.width = width;
  cam.pixel_size = span_u / width;
  cam.height = picture_height(ev + 2 * m, cam.pixel_size, max_height, width);
  const double px = cam.pixel_size;
  const double uc = 0.5 * (u0 + u1), vc = 0.5 * (v0 + v1);
  const double back = w0 - m - 0.01 * box.diagonal();  // rays start in front of everything
  OrthoPane pane;
  pane.columns = width;
  pane.origin = box.center() + (uc + (0.5 - 0.5 * width) * px) * right +
                (vc - (0.5 - 0.5 * cam.height) * px) * up + back * dir;
  pane.step_right = px * right;
  pane.step_down = -px * up;
  pane.dir = dir;
  pane.tmax = (w1 - back) + m + 0.01 * box.diagonal();
  cam.panes.push_back(pane);
  return cam;
}

// Body plan: the aft body (x < midship) seen from astern on the left half, the fore body from
// ahead on the right half; each ray stops at the midship plane. The centre plane y = 0 (or the
// box's nearest y when the mesh lies off it) is the picture's middle column boundary.
ViewCamera fit_body_plan(const BBox3d& box, std::uint32_t width, double margin,
                         std::uint32_t max_height) {
  const double side = shown_side(box);
  const double yc = std::clamp(0.0, box.lo.y, box.hi.y);
  const double half = side > 0 ? box.hi.y - yc : yc - box.lo.y;
  const double ez = box.hi.z - box.lo.z;
  const double m = margin * std::max(2 * half, ez);
  const double span = std::max(2 * half, 0.2 * ez) + 2 * m;
  if (!(span > 0)) throw GeometryError("render: the mesh has zero extent in the picture plane");
  ViewCamera cam;
  cam.width = width;
  cam.pixel_size = span / width;
  cam.height = picture_height(ez + 2 * m, cam.pixel_size, max_height, width);
  cam.centre_line_x = 0.5 * width;
  const double px = cam.pixel_size;
  const double x_mid = box.center().x;
  const double zc = box.center().z;
  const double reach = 0.01 * box.diagonal() + m;
  const double z_first = zc - (0.5 - 0.5 * cam.height) * px;  // centre of row 0
  auto column_offset = [&](std::uint32_t i) { return (i + 0.5 - 0.5 * width) * px; };

  OrthoPane aft;  // columns left of the centre line; moving right approaches the centre plane
  aft.first_column = 0;
  aft.columns = width / 2;
  aft.origin = {box.lo.x - reach, yc - side * column_offset(0), z_first};
  aft.step_right = {0, -side * px, 0};
  aft.step_down = {0, 0, -px};
  aft.dir = {1, 0, 0};
  aft.tmax = x_mid - aft.origin.x;

  OrthoPane fore;
  fore.first_column = width / 2;
  fore.columns = width - width / 2;
  fore.origin = {box.hi.x + reach, yc + side * column_offset(fore.first_column), z_first};
  fore.step_right = {0, side * px, 0};
  fore.step_down = {0, 0, -px};
  fore.dir = {-1, 0, 0};
  fore.tmax = fore.origin.x - x_mid;

  if (aft.columns > 0) cam.panes.push_back(aft);
  cam.panes.push_back(fore);
  return cam;
}

}  // namespace

ViewCamera fit_view_camera(const SurfaceMesh& mesh, ViewKind kind, std::uint32_t width,
                           double margin, std::uint32_t max_height) {
  check_mesh(mesh);
  if (width == 0) throw UsageError("render: the picture width must be positive");
  const BBox3d box = face_box(mesh);
  const Vec3d x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  switch (kind) {
    case ViewKind::kProfile:
      return fit_single(mesh, box, x, z, y, width, margin, max_height);
    case ViewKind::kPlan:
      return fit_single(mesh, box, x, y, z, width, margin, max_height);
    case ViewKind::kBodyPlan:
      return fit_body_plan(box, width, margin, max_height);
    case ViewKind::kIso: {
      // The bow quarter from below, on the side the mesh shows: 35 deg forward of the beam and
      // 25 deg down. A true isometric (equal angles) of a hull 20 times longer than deep is a
      // thin diagonal strip; this shows the wetted bottom, the bow and the side together.
      const double side = shown_side(box);
      const Vec3d dir = normalized(Vec3d{-0.52, -0.74 * side, 0.42});
      const Vec3d up = normalized(z - dot(z, dir) * dir);
      return fit_single(mesh, box, cross(dir, up), up, dir, width, margin, max_height);
    }
  }
  throw InternalError("render: unknown view");
}

ViewHits trace_view(const SurfaceMesh& mesh, const ViewCamera& cam) {
  check_mesh(mesh);
  const Vec3d centre = face_box(mesh).center();

  // Local frame, double and the float copy Embree reads (x y z pad).
  std::vector<Vec3d> local(mesh.positions.size());
  std::vector<std::array<float, 4>> local_f(mesh.positions.size());
  for (std::size_t i = 0; i < local.size(); ++i) {
    local[i] = mesh.positions[i] - centre;
    local_f[i] = {static_cast<float>(local[i].x), static_cast<float>(local[i].y),
                  static_cast<float>(local[i].z), 0.0f};
  }
  // Triangles in face order; a quad owns two, split along 0-2. tri_face maps primID -> face.
  std::vector<std::array<Index, 3>> tri;
  std::vector<Index> tri_face;
  tri.reserve(2 * mesh.faces.size());
  tri_face.reserve(2 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    tri.push_back({face[0], face[1], face[2]});
    tri_face.push_back(static_cast<Index>(f));
    if (!is_triangle(face)) {
      tri.push_back({face[0], face[2], face[3]});
      tri_face.push_back(static_cast<Index>(f));
    }
  }

  RTCDevice device = query::embree_device();
  const query::ScenePtr scene(rtcNewScene(device));
  query::check_embree("rtcNewScene");
  rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, local_f.data(), 0,
                             sizeof(local_f[0]), local_f.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, tri.data(), 0,
                             sizeof(tri[0]), tri.size());
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene.get(), geom);
  rtcReleaseGeometry(geom);
  query::check_embree("building the picture's geometry");
  rtcCommitScene(scene.get());
  query::check_embree("rtcCommitScene");

  ViewHits hits;
  hits.width = cam.width;
  hits.height = cam.height;
  const std::size_t n = std::size_t{cam.width} * cam.height;
  hits.face.assign(n, kInvalid);
  hits.point.assign(n, Vec3d{});
  hits.column_dir.assign(cam.width, Vec3d{});
  std::vector<std::uint32_t> column_pane(cam.width, 0);
  for (std::uint32_t p = 0; p < cam.panes.size(); ++p) {
    const OrthoPane& pane = cam.panes[p];
    for (std::uint32_t i = pane.first_column; i < pane.first_column + pane.columns; ++i) {
      if (i >= cam.width) throw InternalError("render: a camera pane runs past the picture");
      column_pane[i] = p;
      hits.column_dir[i] = pane.dir;
    }
  }

  RTCScene sc = scene.get();
  parallel_for(
      0, cam.height,
      [&](std::size_t j) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        for (std::uint32_t i = 0; i < cam.width; ++i) {
          const OrthoPane& pane = cam.panes[column_pane[i]];
          const Vec3d o = pane.origin + double(i - pane.first_column) * pane.step_right +
                          double(j) * pane.step_down - centre;
          RTCRayHit rh{};
          rh.ray.org_x = static_cast<float>(o.x);
          rh.ray.org_y = static_cast<float>(o.y);
          rh.ray.org_z = static_cast<float>(o.z);
          rh.ray.dir_x = static_cast<float>(pane.dir.x);
          rh.ray.dir_y = static_cast<float>(pane.dir.y);
          rh.ray.dir_z = static_cast<float>(pane.dir.z);
          rh.ray.tnear = 0.0f;
          rh.ray.tfar = static_cast<float>(pane.tmax);
          rh.ray.mask = ~0u;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(sc, &ctx, &rh);
          if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
          const std::size_t slot = j * cam.width + i;
          const Index t = rh.hit.primID;
          hits.face[slot] = tri_face[t];
          // The crossing of the ray with the hit triangle's plane, in double.
          const Vec3d& a = local[tri[t][0]];
          const Vec3d nrm = cross(local[tri[t][1]] - a, local[tri[t][2]] - a);
          const double denom = dot(nrm, pane.dir);
          const double s = denom != 0 ? dot(nrm, a - o) / denom : double{rh.ray.tfar};
          hits.point[slot] = o + s * pane.dir + centre;
        }
      },
      1, 2);
  return hits;
}

}  // namespace hm
