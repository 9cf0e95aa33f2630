#include "cli/merge_mirrored.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "cli/prepare_hull.h"
#include "core/error.h"
#include "mesh/adjacency.h"
#include "mesh/mirror_mesh.h"
#include "unstructured/features.h"

namespace hm::cli {
namespace {

// The image half: faces from `first_image` on and vertices from `first_image_vertex` on take the
// mirrored patch (p + n) and its (u, v), u reversed over the patch's domain.
void name_images(std::span<const Patch> whole, std::size_t n, std::size_t first_image,
                 std::size_t first_image_vertex, SurfaceMesh& m) {
  for (std::size_t f = first_image; f < m.face_count(); ++f) {
    m.face_patch[f] += static_cast<PatchId>(n);
  }
  for (std::size_t v = first_image_vertex; v < m.vertex_count(); ++v) {
    const PatchId p = m.vertex_patch[v];
    const NurbsSurface& s = whole[p].surface;
    m.vertex_uv[v].x = s.u0 + (s.u1 - m.vertex_uv[v].x);
    m.vertex_patch[v] = p + static_cast<PatchId>(n);
  }
}

// Splits at its midpoint each interior edge whose two ends lie on the open boundary within tol
// of y = 0: the mirror shares both ends, so the image's two faces would join the half's two on
// that edge. A Wigley's end, where the hull has no thickness, has such chords across the corner
// of stem or stern and keel. Each face keeps its patch; the midpoint takes its first end's patch
// and (u, v), averaged when both ends lie on one patch. Returns the edges split.
std::size_t split_plane_chords(MergedSurface& half, double tol) {
  SurfaceMesh& m = half.mesh;
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  std::vector<std::uint8_t> open(m.vertex_count(), 0);
  for (Index e : adj.boundary_edges) open[adj.edges[e].v0] = open[adj.edges[e].v1] = 1;
  const auto on_plane = [&](Index v) { return open[v] && std::abs(m.positions[v].y) <= tol; };
  std::vector<Index> chords;
  for (std::size_t e = 0; e < adj.edges.size(); ++e) {
    const MeshEdge& edge = adj.edges[e];
    if (edge.uses == 2 && on_plane(edge.v0) && on_plane(edge.v1)) chords.push_back(Index(e));
  }
  const std::size_t first_new_face = m.face_count();
  for (Index e : chords) {
    const MeshEdge& edge = adj.edges[e];
    const Index a = edge.v0, b = edge.v1;
    // The edge's two faces as the adjacency knows them, and those earlier splits appended (a
    // face with two such chords has one of them moved into its second half).
    std::vector<std::size_t> around{edge.first_slot / 4, adj.opposite_face[edge.first_slot]};
    for (std::size_t f = first_new_face; f < m.face_count(); ++f) around.push_back(f);
    const Index mid = static_cast<Index>(m.vertex_count());
    m.positions.push_back(0.5 * (m.positions[a] + m.positions[b]));
    m.vertex_patch.push_back(m.vertex_patch[a]);
    m.vertex_uv.push_back(m.vertex_patch[a] == m.vertex_patch[b]
                              ? 0.5 * (m.vertex_uv[a] + m.vertex_uv[b])
                              : m.vertex_uv[a]);
    half.vert_new2old.push_back(half.vert_new2old[a]);
    // Each face on the edge becomes two, the second appended with the first's patch.
    for (const std::size_t f : around) {
      if (f >= m.face_count()) continue;  // kInvalid: no face across (not expected at two uses)
      Face& t = m.faces[f];
      for (int k = 0; k < 3; ++k) {
        const Index p = t[k], q = t[(k + 1) % 3];
        if (!((p == a && q == b) || (p == b && q == a))) continue;
        const Index r = t[(k + 2) % 3];
        t = Face{p, mid, r, kInvalid};
        m.faces.push_back(Face{mid, q, r, kInvalid});
        m.face_patch.push_back(m.face_patch[f]);
        half.face_new2old.push_back(half.face_new2old[f]);
        break;
      }
    }
  }
  return chords.size();
}

}  // namespace

MergedSurface merge_mirrored_half(std::span<const Patch> whole,
                                  const Tessellation& half_tessellation,
                                  const MergeOptions& options, const FloatingTransform& to_placed,
                                  Progress& progress) {
  if (whole.size() % 2 != 0) {
    throw GeometryError("mirrored merge: the patches are not a half and its mirror image");
  }
  const std::size_t n = whole.size() / 2;
  // merge the half -> mirror it -> name the image's patches -> place the whole -> report.
  MergedSurface half = merge_patches(whole.first(n), half_tessellation.mesh, options, progress);
  const double centre_tol = kPlaneTolerance * hull_length(half.mesh);
  split_plane_chords(half, centre_tol);
  const std::size_t half_vertices = half.mesh.vertex_count();
  MirroredMesh mirrored = mirror_half_hull(half.mesh, centre_tol);

  MergedSurface out;
  out.mesh = std::move(mirrored.mesh);
  name_images(whole, n, out.mesh.face_count() / 2, half_vertices, out.mesh);
  for (Vec3d& p : out.mesh.positions) p = to_placed(p);
  for (Index v : mirrored.vert_new2old) out.vert_new2old.push_back(half.vert_new2old[v]);
  for (Index f : mirrored.face_new2old) out.face_new2old.push_back(half.face_new2old[f]);

  out.report = half.report;
  MergeReport& r = out.report;
  const std::size_t flipped = r.patches_flipped.size();
  for (std::size_t i = 0; i < flipped; ++i) {
    r.patches_flipped.push_back(r.patches_flipped[i] + static_cast<PatchId>(n));
  }
  const EdgeAdjacency adj = build_edge_adjacency(out.mesh.faces, out.mesh.vertex_count());
  r.boundary_loops = adj.boundary_loops.size();
  r.nonmanifold_edges = adj.nonmanifold_edges.size();
  r.inconsistent_edges = adj.inconsistent_edges.size();
  r.enclosed_volume = merge::enclosed_volume(out.mesh, adj);
  return out;
}

}  // namespace hm::cli
