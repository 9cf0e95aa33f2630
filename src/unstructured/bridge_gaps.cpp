// Bridging: a gap the snap could not close (wider than the border edges on each side, so that
// no vertex of one border comes near a vertex or inside an edge of the other) stays a long thin
// boundary loop along two or more patches. Such a loop is zipped shut: its two runs, from one
// end of the loop to the other, are joined by triangles, each time across the shorter of the two
// next diagonals (the classic zipper between two polylines).
//
// collect (closed loops along two or more patches, each vertex once) -> score (mean width, twice
// the area over the perimeter, within the widest gap) -> select (the two ends: the vertex
// farthest from the centroid and the vertex farthest from it) -> apply (zip, refusing a diagonal
// that is an edge already or longer than kLongestDiagonal widths) -> the faces run against the
// loop, so the winding stays consistent.
#include <algorithm>
#include <cstdint>
#include <set>

#include "mesh/adjacency.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

// A diagonal longer than this many times the widest gap is across something other than a gap.
constexpr double kLongestDiagonal = 4;

// Faces zipping loop r shut between its ends i0 and j0, or empty when a diagonal would be an edge
// already or too long. The loop runs in its faces' winding; the new faces run against it.
template <class IsEdge>
std::vector<Face> zip(const SurfaceMesh& m, const std::vector<Index>& r, std::size_t i0,
                      std::size_t j0, double longest, IsEdge&& is_edge) {
  const std::size_t k = r.size();
  std::vector<Index> a, b;  // both from r[i0] to r[j0]: a along the loop, b against it
  for (std::size_t i = i0;; i = (i + 1) % k) {
    a.push_back(r[i]);
    if (i == j0) break;
  }
  for (std::size_t i = i0;; i = (i + k - 1) % k) {
    b.push_back(r[i]);
    if (i == j0) break;
  }
  if (a.size() < 3 || b.size() < 3) return {};
  const auto ok = [&](Index u, Index v) {
    return !is_edge(u, v) && norm(m.positions[u] - m.positions[v]) <= longest;
  };
  std::vector<Face> out;
  if (!ok(a[1], b[1])) return {};
  out.push_back({a[1], a[0], b[1], kInvalid});
  std::size_t ia = 1, ib = 1;
  const std::size_t last_a = a.size() - 2, last_b = b.size() - 2;
  while (ia < last_a || ib < last_b) {
    // Step a: diagonal a[ia + 1] - b[ib]; step b: diagonal a[ia] - b[ib + 1].
    const bool can_a = ia < last_a && ok(a[ia + 1], b[ib]);
    const bool can_b = ib < last_b && ok(a[ia], b[ib + 1]);
    if (!can_a && !can_b) return {};
    bool step_a = can_a;
    if (can_a && can_b) {
      step_a = norm(m.positions[a[ia + 1]] - m.positions[b[ib]]) <=
               norm(m.positions[a[ia]] - m.positions[b[ib + 1]]);
    }
    if (step_a) {
      out.push_back({a[ia + 1], a[ia], b[ib], kInvalid});
      ++ia;
    } else {
      out.push_back({b[ib], b[ib + 1], a[ia], kInvalid});
      ++ib;
    }
  }
  out.push_back({a.back(), a[ia], b[ib], kInvalid});
  return out;
}

}  // namespace

std::size_t bridge_gaps(Work& w, const EdgeAdjacency& adj, double widest) {
  SurfaceMesh& m = w.mesh;
  std::vector<std::uint64_t> edge_keys;
  edge_keys.reserve(adj.edges.size());
  for (const MeshEdge& e : adj.edges) edge_keys.push_back(std::uint64_t{e.v0} << 32 | e.v1);
  std::sort(edge_keys.begin(), edge_keys.end());
  std::set<std::uint64_t> added;  // edges of the faces added in this pass
  const auto is_edge = [&](Index u, Index v) {
    const std::uint64_t key = std::uint64_t{std::min(u, v)} << 32 | std::max(u, v);
    return std::binary_search(edge_keys.begin(), edge_keys.end(), key) || added.count(key) > 0;
  };
  std::size_t bridged = 0;
  for (const BoundaryLoop& loop : adj.boundary_loops) {
    const std::vector<Index>& r = loop.vertices;
    if (!loop.closed || r.size() < 5) continue;
    std::vector<Index> sorted = r;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) continue;
    std::set<PatchId> patches;
    std::vector<Index> around;  // the faces along the loop
    Vec3d centroid{0, 0, 0};
    for (Index v : r) centroid += m.positions[v] / double(r.size());
    double perimeter = 0, area2 = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const Index f = adj.edges[loop.edges[i]].first_slot / 4;
      patches.insert(m.face_patch[f]);
      around.push_back(f);
      const Vec3d& p = m.positions[r[i]];
      const Vec3d& q = m.positions[r[(i + 1) % r.size()]];
      perimeter += norm(q - p);
      area2 += norm(cross(p - centroid, q - centroid));
    }
    // Mean width: twice the area over the perimeter, area2 / perimeter (both runs counted).
    if (patches.size() < 2 || !(perimeter > 0) || area2 / perimeter > widest) continue;
    std::size_t i0 = 0, j0 = 0;
    double far = -1;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const double d = norm(m.positions[r[i]] - centroid);
      if (d > far) far = d, i0 = i;
    }
    far = -1;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const double d = norm(m.positions[r[i]] - m.positions[r[i0]]);
      if (d > far) far = d, j0 = i;
    }
    const std::vector<Face> add = zip(m, r, i0, j0, kLongestDiagonal * widest, is_edge);
    if (add.empty()) continue;
    for (const Face& f : add) {
      for (int c = 0; c < 3; ++c) {
        const Index u = f[c], v = f[(c + 1) % 3];
        added.insert(std::uint64_t{std::min(u, v)} << 32 | std::max(u, v));
      }
    }
    append_faces(w, add, around);
    ++bridged;
  }
  return bridged;
}

}  // namespace hm::merge
