// Flaps folded back over their neighbours, flipped flat. Where a thin slit between two patches
// is closed by a fan from one of its ends, and the other border's vertices lie a hair on the far
// side of the first border's edge, the fan's triangles come out turned against everything around
// them: dtmb5415.iges at 10,000-16,000 fine triangles, two triangles of patch 1 by the skeg
// (x = -2.01 m, y = 1 mm) folded over patch 0's border, one of them through a patch 0 face. A
// flap is a triangle turned against at least two of its three neighbours. Flipping its edge with
// the folded neighbour splits that neighbour at the flap's third corner, which is what the snap's
// T-junction split would have made; a fan of flaps takes one flip per pass.
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/parallel.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

// Two unit normals at least this far apart (cosine) are folded: a turn past 120 degrees.
constexpr double kFoldedCosine = -0.5;
// The flip's triangles face within 60 degrees of the good one's normal.
constexpr double kAgreeCosine = 0.5;
// A triangle this flat (twice its area over its longest side squared) has no normal to speak of.
constexpr double kMinShape = 1e-9;
// Flips of a fan run one per pass.
constexpr int kPasses = 8;

Vec3d unit_normal(const SurfaceMesh& mesh, const Face& f) {
  const Vec3d &a = mesh.positions[f[0]], &b = mesh.positions[f[1]], &c = mesh.positions[f[2]];
  const Vec3d n = cross(b - a, c - a);
  const double longest = std::max({squared_norm(b - a), squared_norm(c - b), squared_norm(a - c)});
  const double len = norm(n);
  return len > kMinShape * longest && len > 0 ? n / len : Vec3d{};
}

Index off_edge(const Face& f, Index a, Index b) {
  for (int k = 0; k < 3; ++k) {
    if (f[k] != a && f[k] != b) return f[k];
  }
  return kInvalid;
}

// One pass over the edges in order; each face flips at most once. Returns the flips.
std::size_t flip_pass(Work& w, const EdgeAdjacency& adj) {
  SurfaceMesh& m = w.mesh;
  std::vector<Vec3d> normal(m.face_count());
  parallel_for(0, m.face_count(), [&](std::size_t f) { normal[f] = unit_normal(m, m.faces[f]); });
  const auto turned = [&](Index f, Index g) {
    return normal[f] != Vec3d{} && normal[g] != Vec3d{} &&
           dot(normal[f], normal[g]) <= kFoldedCosine;
  };
  const auto flap = [&](Index f) {
    int against = 0;
    for (int k = 0; k < 3; ++k) {
      const Index g = adj.opposite_face[4 * f + k];
      against += g != kInvalid && turned(f, g);
    }
    return against >= 2;
  };
  std::vector<std::uint8_t> touched(m.face_count(), 0);
  std::vector<std::array<Index, 2>> made;  // edges the flips made, unknown to adj
  std::size_t flipped = 0;
  for (std::size_t e = 0; e < adj.edges.size(); ++e) {
    // collect: interior, consistently wound edges between two folded triangles, one a flap.
    const MeshEdge& edge = adj.edges[e];
    if (edge.uses != 2 || edge.same_direction) continue;
    const Index g = edge.first_slot / 4, h = adj.opposite_face[edge.first_slot];
    if (h == kInvalid || touched[g] || touched[h]) continue;
    if (!is_triangle(m.faces[g]) || !is_triangle(m.faces[h]) || !turned(g, h)) continue;
    // One of the two is the flap; the other lies in the surface around it.
    const bool flap_g = flap(g), flap_h = flap(h);
    if (flap_g == flap_h) continue;
    const Vec3d& n_good = flap_g ? normal[h] : normal[g];
    // g runs a -> b along the edge, h b -> a; the flip's triangles (a, d, c) and (d, b, c) keep
    // the pair's outline a -> d -> b -> c.
    const Index a = m.faces[g][edge.first_slot % 4], b = m.faces[g][(edge.first_slot % 4 + 1) % 3];
    const Index c = off_edge(m.faces[g], a, b), d = off_edge(m.faces[h], a, b);
    if (c == kInvalid || d == kInvalid || c == d) continue;
    const std::array<Index, 2> cd{std::min(c, d), std::max(c, d)};
    if (find_edge(adj, c, d) != kInvalid || std::find(made.begin(), made.end(), cd) != made.end()) {
      continue;
    }
    // select: the flip leaves two triangles that face as the good one does. A sharp edge of the
    // hull (a Wigley's foot, its two halves meeting at a few degrees, where a corner triangle of
    // a file with gaps and flipped patches has two neighbours across the edge) would be flipped
    // into triangles across the hull, facing neither half.
    const Face t0{a, d, c, kInvalid}, t1{d, b, c, kInvalid};
    const Vec3d n0 = unit_normal(m, t0), n1 = unit_normal(m, t1);
    if (n0 == Vec3d{} || n1 == Vec3d{} || dot(n0, n_good) < kAgreeCosine ||
        dot(n1, n_good) < kAgreeCosine) {
      continue;
    }
    // apply: each face keeps its slot, so its patch and input triangle.
    m.faces[g] = t0;
    m.faces[h] = t1;
    touched[g] = touched[h] = 1;
    made.push_back(cd);
    ++flipped;
  }
  return flipped;
}

}  // namespace

std::size_t flip_folded_flaps(Work& w, EdgeAdjacency& adj) {
  std::size_t total = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    const std::size_t flipped = flip_pass(w, adj);
    if (flipped == 0) break;
    total += flipped;
    adj = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  }
  return total;
}

}  // namespace hm::merge
