// Overlap remnants the cut left: the snap can lay a face of one patch on a face of another that
// it shares an edge with, both on the same side of that edge (a sliver of the higher patch that
// reached past the border of the lower one where several patch corners meet). The edge then has
// three faces, and the retries with a smaller tolerance do not undo it, since the two faces
// cover each other whatever the snap does. Of each such pair the remnant goes: the face with
// more boundary edges (it lies at the border of the overlap), then the higher-numbered patch's
// (the overlap rule: the lowest-numbered patch keeps what two cover). The same holds on an edge
// whose two faces run along it the same way (drop_inconsistent_remnants), where it is the
// orientation, not the face count, that the remnant spoils; there a face turned inside out
// against all its neighbours goes too.
//
// collect (faces on each edge with three faces or more) -> score (their directions away from the
// edge, their boundary edges) -> select (one face of each pair folded onto each other) -> apply
// (compact).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <tuple>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

// Two faces on one edge lie on each other when their directions away from it, across the edge,
// are within this angle.
const double kFoldCos = std::cos(20.0 * std::numbers::pi / 180.0);

// The unit direction from the edge (u, v) to the face's third corner, perpendicular to the edge,
// or zero when the face has no width there.
Vec3d away_from_edge(const SurfaceMesh& m, const Face& t, Index u, Index v) {
  Index w = kInvalid;
  for (int c = 0; c < 3; ++c) {
    if (t[c] != u && t[c] != v) w = t[c];
  }
  if (w == kInvalid) return {};
  const Vec3d& a = m.positions[u];
  const Vec3d e = m.positions[v] - a;
  const double ee = dot(e, e);
  if (!(ee > 0)) return {};
  const Vec3d d = m.positions[w] - a;
  const Vec3d across = d - (dot(d, e) / ee) * e;
  const double n = norm(across);
  return n > 0 ? across / n : Vec3d{};
}

// Of faces a and b lying on each other, the remnant: the one with more boundary edges (open_a,
// open_b), then the higher patch's, then the later face.
Index remnant_of(const SurfaceMesh& m, Index a, int open_a, Index b, int open_b) {
  return std::make_tuple(open_a, m.face_patch[a], a) > std::make_tuple(open_b, m.face_patch[b], b)
             ? a
             : b;
}

// A fold's two third corners are welded when they lie within this share of the folded edge's
// length of each other (measured: 1%), so that the weld moves the surface by a sliver's width.
constexpr double kFoldWeldShare = 0.1;

}  // namespace

FoldStats drop_folded_faces(Work& w, const EdgeAdjacency& adj) {
  FoldStats stats;
  if (adj.nonmanifold_edges.empty()) return stats;
  const SurfaceMesh& m = w.mesh;
  std::vector<std::uint8_t> nonmanifold(adj.edges.size(), 0), boundary(adj.edges.size(), 0);
  for (Index e : adj.nonmanifold_edges) nonmanifold[e] = 1;
  for (Index e : adj.boundary_edges) boundary[e] = 1;
  // (edge, face) for every use of an edge with three faces or more; each face's boundary edges.
  std::vector<std::pair<Index, Index>> uses;
  std::vector<std::uint8_t> open_edges(m.face_count(), 0);
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index e = adj.slot_edge[4 * f + c];
      if (e == kInvalid) continue;
      if (nonmanifold[e]) uses.emplace_back(e, Index(f));
      open_edges[f] += boundary[e];
    }
  }
  std::sort(uses.begin(), uses.end());
  std::vector<std::uint8_t> keep(m.face_count(), 1);
  for (std::size_t lo = 0; lo < uses.size();) {
    std::size_t hi = lo;
    while (hi < uses.size() && uses[hi].first == uses[lo].first) ++hi;
    const MeshEdge& edge = adj.edges[uses[lo].first];
    std::vector<Index> faces;
    for (std::size_t i = lo; i < hi; ++i) {
      if (keep[uses[i].second]) faces.push_back(uses[i].second);
    }
    std::vector<Vec3d> away(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) {
      away[i] = away_from_edge(m, m.faces[faces[i]], edge.v0, edge.v1);
    }
    std::size_t left = faces.size();
    for (std::size_t i = 0; i < faces.size() && left > 2; ++i) {
      for (std::size_t j = i + 1; j < faces.size() && left > 2; ++j) {
        const Index a = faces[i], b = faces[j];
        if (!keep[a] || !keep[b] || m.face_patch[a] == m.face_patch[b]) continue;
        if (!(dot(away[i], away[j]) >= kFoldCos)) continue;
        // The remnant: more boundary edges, then the higher patch, then the later face.
        const Index drop = remnant_of(m, a, open_edges[a], b, open_edges[b]);
        keep[drop] = 0;
        --left;
        ++stats.faces;
        stats.area += face_area(m.positions, m.faces[drop]);
      }
    }
    lo = hi;
  }
  if (stats.faces > 0) compact_faces(w, keep);
  return stats;
}

