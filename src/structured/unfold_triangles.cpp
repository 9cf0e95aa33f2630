// Pairs of triangles folded onto each other, flipped along their quad's other diagonal. Where a
// station's row runs the full depth and the row beyond it only round a bulb below a raked stem,
// the end cap's zip fans from the bulb's top to the station's upper nodes, and the stem's own
// triangles fold back over that fan (property seed 2563: two triangles 0.11 m apart with opposite
// normals, a 3.7 m diagonal between them where their other diagonal is 0.11 m). The flip turns
// such a pair into two triangles that face the same way, when it makes no edge that is there
// already (or that an earlier flip made). Knuckle edges stay. Nothing moves. Serial in edge order;
// each face flips at most once.
#include <algorithm>
#include <cmath>
#include <optional>

#include "mesh/adjacency.h"
#include "mesh/edge_flip.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// Two unit normals this far from each other (cosine) are folded over: a turn past 120 degrees,
// which no panel code takes between neighbours off a knuckle.
constexpr double kFoldedCosine = -0.5;

// A triangle this flat (doubled area over its longest side squared) has no normal to speak of:
// two of its corners coincide or all three lie on a line, and another step deals with it.
constexpr double kMinShape = 1e-6;

}  // namespace

std::size_t unfold_triangles(std::span<const std::array<Index, 2>> knuckle_edges,
                             SurfaceMesh& mesh) {
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  std::vector<std::uint8_t> knuckle(adj.edges.size(), 0);
  for (const std::array<Index, 2>& k : knuckle_edges) {
    const Index id = find_edge(adj, k[0], k[1]);
    if (id != kInvalid) knuckle[id] = 1;
  }
  std::vector<std::uint8_t> touched(mesh.faces.size(), 0);
  // The edges the flips made: the adjacency, built before them, does not know them.
  std::vector<std::array<Index, 2>> made;
  std::size_t flipped = 0;
  for (std::size_t e = 0; e < adj.edges.size(); ++e) {
    const MeshEdge& edge = adj.edges[e];
    if (knuckle[e] || edge.uses != 2) continue;
    const Index g = edge.first_slot / 4, h = adj.opposite_face[edge.first_slot];
    if (h == kInvalid || touched[g] || touched[h]) continue;
    if (!is_triangle(mesh.faces[g]) || !is_triangle(mesh.faces[h])) continue;
    const Vec3d ng = unit_triangle_normal(mesh, mesh.faces[g], kMinShape),
                nh = unit_triangle_normal(mesh, mesh.faces[h], kMinShape);
    if (ng == Vec3d{} || nh == Vec3d{} || dot(ng, nh) > kFoldedCosine) continue;
    const std::optional<EdgeFlip> f = edge_flip(mesh, adj, static_cast<Index>(e));
    if (!f) continue;
    if (std::find(made.begin(), made.end(), f->made) != made.end()) continue;
    const Vec3d n0 = unit_triangle_normal(mesh, f->t0, kMinShape),
                n1 = unit_triangle_normal(mesh, f->t1, kMinShape);
    if (n0 == Vec3d{} || n1 == Vec3d{} || dot(n0, n1) <= 0) continue;
    mesh.faces[f->g] = f->t0;
    mesh.faces[f->h] = f->t1;
    touched[f->g] = touched[f->h] = 1;
    made.push_back(f->made);
    ++flipped;
  }
  return flipped;
}

}  // namespace hm::structured
