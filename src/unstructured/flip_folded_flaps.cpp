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
#include <optional>
#include <vector>

#include "core/parallel.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "mesh/edge_flip.h"
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

// One pass over the edges in order; each face flips at most once. Returns the flips.
std::size_t flip_pass(Work& w, const EdgeAdjacency& adj) {
  SurfaceMesh& m = w.mesh;
  std::vector<Vec3d> normal(m.face_count());
  parallel_for(0, m.face_count(),
               [&](std::size_t f) { normal[f] = unit_triangle_normal(m, m.faces[f], kMinShape); });
  const auto turned = [&](Index f, Index g) {
    return normal[f] != Vec3d{} && normal[g] != Vec3d{} &&
           dot(normal[f], normal[g]) <= kFoldedCosine;
  };
  const auto flap = [&](Index f) { return is_flap(adj, f, turned); };
  std::vector<std::uint8_t> touched(m.face_count(), 0);
  std::vector<std::array<Index, 2>> made;  // edges the flips made, unknown to adj
  std::size_t flipped = 0;
  // collect: interior, consistently wound edges between two folded triangles, one a flap. The
  // fold is read from the normals as the pass began, so each edge's flag is its own, found in
  // parallel; the few flagged are flipped in edge order.
  std::vector<std::uint8_t> folded(adj.edges.size(), 0);
  parallel_for(0, adj.edges.size(), [&](std::size_t e) {
    const MeshEdge& edge = adj.edges[e];
    const Index g = adj.opposite_face[edge.first_slot];
    folded[e] = edge.uses == 2 && g != kInvalid && turned(edge.first_slot / 4, g);
  });
  for (std::size_t e = 0; e < adj.edges.size(); ++e) {
    if (!folded[e]) continue;
    const std::optional<EdgeFlip> f = edge_flip(m, adj, static_cast<Index>(e));
    if (!f || touched[f->g] || touched[f->h]) continue;
    // One of the two is the flap; the other lies in the surface around it.
    const bool flap_g = flap(f->g), flap_h = flap(f->h);
    if (flap_g == flap_h) continue;
    const Vec3d& n_good = flap_g ? normal[f->h] : normal[f->g];
    if (std::find(made.begin(), made.end(), f->made) != made.end()) continue;
    // select: the flip leaves two triangles that face as the good one does. A sharp edge of the
    // hull (a Wigley's foot, its two halves meeting at a few degrees, where a corner triangle of
    // a file with gaps and flipped patches has two neighbours across the edge) would be flipped
    // into triangles across the hull, facing neither half.
    const Vec3d n0 = unit_triangle_normal(m, f->t0, kMinShape),
                n1 = unit_triangle_normal(m, f->t1, kMinShape);
    if (n0 == Vec3d{} || n1 == Vec3d{} || dot(n0, n_good) < kAgreeCosine ||
        dot(n1, n_good) < kAgreeCosine) {
      continue;
    }
    // apply: each face keeps its slot (t0 g's, t1 h's), so its patch and input triangle.
    m.faces[f->g] = f->t0;
    m.faces[f->h] = f->t1;
    touched[f->g] = touched[f->h] = 1;
    made.push_back(f->made);
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
