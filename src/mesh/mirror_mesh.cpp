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
  // The half's faces, with each quad that has three corners in the plane split in two along
  // the diagonal from its fourth corner. Such a quad lies folded against the centre plane where
  // the hull has no thickness (a Wigley's stern at its keel, the property test's seed 1068), and
  // its image shares those three corners: their centres lie half the fourth corner's distance
  // from the plane apart, within the "very close" 5% of their size. Both triangles take the
  // fourth corner, so their images lie two thirds of it apart.
  std::vector<Face> faces;
  std::vector<Index> faces_old;  // the half's face each comes from
  faces.reserve(half.face_count());
  faces_old.reserve(half.face_count());
  for (std::size_t f = 0; f < half.face_count(); ++f) {
    const Face& g = half.faces[f];
    int off = -1, on = 0;
    if (g[3] != kInvalid) {
      for (int c = 0; c < 4; ++c) {
        if (mirror[g[c]] == g[c]) {
          ++on;
        } else {
          off = c;
        }
      }
    }
    if (on != 3) {
      faces.push_back(g);
      faces_old.push_back(static_cast<Index>(f));
      continue;
    }
    const Index a = g[off], b = g[(off + 1) % 4], c = g[(off + 2) % 4], d = g[(off + 3) % 4];
    faces.push_back({a, b, c, kInvalid});
    faces.push_back({a, c, d, kInvalid});
    faces_old.push_back(static_cast<Index>(f));
    faces_old.push_back(static_cast<Index>(f));
  }
  if (faces.size() != half.face_count()) {
    m.faces = faces;
    m.face_patch.clear();
    if (has_blocks) m.face_block.clear();
    for (Index f : faces_old) {
      m.face_patch.push_back(half.face_patch[f]);
      if (has_blocks) m.face_block.push_back(half.face_block[f]);
    }
    out.face_new2old = faces_old;
  }
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Face& g = faces[i];
    const Index f = faces_old[i];
    const bool tri = g[3] == kInvalid;
    Face r = tri ? Face{mirror[g[0]], mirror[g[2]], mirror[g[1]], kInvalid}
                 : Face{mirror[g[0]], mirror[g[3]], mirror[g[2]], mirror[g[1]]};
    m.faces.push_back(r);
    m.face_patch.push_back(half.face_patch[f]);
    if (has_blocks) m.face_block.push_back(half.face_block[f]);
    out.face_new2old.push_back(f);
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
