#include "mesh/edge_flip.h"

#include <algorithm>

namespace hm {
namespace {

Index off_edge(const Face& f, Index a, Index b) {
  for (int k = 0; k < 3; ++k) {
    if (f[k] != a && f[k] != b) return f[k];
  }
  return kInvalid;
}

}  // namespace

Vec3d unit_triangle_normal(const SurfaceMesh& mesh, const Face& f, double min_shape) {
  const Vec3d &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &c = mesh.positions[f[2]];
  const Vec3d n = cross(b - a, c - a);
  const double longest = std::max({squared_norm(b - a), squared_norm(c - b), squared_norm(a - c)});
  const double len = norm(n);
  return len > min_shape * longest && len > 0 ? n / len : Vec3d{};
}

std::optional<EdgeFlip> edge_flip(const SurfaceMesh& mesh, const EdgeAdjacency& adj, Index e) {
  const MeshEdge& edge = adj.edges[e];
  if (edge.uses != 2 || edge.same_direction) return std::nullopt;
  EdgeFlip f;
  f.g = edge.first_slot / 4;
  f.h = adj.opposite_face[edge.first_slot];
  if (f.h == kInvalid || !is_triangle(mesh.faces[f.g]) || !is_triangle(mesh.faces[f.h])) {
    return std::nullopt;
  }
  const Face& g = mesh.faces[f.g];
  const Index a = g[edge.first_slot % 4], b = g[(edge.first_slot % 4 + 1) % 3];
  const Index c = off_edge(g, a, b), d = off_edge(mesh.faces[f.h], a, b);
  if (c == kInvalid || d == kInvalid || c == d || find_edge(adj, c, d) != kInvalid) {
    return std::nullopt;
  }
  f.t0 = {a, d, c, kInvalid};
  f.t1 = {d, b, c, kInvalid};
  f.made = {std::min(c, d), std::max(c, d)};
  return f;
}

}  // namespace hm
