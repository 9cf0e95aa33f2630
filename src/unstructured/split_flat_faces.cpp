// Flat faces: a zipper or fan laid along a straight border (the transom's bottom edge where the
// two halves' keels of a full hull with a gap end on it) can make triangles whose three corners
// lie on one line. Such a face (a, b, c) either has c inside its longest side a-b, or two corners
// on one spot (a side of no length).
// - Inside: with the face across a-b, (b, a, d), it is replaced by (b, c, d) and (c, a, d): the
//   neighbour is split at c, as a T-junction is split, and the flat face goes.
// - No length: the side's two ends are welded, where they share no neighbour but the corners
//   across that side (the link condition, so the surface stays a manifold); its two faces lose
//   their area and go (drop_degenerate).
// The surface keeps its orientation. Faces are taken in index order, and passes repeat while
// any changes: a fan of flat faces is taken apart from its outside in.
//
// collect (flat faces, and which kind) -> select (the neighbour has area, the link condition
// holds, nothing around was changed in this pass) -> apply (split or weld, drop) -> again until
// nothing changes.
#include <algorithm>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <vector>

#include "core/parallel.h"
#include "mesh/adjacency.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

// A face no larger than this share of its longest side squared has no area (the quality
// report's and --validate's rule).
constexpr double kFlatRel = 1e-10;
// The corner must lie inside the longest side by at least this share of it: a corner on an end
// is a repeated position, which the split would only move to the neighbour.
constexpr double kInside = 1e-6;
constexpr int kMaxPasses = 64;

// The longest side of face t as its corner index k (side t[k] -> t[k + 1]), and whether t is
// flat with its third corner well inside that side.
bool flat_with_inside_corner(const SurfaceMesh& m, const Face& t, int& k) {
  double longest = -1;
  for (int c = 0; c < 3; ++c) {
    const double l = squared_norm(m.positions[t[(c + 1) % 3]] - m.positions[t[c]]);
    if (l > longest) longest = l, k = c;
  }
  if (!(longest > 0) || face_area(m.positions, t) > kFlatRel * longest) return false;
  const Vec3d& a = m.positions[t[k]];
  const Vec3d& b = m.positions[t[(k + 1) % 3]];
  const Vec3d& c = m.positions[t[(k + 2) % 3]];
  const double s = dot(c - a, b - a) / longest;
  return s > kInside && s < 1 - kInside;
}

// The side of flat face t whose ends lie on one spot (within kInside of its longest side), as
// its corner index k (side t[k] -> t[k + 1]); false when none.
bool flat_with_spot_side(const SurfaceMesh& m, const Face& t, int& k) {
  double longest = 0, shortest = std::numeric_limits<double>::infinity();
  for (int c = 0; c < 3; ++c) {
    const double l = squared_norm(m.positions[t[(c + 1) % 3]] - m.positions[t[c]]);
    longest = std::max(longest, l);
    if (l < shortest) shortest = l, k = c;
  }
  return longest > 0 && face_area(m.positions, t) <= kFlatRel * longest &&
         shortest <= kInside * kInside * longest;
}

// The vertices around each vertex (its faces' corners), sorted and unique: CSR.
void rings(const SurfaceMesh& m, std::vector<Index>& begin, std::vector<Index>& ring) {
  std::vector<std::pair<Index, Index>> pairs;
  pairs.reserve(6 * m.face_count());
  for (const Face& t : m.faces) {
    for (int c = 0; c < 3; ++c) {
      pairs.push_back({t[c], t[(c + 1) % 3]});
      pairs.push_back({t[(c + 1) % 3], t[c]});
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  begin.assign(m.vertex_count() + 1, 0);
  for (const auto& [v, u] : pairs) ++begin[v + 1];
  for (std::size_t v = 0; v < m.vertex_count(); ++v) begin[v + 1] += begin[v];
  ring.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) ring[i] = pairs[i].second;
}

}  // namespace

