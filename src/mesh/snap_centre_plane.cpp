#include "mesh/snap_centre_plane.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "mesh/adjacency.h"

namespace hm {

std::size_t snap_to_centre_plane(SurfaceMesh& mesh, double tol, bool slivers) {
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
  // A face on the open side (a side of it on the plane, with no other face off the plane) whose
  // other corners lie within tol of the plane, so near it that its mirror image's centre would
  // come within a twentieth of its size of its own (the quality report's "very close" rule,
  // which panel codes refuse): its corners go onto the plane as well, and
  // drop_centre_plane_faces removes it. A fine stem meeting the waterline aft of a raked
  // forefoot leaves such a sliver between the last station and the stem (property seed 1987:
  // 3 cm off the plane, panels of 2.3 m).
  if (!slivers) return moved;
  const auto on_plane = [&](Index v) { return mesh.positions[v].y == 0; };
  const auto in_plane = [&](const Face& f) {
    for (int c = 0; c < corner_count(f); ++c)
      if (!on_plane(f[c])) return false;
    return true;
  };
  std::map<std::pair<Index, Index>, int> users;  // a side on the plane: faces off it using it
  const auto for_plane_sides = [&](const Face& f, auto&& visit) {
    const int n = corner_count(f);
    for (int c = 0; c < n; ++c) {
      const Index a = f[c], b = f[(c + 1) % n];
      if (on_plane(a) && on_plane(b)) visit(std::pair{std::min(a, b), std::max(a, b)});
    }
  };
  for (const Face& f : mesh.faces)
    if (!in_plane(f)) for_plane_sides(f, [&](const auto& side) { ++users[side]; });
  std::vector<Index> sliver;
  for (std::size_t fi = 0; fi < mesh.faces.size(); ++fi) {
    const Face& f = mesh.faces[fi];
    if (in_plane(f)) continue;
    bool open = false;
    for_plane_sides(f, [&](const auto& side) { open = open || users[side] == 1; });
    if (!open) continue;
    bool near = true;
    for (int c = 0; c < corner_count(f); ++c)
      near = near && std::abs(mesh.positions[f[c]].y) <= tol;
    const double size = std::sqrt(face_area(mesh.positions, f));
    if (near && 2 * std::abs(face_centroid(mesh.positions, f).y) < kCloseCentreFraction * size)
      sliver.push_back(static_cast<Index>(fi));
  }
  for (Index fi : sliver) {
    const Face& f = mesh.faces[fi];
    for (int c = 0; c < corner_count(f); ++c) {
      double& y = mesh.positions[f[c]].y;
      if (y != 0) {
        y = 0;
        ++moved;
      }
    }
  }
  return moved;
}

std::size_t drop_centre_plane_faces(SurfaceMesh& mesh) {
  std::vector<std::uint8_t> keep(mesh.faces.size(), 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    bool on_plane = true;
    for (int c = 0; c < corner_count(face); ++c)
      on_plane = on_plane && mesh.positions[face[c]].y == 0;
    keep[f] = on_plane ? 0 : 1;
  }
  return keep_faces(mesh, keep);
}

}  // namespace hm
