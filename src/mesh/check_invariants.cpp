#include "mesh/check_invariants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mesh/adjacency.h"

namespace hm {
namespace {

std::string at(const Vec3d& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "at (%.6g, %.6g, %.6g)", p.x, p.y, p.z);
  return buf;
}

// " (and N more)" when a break occurs more than once.
std::string more(std::size_t count) {
  return count > 1 ? " (and " + std::to_string(count - 1) + " more)" : std::string();
}

Vec3d edge_midpoint(const SurfaceMesh& m, const MeshEdge& e) {
  return 0.5 * (m.positions[e.v0] + m.positions[e.v1]);
}

// Sizes, index ranges, distinct corners and finite coordinates: what every later check relies on.
void check_indices(const SurfaceMesh& m, std::vector<InvariantBreak>& out) {
  const std::size_t nv = m.vertex_count(), nf = m.face_count();
  if (m.face_patch.size() != nf) {
    out.push_back({"provenance", std::to_string(m.face_patch.size()) + " source patches for " +
                                     std::to_string(nf) + " faces"});
  }
  if (!m.face_block.empty() && m.face_block.size() != nf) {
    out.push_back({"provenance", std::to_string(m.face_block.size()) + " block ids for " +
                                     std::to_string(nf) + " faces"});
  }
  if ((!m.vertex_patch.empty() && m.vertex_patch.size() != nv) ||
      (!m.vertex_uv.empty() && m.vertex_uv.size() != nv)) {
    out.push_back({"provenance", "per-vertex patch or (u, v) arrays do not match the " +
                                     std::to_string(nv) + " vertices"});
  }
  std::size_t bad_faces = 0, first_face = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const Face& face = m.faces[f];
    const int n = corner_count(face);
    bool bad = false;
    for (int k = 0; k < n; ++k) {
      bad = bad || face[k] >= nv;
      for (int j = 0; j < k; ++j) bad = bad || face[j] == face[k];
    }
    if (bad && bad_faces++ == 0) first_face = f;
  }
  if (bad_faces > 0) {
    out.push_back({"indices", "face " + std::to_string(first_face) +
                                  " names a missing vertex or one vertex twice" + more(bad_faces)});
  }
  std::size_t bad_points = 0, first_point = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const Vec3d& p = m.positions[v];
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) && bad_points++ == 0)
      first_point = v;
  }
  if (bad_points > 0) {
    out.push_back(
        {"finite", "vertex " + std::to_string(first_point) + " is not finite" + more(bad_points)});
  }
}

void check_edges(const SurfaceMesh& m, const EdgeAdjacency& adj, const InvariantOptions& o,
                 std::vector<InvariantBreak>& out) {
  if (o.manifold && !adj.nonmanifold_edges.empty()) {
    const MeshEdge& e = adj.edges[adj.nonmanifold_edges.front()];
    out.push_back({"manifold", "an edge with " + std::to_string(e.uses) + " faces " +
                                   at(edge_midpoint(m, e)) + more(adj.nonmanifold_edges.size())});
  }
  if (o.oriented && !adj.inconsistent_edges.empty()) {
    const MeshEdge& e = adj.edges[adj.inconsistent_edges.front()];
    out.push_back({"orientation", "two faces run the same way along the edge " +
                                      at(edge_midpoint(m, e)) +
                                      more(adj.inconsistent_edges.size())});
  }
  if (o.boundary_loops_in != std::numeric_limits<std::size_t>::max() &&
      adj.boundary_loops.size() != o.boundary_loops_in) {
    std::string where;
    if (!adj.boundary_loops.empty() && !adj.boundary_loops.front().vertices.empty())
      where = ", the first " + at(m.positions[adj.boundary_loops.front().vertices.front()]);
    out.push_back({"boundaries", std::to_string(adj.boundary_loops.size()) +
                                     " boundary loops where the input had " +
                                     std::to_string(o.boundary_loops_in) + where});
  }
}

void check_areas(const SurfaceMesh& m, const InvariantOptions& o,
                 std::vector<InvariantBreak>& out) {
  std::size_t count = 0, first = 0;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const Face& face = m.faces[f];
    const int n = corner_count(face);
    double longest = 0;
    for (int k = 0; k < n; ++k) {
      const Vec3d d = m.positions[face[(k + 1) % n]] - m.positions[face[k]];
      longest = std::max(longest, dot(d, d));
    }
    if (face_area(m.positions, face) <= o.zero_area_rel * longest && count++ == 0) first = f;
  }
  if (count > 0) {
    out.push_back({"zero-area", "face " + std::to_string(first) + " " +
                                    at(face_centroid(m.positions, m.faces[first])) +
                                    " has no area" + more(count)});
  }
}

void check_measures(const InvariantOptions& o, std::vector<InvariantBreak>& out) {
  char buf[160];
  if (o.max_deviation > 0 && !(o.deviation <= o.max_deviation)) {
    std::snprintf(buf, sizeof buf, "%.4g m from the NURBS, over the bound %.4g m, ", o.deviation,
                  o.max_deviation);
    out.push_back({"deviation", buf + at(o.deviation_where)});
  }
  if (o.feature_length_in > 0) {
    const double rel = o.feature_length_out / o.feature_length_in - 1;
    if (!(std::abs(rel) <= o.feature_rel_tol)) {
      std::snprintf(buf, sizeof buf,
                    "knuckle and boundary lines %.6g m long where the input's were %.6g m "
                    "(%+.3g%%, allowed %.3g%%)",
                    o.feature_length_out, o.feature_length_in, 100 * rel, 100 * o.feature_rel_tol);
      out.push_back({"features", buf});
    }
  }
}

}  // namespace

double edges_length(const SurfaceMesh& mesh, std::span<const std::array<Index, 2>> edges) {
  double length = 0;
  for (const auto& e : edges) length += norm(mesh.positions[e[1]] - mesh.positions[e[0]]);
  return length;
}

std::vector<InvariantBreak> find_invariant_breaks(const SurfaceMesh& mesh,
                                                  const InvariantOptions& options) {
  std::vector<InvariantBreak> out;
  check_indices(mesh, out);
  if (!out.empty()) return out;
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  check_edges(mesh, adj, options, out);
  if (options.no_zero_area) check_areas(mesh, options, out);
  check_measures(options, out);
  return out;
}

}  // namespace hm
