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

}  // namespace hm
