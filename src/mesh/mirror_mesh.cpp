#include "mesh/mirror_mesh.h"

#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "mesh/adjacency.h"

namespace hm {

bool is_half_hull(const SurfaceMesh& mesh, double tol) {
  bool port = false, starboard = false;
  for (const Vec3d& p : mesh.positions) {
    port |= p.y > tol;
    starboard |= p.y < -tol;
  }
  return !(port && starboard);
}

MirroredMesh mirror_half_hull(const SurfaceMesh& half, double on_plane_tol) {
  const std::size_t nv = half.vertex_count();
  if (!is_half_hull(half, on_plane_tol)) {
    throw GeometryError("mirror: the mesh has vertices on both sides of y = 0 beyond " +
                        std::to_string(on_plane_tol) + " m; it is not a half hull");
  }
  const bool has_uv = half.vertex_uv.size() == nv && half.vertex_patch.size() == nv;
  const bool has_blocks = half.face_block.size() == half.face_count();

  MirroredMesh out;
  SurfaceMesh& m = out.mesh;
  m = half;
  out.vert_new2old.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) out.vert_new2old[v] = static_cast<Index>(v);
  out.face_new2old.resize(half.face_count());
  for (std::size_t f = 0; f < half.face_count(); ++f) out.face_new2old[f] = static_cast<Index>(f);

  // Vertices on the open boundary (an edge with one face): only they may be shared. An interior
  // vertex near y = 0 (a narrow keel) is repeated, or the halves would overlap there.
  const EdgeAdjacency adj = build_edge_adjacency(half.faces, nv);
  std::vector<std::uint8_t> open(nv, 0);
  for (Index e : adj.boundary_edges) open[adj.edges[e].v0] = open[adj.edges[e].v1] = 1;

  // Mirror index of every vertex: itself on the plane, else a new vertex (in vertex order).
  std::vector<Index> mirror(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    Vec3d& p = m.positions[v];
    if (open[v] && std::abs(p.y) <= on_plane_tol) {
      p.y = 0;
      mirror[v] = static_cast<Index>(v);
      continue;
    }
    mirror[v] = static_cast<Index>(m.positions.size());
    m.positions.push_back({p.x, -p.y, p.z});
    out.vert_new2old.push_back(static_cast<Index>(v));
    if (has_uv) {
      m.vertex_patch.push_back(half.vertex_patch[v]);
      m.vertex_uv.push_back(half.vertex_uv[v]);
    }
  }
  for (std::size_t f = 0; f < half.face_count(); ++f) {
    const Face& g = half.faces[f];
    const bool tri = g[3] == kInvalid;
    Face r = tri ? Face{mirror[g[0]], mirror[g[2]], mirror[g[1]], kInvalid}
                 : Face{mirror[g[0]], mirror[g[3]], mirror[g[2]], mirror[g[1]]};
    m.faces.push_back(r);
    m.face_patch.push_back(half.face_patch[f]);
    if (has_blocks) m.face_block.push_back(half.face_block[f]);
    out.face_new2old.push_back(static_cast<Index>(f));
  }
  return out;
}

std::vector<std::array<Index, 2>> mirrored_edges(const MirroredMesh& m, std::size_t half_vertices,
                                                 std::span<const std::array<Index, 2>> edges) {
  std::vector<Index> twin(half_vertices);
  for (std::size_t v = 0; v < twin.size(); ++v) twin[v] = static_cast<Index>(v);
  for (std::size_t v = half_vertices; v < m.vert_new2old.size(); ++v) {
    twin[m.vert_new2old[v]] = static_cast<Index>(v);
  }
  std::vector<std::array<Index, 2>> out;
  out.reserve(edges.size());
  for (const auto& [a, b] : edges) out.push_back({twin[a], twin[b]});
  return out;
}

}  // namespace hm
