#include "mesh/surface_mesh.h"

namespace hm {

double face_area(std::span<const Vec3d> p, const Face& f) {
  double a = 0.5 * norm(cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]));
  if (!is_triangle(f)) a += 0.5 * norm(cross(p[f[2]] - p[f[0]], p[f[3]] - p[f[0]]));
  return a;
}

Vec3d face_normal(std::span<const Vec3d> p, const Face& f) {
  // Newell's method: exact for planar polygons, a sensible average for warped quads.
  const int n = corner_count(f);
  Vec3d sum;
  for (int i = 0; i < n; ++i) {
    const Vec3d& a = p[f[i]];
    const Vec3d& b = p[f[(i + 1) % n]];
    sum += Vec3d{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  return normalized(sum);
}

Vec3d face_centroid(std::span<const Vec3d> p, const Face& f) {
  const int n = corner_count(f);
  Vec3d c;
  for (int i = 0; i < n; ++i) c += p[f[i]];
  return c / n;
}

std::size_t keep_faces(SurfaceMesh& mesh, std::span<const std::uint8_t> keep) {
  const std::size_t n = mesh.faces.size();
  std::size_t kept = 0;
  for (std::size_t f = 0; f < n; ++f) {
    if (!keep[f]) continue;
    mesh.faces[kept] = mesh.faces[f];
    if (!mesh.face_patch.empty()) mesh.face_patch[kept] = mesh.face_patch[f];
    if (!mesh.face_block.empty()) mesh.face_block[kept] = mesh.face_block[f];
    ++kept;
  }
  mesh.faces.resize(kept);
  if (!mesh.face_patch.empty()) mesh.face_patch.resize(kept);
  if (!mesh.face_block.empty()) mesh.face_block.resize(kept);
  return n - kept;
}

}  // namespace hm
