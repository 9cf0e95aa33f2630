// Small holes: where three or four patches meet at a corner, zipping their borders pairwise can
// leave a hole of one or two triangles' size. Closed boundary loops of 3 or 4 vertices that run
// along two or more patches are such holes (a true boundary of a hull is never that short); they
// are closed with one triangle or two (split along the shorter diagonal that is not an edge
// already). Longer loops (up to 16 vertices) are closed only when their perimeter is shorter than
// the longest edge of the faces along them: pinholes.
#include <algorithm>
#include <cstdint>
#include <set>

#include "mesh/adjacency.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {

namespace {

constexpr std::size_t kMaxHoleVertices = 16;

// A boundary loop that passes a vertex twice (a hole touching the hull's outline at one vertex)
// is several cycles; cut it there. Each cycle is (vertices, edges), edges[i] leaving vertices[i].
std::vector<std::pair<std::vector<Index>, std::vector<Index>>> cycles_of(const BoundaryLoop& loop) {
  std::vector<std::pair<std::vector<Index>, std::vector<Index>>> out;
  std::vector<Index> vs, es;
  for (std::size_t i = 0; i < loop.vertices.size(); ++i) {
    const Index v = loop.vertices[i];
    auto again = std::find(vs.begin(), vs.end(), v);
    if (again != vs.end()) {
      const std::ptrdiff_t at = again - vs.begin();
      out.push_back({std::vector<Index>(vs.begin() + at, vs.end()),
                     std::vector<Index>(es.begin() + at, es.end())});
      vs.resize(std::size_t(at));
      es.resize(std::size_t(at));
    }
    vs.push_back(v);
    es.push_back(loop.edges[i]);
  }
  out.push_back({std::move(vs), std::move(es)});
  return out;
}

}  // namespace

std::size_t fill_small_holes(Work& w, const EdgeAdjacency& adj) {
  SurfaceMesh& m = w.mesh;
  std::size_t filled = 0;
  // The mesh's edges as sorted keys, collected at the first hole of four vertices.
  std::vector<std::uint64_t> edge_keys;
  const auto is_edge = [&](Index a, Index b) {
    if (edge_keys.empty()) {
      edge_keys.reserve(adj.edges.size());
      for (const MeshEdge& e : adj.edges) edge_keys.push_back(std::uint64_t{e.v0} << 32 | e.v1);
      std::sort(edge_keys.begin(), edge_keys.end());
    }
    const std::uint64_t k = std::uint64_t{std::min(a, b)} << 32 | std::max(a, b);
    return std::binary_search(edge_keys.begin(), edge_keys.end(), k);
  };
  for (const BoundaryLoop& loop : adj.boundary_loops) {
    if (!loop.closed) continue;
    for (const auto& [r, edges] : cycles_of(loop)) {
      if (r.size() < 3 || r.size() > kMaxHoleVertices) continue;
      std::set<PatchId> patches;
      Index first_face = kInvalid;
      double perimeter = 0, local = 0;
      for (std::size_t i = 0; i < edges.size(); ++i) {
        const Index f = adj.edges[edges[i]].first_slot / 4;
        patches.insert(m.face_patch[f]);
        first_face = std::min(first_face, f);
        perimeter += norm(m.positions[r[(i + 1) % r.size()]] - m.positions[r[i]]);
        const Face& t = m.faces[f];
        for (int c = 0; c < 3; ++c) {
          local = std::max(local, norm(m.positions[t[(c + 1) % 3]] - m.positions[t[c]]));
        }
      }
      if (patches.size() < 2) continue;
      // Beyond four vertices only holes far smaller than the faces around them: pinholes left
      // where several short border edges met.
      if (r.size() > 4 && !(perimeter < local)) continue;
      // The loop follows its faces' winding, so the new faces run against it.
      std::vector<Face> add;
      if (r.size() == 3) {
        add.push_back({r[0], r[2], r[1], kInvalid});
      } else if (r.size() > 4) {
        // A pinhole: a fan from its first vertex (its shape is below the mesh's resolution).
        for (std::size_t i = 1; i + 1 < r.size(); ++i)
          add.push_back({r[0], r[i + 1], r[i], kInvalid});
      } else {
        // The shorter diagonal, unless it is an edge of the mesh already (the hole then folds
        // round it, and a third face would meet there).
        const bool d02 = !is_edge(r[0], r[2]), d13 = !is_edge(r[1], r[3]);
        if (!d02 && !d13) continue;
        if (d02 && (!d13 || norm(m.positions[r[0]] - m.positions[r[2]]) <=
                                norm(m.positions[r[1]] - m.positions[r[3]]))) {
          add.push_back({r[0], r[2], r[1], kInvalid});
          add.push_back({r[0], r[3], r[2], kInvalid});
        } else {
          add.push_back({r[1], r[3], r[2], kInvalid});
          add.push_back({r[1], r[0], r[3], kInvalid});
        }
      }
      for (const Face& f : add) {
        m.faces.push_back(f);
        m.face_patch.push_back(m.face_patch[first_face]);
        w.face_old.push_back(w.face_old[first_face]);
      }
      ++filled;
    }
  }
  return filled;
}

}  // namespace hm::merge