std::size_t split_flat_faces(Work& w, double length) {
  SurfaceMesh& m = w.mesh;
  // Most merges have none: a scan, and no adjacency built (the merge's cost is issue 4's goal).
  // The scan runs in blocks, each its own flag. A face with area (over kFlatRel of its longest
  // side squared) is neither kind of flat face, and only such a face's kind is asked: at 470,000
  // triangles the scan took 14 ms, serial and asking both kinds of every face.
  constexpr std::size_t kBlock = 4096;
  std::vector<std::uint8_t> block_has((m.face_count() + kBlock - 1) / kBlock, 0);
  parallel_for(
      0, block_has.size(),
      [&](std::size_t b) {
        const std::size_t end = std::min(m.face_count(), (b + 1) * kBlock);
        for (std::size_t f = b * kBlock; f < end; ++f) {
          const Face& t = m.faces[f];
          double longest = 0;
          for (int c = 0; c < 3; ++c) {
            longest =
                std::max(longest, squared_norm(m.positions[t[(c + 1) % 3]] - m.positions[t[c]]));
          }
          if (!(longest > 0) || face_area(m.positions, t) > kFlatRel * longest) continue;
          int k = 0;
          if (flat_with_spot_side(m, t, k) || flat_with_inside_corner(m, t, k)) {
            block_has[b] = 1;
            break;
          }
        }
      },
      1);
  if (std::none_of(block_has.begin(), block_has.end(), [](std::uint8_t h) { return h != 0; })) {
    return 0;
  }
  std::size_t total = 0;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
    std::vector<std::uint8_t> keep(m.face_count(), 1), touched(m.face_count(), 0);
    // Vertices of a split or round a weld in this pass: one change per neighbourhood a pass.
    std::vector<std::uint8_t> moved(m.vertex_count(), 0);
    std::vector<Index> onto(m.vertex_count());
    for (std::size_t v = 0; v < onto.size(); ++v) onto[v] = static_cast<Index>(v);
    std::vector<Index> ring_begin, ring;
    std::size_t done = 0, welded = 0;
    for (std::size_t f = 0; f < m.face_count(); ++f) {
      int k = 0;
      if (touched[f]) continue;
      if (flat_with_spot_side(m, m.faces[f], k)) {
        const Index g = adj.opposite_face[4 * f + static_cast<std::size_t>(k)];
        const Face& t = m.faces[f];
        const Index p = t[k], q = t[(k + 1) % 3];
        if (g == kInvalid || touched[g]) continue;
        if (ring.empty()) rings(m, ring_begin, ring);
        const auto around = [&](Index v) {
          return std::span<const Index>(ring.data() + ring_begin[v],
                                        ring_begin[v + 1] - ring_begin[v]);
        };
        // The rings were taken at the pass's start: nothing around may have changed since.
        const auto still = [&](Index v) {
          return !moved[v] && std::none_of(around(v).begin(), around(v).end(),
                                           [&](Index u) { return moved[u] != 0; });
        };
        if (!still(p) || !still(q)) continue;
        // Link condition: p and q share exactly the two corners across their side.
        std::vector<Index> common;
        std::set_intersection(around(p).begin(), around(p).end(), around(q).begin(),
                              around(q).end(), std::back_inserter(common));
        if (common.size() != 2) continue;
        onto[q] = p;
        for (Index v : {p, q}) {
          moved[v] = 1;
          for (Index u : around(v)) moved[u] = 1;
        }
        touched[f] = touched[g] = 1;
        ++welded;
        continue;
      }
      if (!flat_with_inside_corner(m, m.faces[f], k)) continue;
      const Index g = adj.opposite_face[4 * f + static_cast<std::size_t>(k)];
      if (g == kInvalid || touched[g]) continue;
      const Face& t = m.faces[f];
      const Index a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      // The neighbour runs b -> a; d is its third corner.
      const Face& u = m.faces[g];
      int j = 0;
      while (j < 3 && !(u[j] == b && u[(j + 1) % 3] == a)) ++j;
      if (j == 3) continue;  // run the same way: an inconsistent edge, left to the report
      const Index d = u[(j + 2) % 3];
      if (d == c || moved[a] || moved[b] || moved[c] || moved[d]) continue;
      int unused = 0;
      const Face split_b{b, c, d, kInvalid}, split_a{c, a, d, kInvalid};
      if (flat_with_inside_corner(m, u, unused) || face_area(m.positions, split_b) <= 0 ||
          face_area(m.positions, split_a) <= 0) {
        continue;
      }
      m.faces[g] = split_b;
      m.faces.push_back(split_a);
      m.face_patch.push_back(m.face_patch[g]);
      w.face_old.push_back(w.face_old[g]);
      keep.push_back(1);
      touched.push_back(1);
      keep[f] = 0;
      touched[f] = touched[g] = 1;
      for (Index v : {a, b, c, d}) moved[v] = 1;
      ++done;
    }
    if (done == 0 && welded == 0) break;
    compact_faces(w, keep);
    total += done;
    if (welded > 0) {
      for (Face& t : m.faces) {
        for (int c = 0; c < 3; ++c) t[c] = onto[t[c]];
      }
      total += drop_degenerate(w, length);
    }
  }
  return total;
}

}  // namespace hm::merge
