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

#include "mesh/adjacency.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// Two unit normals this far from each other (cosine) are folded over: a turn past 120 degrees,
// which no panel code takes between neighbours off a knuckle.
constexpr double kFoldedCosine = -0.5;

// A triangle this flat (doubled area over its longest side squared) has no normal to speak of:
// two of its corners coincide or all three lie on a line, and another step deals with it.
constexpr double kMinShape = 1e-6;

// The unit normal of triangle f, or zero when it is that flat.
Vec3d unit_normal(const SurfaceMesh& mesh, const Face& f) {
  const Vec3d &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &c = mesh.positions[f[2]];
  const Vec3d n = cross(b - a, c - a);
  const double longest = std::max({squared_norm(b - a), squared_norm(c - b), squared_norm(a - c)});
  const double len = norm(n);
  return len > kMinShape * longest && len > 0 ? n / len : Vec3d{};
}

// The corner of triangle f that is neither a nor b.
Index off_edge(const Face& f, Index a, Index b) {
  for (int k = 0; k < 3; ++k) {
    if (f[k] != a && f[k] != b) return f[k];
  }
  return kInvalid;
}

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
    if (edge.uses != 2 || edge.same_direction) continue;
    const Index g = edge.first_slot / 4, h = adj.opposite_face[edge.first_slot];
    if (h == kInvalid || touched[g] || touched[h]) continue;
    if (knuckle[e] || !is_triangle(mesh.faces[g]) || !is_triangle(mesh.faces[h])) continue;
    const Vec3d ng = unit_normal(mesh, mesh.faces[g]), nh = unit_normal(mesh, mesh.faces[h]);
    if (ng == Vec3d{} || nh == Vec3d{} || dot(ng, nh) > kFoldedCosine) continue;
    // g runs a -> b along the edge, h b -> a; the flip's triangles (a, d, c) and (d, b, c) keep
    // the boundary a -> d -> b -> c of the pair.
    const Index a = mesh.faces[g][edge.first_slot % 4],
                b = mesh.faces[g][(edge.first_slot % 4 + 1) % 3];
    const Index c = off_edge(mesh.faces[g], a, b), d = off_edge(mesh.faces[h], a, b);
    const std::array<Index, 2> cd{std::min(c, d), std::max(c, d)};
    if (c == kInvalid || d == kInvalid || c == d || find_edge(adj, c, d) != kInvalid ||
        std::find(made.begin(), made.end(), cd) != made.end()) {
      continue;
    }
    const Face t0{a, d, c, kInvalid}, t1{d, b, c, kInvalid};
    const Vec3d n0 = unit_normal(mesh, t0), n1 = unit_normal(mesh, t1);
    if (n0 == Vec3d{} || n1 == Vec3d{} || dot(n0, n1) <= 0) continue;
    mesh.faces[g] = t0;
    mesh.faces[h] = t1;
    touched[g] = touched[h] = 1;
    made.push_back(cd);
    ++flipped;
  }
  return flipped;
}

}  // namespace hm::structured
