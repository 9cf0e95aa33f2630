// Bridging: a gap the snap could not close (wider than the border edges on each side, so that
// no vertex of one border comes near a vertex or inside an edge of the other) stays a long thin
// boundary loop along two or more patches. Such a loop is zipped shut: its two runs, from one
// end of the loop to the other, are joined by triangles, each time across the shorter of the two
// next diagonals (the classic zipper between two polylines).
//
// collect (closed loops along two or more patches, cut into simple cycles where they pass a
// vertex twice) -> score (mean width, twice the area over the perimeter, within the widest gap)
// -> select (the two ends: the vertex farthest from the centroid and the vertex farthest from
// it) -> apply (zip, refusing a diagonal that is an edge already or longer than kLongestDiagonal
// widths) -> the faces run against the loop, so the winding stays consistent. A cycle that is
// not zipped may hold notches, gaps that open onto it (close_notch), zipped from their apex.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>
#include <span>
#include <vector>

#include "mesh/adjacency.h"
#include "unstructured/merge_border.h"
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

// The widest angle at a notch's apex between the loop's two edges there, radians. (60 degrees
// until 2026-12-05: where the snap welds the tips of two patches' station borders at a half
// hull's keel, 0.1 m apart at 400,000 triangles, the notch left is a V of 62-64 degrees.)
const double kNotchApex = std::numbers::pi / 2;
// A notch face whose area is at most this times its longest side squared has none to speak of:
// where two borders run along one straight line (a stem) the loop turns back along it.
constexpr double kNotchFlat = 1e-3;

// The least cosine between a notch face and the face along the loop it joins (72 degrees): a
// gap's faces lie nearly in the surface on both sides, or across a knuckle between them; a lid
// across a sharp corner of the outline (a full hull's bow at the deck) stands square to them.
constexpr double kNotchAgree = 0.3;

// A notch whose width at the third vertex from its apex is at most this times its width at the
// first is a slit between two runs that stay side by side: a gap, whichever way its faces stand.
// Where a full hull's halves stand apart at a sharp stem (a Wigley hull with 0.1 m gaps at
// 40,000 triangles), the strip that closes the slit stands square to both sides, and the
// agreement test took it for a lid: 5 m of slit stayed open at each end, below the deck. A lid
// across a sharp corner of the outline widens step by step (1 : 2 : 3 at a bow's deck edge). A
// slit is zipped as a thin loop is (diagonals up to kLongestDiagonal widths: its runs' edges
// may be longer than it is wide) while each new vertex stays within `widest` of the other run
// and each new face agrees with the one before it (the strip turns no corner: at the slit's
// mouth the next face would lie across the deck).
constexpr double kSlitWidening = 1.5;

// Faces closing a notch of cycle r (its vertices in its faces' winding, edges[i] leaving r[i])
// at apex i: where a gap between two patches opens onto a boundary (the transom of a full hull
// whose halves stand apart meets the deck there), the loop runs into the gap and back out, and
// the gap is no closed loop of its own. From the apex the two runs are zipped outwards while the
// next diagonal is at most `widest` and no edge already, and each new face agrees with the face
// along the loop it joins (kNotchAgree; at a convex corner of a true boundary the first face
// would turn over, or stand as a lid). Empty when the apex is no such notch: the edges at it from
// one patch, an angle between them wider than kNotchApex, or the mouth wider than `widest`.
template <class IsEdge>
std::vector<Face> close_notch(const SurfaceMesh& m, const EdgeAdjacency& adj,
                              const std::vector<Index>& r, const std::vector<Index>& edges,
                              std::size_t i, double widest, std::span<const std::uint8_t> used,
                              IsEdge&& is_edge) {
  const std::size_t k = r.size();
  const auto face_of = [&](std::size_t e) { return adj.edges[edges[e % k]].first_slot / 4; };
  const Index f_in = face_of(i + k - 1), f_out = face_of(i);
  if (m.face_patch[f_in] == m.face_patch[f_out]) return {};
  // a[n] = r[i + n] (with the loop), b[n] = r[i - n] (against it); a[0] = b[0] is the apex.
  const auto a = [&](std::size_t n) { return r[(i + n) % k]; };
  const auto b = [&](std::size_t n) { return r[(i + k - n % k) % k]; };
  const auto width = [&](std::size_t n) { return norm(m.positions[a(n)] - m.positions[b(n)]); };
  if (k < 5 || !(width(1) <= widest)) return {};
  const bool slit = k >= 8 && width(3) <= kSlitWidening * width(1);
  const double reach = slit ? kLongestDiagonal * widest : widest;
  const auto ok = [&](Index u, Index v) {
    return !is_edge(u, v) && norm(m.positions[u] - m.positions[v]) <= reach;
  };
  // A slit's new vertex u within `widest` of the other run's edge v0 -> v1.
  const auto beside = [&](Index u, Index v0, Index v1) {
    return !slit ||
           closest_on_segment(m.positions[u], m.positions[v0], m.positions[v1]).distance <= widest;
  };
  if (!ok(a(1), b(1))) return {};
  std::vector<Face> out;
  const auto agrees = [&](const Face& add, Index along) {
    double longest = 0;
    for (int c = 0; c < 3; ++c) {
      longest = std::max(longest, norm(m.positions[add[(c + 1) % 3]] - m.positions[add[c]]));
    }
    if (!(face_area(m.positions, add) > kNotchFlat * longest * longest)) return false;
    const Vec3d n = face_normal(m.positions, add);
    if (!slit) return dot(n, face_normal(m.positions, m.faces[along])) > kNotchAgree;
    return out.empty() || dot(n, face_normal(m.positions, out.back())) > kNotchAgree;
  };
  // The loop turns back at the apex (within kNotchApex), not merely from one patch to the next
  // along a run.
  const Vec3d to_a = normalized(m.positions[a(1)] - m.positions[a(0)]);
  const Vec3d to_b = normalized(m.positions[b(1)] - m.positions[a(0)]);
  if (!(dot(to_a, to_b) >= std::cos(kNotchApex))) return {};
  const Face first{a(1), a(0), b(1), kInvalid};
  if (!agrees(first, f_in) || !agrees(first, f_out)) return {};
  out.push_back(first);
  std::size_t ia = 1, ib = 1;
  while (ia + ib + 2 < k) {
    // Step a joins the loop edge a[ia] -> a[ia + 1], step b the edge b[ib + 1] -> b[ib].
    const Face fa{a(ia + 1), a(ia), b(ib), kInvalid}, fb{b(ib), b(ib + 1), a(ia), kInvalid};
    // A vertex another notch's faces took is where this one's runs stop.
    const bool can_a = !used[a(ia + 1)] && ok(a(ia + 1), b(ib)) &&
                       beside(a(ia + 1), b(ib), b(ib + 1)) && agrees(fa, face_of(i + ia));
    const bool can_b = !used[b(ib + 1)] && ok(a(ia), b(ib + 1)) &&
                       beside(b(ib + 1), a(ia), a(ia + 1)) && agrees(fb, face_of(i + k - ib - 1));
    if (!can_a && !can_b) break;
    bool step_a = can_a;
    if (can_a && can_b) {
      step_a = norm(m.positions[a(ia + 1)] - m.positions[b(ib)]) <=
               norm(m.positions[a(ia)] - m.positions[b(ib + 1)]);
    }
    out.push_back(step_a ? fa : fb);
    (step_a ? ia : ib) += 1;
  }
  return out;
}

}  // namespace