FoldStats drop_inconsistent_remnants(Work& w, const EdgeAdjacency& adj) {
  FoldStats stats;
  if (adj.inconsistent_edges.empty()) return stats;
  const SurfaceMesh& m = w.mesh;
  const auto open_edges = [&](Index f) {
    int n = 0;
    for (int c = 0; c < 3; ++c)
      n += adj.slot_edge[4 * f + c] != kInvalid && adj.edges[adj.slot_edge[4 * f + c]].uses == 1;
    return n;
  };
  // Turned against every face across its edges (two at least).
  const auto inverted = [&](Index f) {
    const Vec3d n = face_normal(m.positions, m.faces[f]);
    int across = 0, against = 0;
    for (int c = 0; c < 3; ++c) {
      const Index g = adj.opposite_face[4 * f + c];
      if (g == kInvalid) continue;
      ++across;
      against += dot(n, face_normal(m.positions, m.faces[g])) < 0;
    }
    return across >= 2 && against == across;
  };
  std::vector<std::uint8_t> keep(m.face_count(), 1);
  for (Index e : adj.inconsistent_edges) {
    // collect: the edge's two faces; score: on each other, or one inside out.
    const MeshEdge& edge = adj.edges[e];
    const Index a = edge.first_slot / 4, b = adj.opposite_face[edge.first_slot];
    if (b == kInvalid || !keep[a] || !keep[b]) continue;
    Index drop = kInvalid;
    const Vec3d away_a = away_from_edge(m, m.faces[a], edge.v0, edge.v1);
    const Vec3d away_b = away_from_edge(m, m.faces[b], edge.v0, edge.v1);
    if (m.face_patch[a] != m.face_patch[b] && dot(away_a, away_b) >= kFoldCos) {
      drop = remnant_of(m, a, open_edges(a), b, open_edges(b));
    } else if (const bool ia = inverted(a); ia != inverted(b)) {
      drop = ia ? a : b;
    }
    if (drop == kInvalid) continue;
    // apply
    keep[drop] = 0;
    ++stats.faces;
    stats.area += face_area(m.positions, m.faces[drop]);
  }
  if (stats.faces > 0) compact_faces(w, keep);
  return stats;
}

