#include "mesh/snap_centre_plane.h"

#include <cmath>

#include "mesh/adjacency.h"

namespace hm {

std::size_t snap_to_centre_plane(SurfaceMesh& mesh, double tol) {
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  std::size_t moved = 0;
  for (Index e : adj.boundary_edges) {
    for (Index v : {adj.edges[e].v0, adj.edges[e].v1}) {
      double& y = mesh.positions[v].y;
      if (y != 0 && std::abs(y) <= tol) {
        y = 0;
        ++moved;
      }
    }
  }
  return moved;
}

std::size_t drop_centre_plane_faces(SurfaceMesh& mesh) {
  std::size_t kept = 0;
  const std::size_t n = mesh.faces.size();
  for (std::size_t f = 0; f < n; ++f) {
    const Face& face = mesh.faces[f];
    bool on_plane = true;
    for (int c = 0; c < corner_count(face); ++c)
      on_plane = on_plane && mesh.positions[face[c]].y == 0;
    if (on_plane) continue;
    mesh.faces[kept] = face;
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