std::size_t bridge_gaps(Work& w, const EdgeAdjacency& adj, double widest) {
  SurfaceMesh& m = w.mesh;
  std::set<std::uint64_t> added;  // edges of the faces added in this pass
  // The adjacency's edges are in key order, so a binary search finds one; until 2026-12-06 they
  // were copied and sorted again at every call (a tenth of the merge at 470,000 triangles).
  const auto is_edge = [&](Index u, Index v) {
    const std::uint64_t key = std::uint64_t{std::min(u, v)} << 32 | std::max(u, v);
    return find_edge(adj, u, v) != kInvalid || added.count(key) > 0;
  };
  std::size_t bridged = 0;
  std::vector<std::uint8_t> used(m.vertex_count(), 0);  // corners of the faces added
  const auto commit = [&](const std::vector<Face>& add, const std::vector<Index>& around) {
    for (const Face& f : add) {
      for (int c = 0; c < 3; ++c) {
        const Index u = f[c], v = f[(c + 1) % 3];
        added.insert(std::uint64_t{std::min(u, v)} << 32 | std::max(u, v));
        used[u] = 1;
      }
    }
    append_faces(w, add, around);
    ++bridged;
  };
  // Each apex of a notch in cycle r, once; a notch's faces touch no other's.
  const auto close_notches = [&](const std::vector<Index>& r, const std::vector<Index>& edges,
                                 const std::vector<Index>& around) {
    for (std::size_t i = 0; i < r.size(); ++i) {
      const std::size_t k = r.size();
      if (used[r[i]] || used[r[(i + 1) % k]] || used[r[(i + k - 1) % k]]) continue;
      const std::vector<Face> add = close_notch(m, adj, r, edges, i, widest, used, is_edge);
      if (!add.empty()) commit(add, around);
    }
  };
  for (const BoundaryLoop& loop : adj.boundary_loops) {
    if (!loop.closed) continue;
    // A loop that passes a vertex twice (holes touching at a corner) is zipped cycle by cycle.
    for (const auto& [r, edges] : cycles_of(loop)) {
      if (r.size() < 5) continue;
      std::set<PatchId> patches;
      std::vector<Index> around;  // the faces along the loop
      Vec3d centroid{0, 0, 0};
      for (Index v : r) centroid += m.positions[v] / double(r.size());
      double perimeter = 0, area2 = 0;
      for (std::size_t i = 0; i < r.size(); ++i) {
        const Index f = adj.edges[edges[i]].first_slot / 4;
        patches.insert(m.face_patch[f]);
        around.push_back(f);
        const Vec3d& p = m.positions[r[i]];
        const Vec3d& q = m.positions[r[(i + 1) % r.size()]];
        perimeter += norm(q - p);
        area2 += norm(cross(p - centroid, q - centroid));
      }
      if (patches.size() < 2 || !(perimeter > 0)) continue;
      // Mean width: twice the area over the perimeter (both runs counted), the area of the fan
      // from the centroid; or, where that is too wide, of the zipper's own faces. The fan
      // overstates a slit that bends round its centroid: the stem of a full round-bilge hull
      // whose halves stand 0.1 m apart, 2.6 m high and bent like a C, measured 0.43 m.
      const bool thin_fan = area2 / perimeter <= widest;
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
      std::vector<Face> add = zip(m, r, i0, j0, kLongestDiagonal * widest, is_edge);
      if (!add.empty() && !thin_fan) {
        double zipped2 = 0;  // twice the zipper's area
        for (const Face& f : add) zipped2 += 2 * face_area(m.positions, f);
        if (zipped2 / perimeter > widest) add.clear();
      }
      if (!add.empty()) {
        commit(add, around);
        continue;
      }
      close_notches(r, edges, around);
    }
  }
  return bridged;
}

}  // namespace hm::merge