std::vector<std::pair<Index, Index>> folded_edge_welds(const Work& w, const EdgeAdjacency& adj) {
  const SurfaceMesh& m = w.mesh;
  std::vector<std::pair<Index, Index>> welds;
  // A face can be a sliver along one of its edges only if twice its area is under
  // kFoldWeldShare of its longest edge squared (its width over any edge is at least that share
  // of that edge). A flap, a wider face folded flat, faces against its neighbours across two or
  // more of its edges. Only edges between two thin faces, or between two faces whose normals are
  // within kFoldCos of opposite with one of them such a flap, are looked at.
  std::vector<std::uint8_t> thin(m.face_count(), 0);
  std::vector<Vec3d> normal(m.face_count());
  parallel_for(0, m.face_count(), [&](std::size_t f) {
    const Face& t = m.faces[f];
    const Vec3d &p = m.positions[t[0]], &q = m.positions[t[1]], &r = m.positions[t[2]];
    const double longest2 =
        std::max({squared_norm(q - p), squared_norm(r - q), squared_norm(p - r)});
    const Vec3d n = cross(q - p, r - p);
    const double twice_area = norm(n);
    thin[f] = twice_area < kFoldWeldShare * longest2;
    normal[f] = twice_area > 0 ? n / twice_area : Vec3d{};
  });
  const auto turned = [&](Index f, Index g) { return dot(normal[f], normal[g]) <= -kFoldCos; };
  // Asked only of faces already turned against one neighbour (a few in a merge).
  const auto flap = [&](Index f) { return is_flap(adj, f, turned); };
  std::vector<std::uint8_t> taken(m.vertex_count(), 0), inconsistent(adj.edges.size(), 0);
  for (Index e : adj.inconsistent_edges) inconsistent[e] = 1;
  // collect: interior edges wound consistently between two thin faces or two faces turned
  // against each other; score: the faces' directions away from the edge. Each edge's own flag,
  // in parallel (none depends on another's selection); the few kept are selected in edge order.
  std::vector<std::uint8_t> candidate(adj.edges.size(), 0);
  parallel_for(0, adj.edges.size(), [&](std::size_t e) {
    const MeshEdge& edge = adj.edges[e];
    if (edge.uses != 2 || inconsistent[e]) return;
    const Index a = edge.first_slot / 4, b = adj.opposite_face[edge.first_slot];
    if (b == kInvalid) return;
    if (!(thin[a] && thin[b]) && !(turned(a, b) && (flap(a) || flap(b)))) return;
    const Vec3d away_a = away_from_edge(m, m.faces[a], edge.v0, edge.v1);
    const Vec3d away_b = away_from_edge(m, m.faces[b], edge.v0, edge.v1);
    candidate[e] = dot(away_a, away_b) >= kFoldCos;
  });
  for (std::size_t e = 0; e < adj.edges.size(); ++e) {
    if (!candidate[e]) continue;
    const MeshEdge& edge = adj.edges[e];
    const Index a = edge.first_slot / 4, b = adj.opposite_face[edge.first_slot];
    const bool slivers = thin[a] && thin[b];
    // select: the third corners, near each other and in no other weld.
    Index c = kInvalid, d = kInvalid;
    for (int k = 0; k < 3; ++k) {
      if (m.faces[a][k] != edge.v0 && m.faces[a][k] != edge.v1) c = m.faces[a][k];
      if (m.faces[b][k] != edge.v0 && m.faces[b][k] != edge.v1) d = m.faces[b][k];
    }
    if (c == kInvalid || d == kInvalid || c == d || taken[c] || taken[d]) continue;
    const Vec3d& p0 = m.positions[edge.v0];
    const Vec3d along = m.positions[edge.v1] - p0;
    const double span = norm(along);
    const double most = kFoldWeldShare * span;
    const Vec3d apart = m.positions[c] - m.positions[d];
    if (!(norm(apart) < most)) continue;
    if (slivers) {
      // Both faces slivers along the edge, their corners near each other: a sharp stem whose
      // two halves meet at a few degrees (a Wigley's foot) has faces as wide as they are long,
      // and stays.
      const auto width = [&](Index x) { return norm(cross(along, m.positions[x] - p0)) / span; };
      if (!(width(c) < most && width(d) < most)) continue;
    }
    // Otherwise one face is a flap lying over the other upside down (property seed 4140: a
    // port face whose third corner was a keel vertex 0.08 m from the starboard face's, over the
    // starboard faces and turned against all three of them). A stem's two halves meeting at a
    // fraction of a degree (a full Wigley's foot) turn against each other across the stem only,
    // and stay.
    taken[c] = taken[d] = 1;
    welds.emplace_back(std::max(c, d), std::min(c, d));
  }
  return welds;
}

}  // namespace hm::merge
