// Snap: border vertices of one patch meet the border of another vertex to vertex.
//
// collect the border -> for each border vertex, in parallel, measure its own patch's width there
// (its tolerance is at most half of it) and find the nearest border vertex and edge of other
// patches -> score welds (pair_welds.cpp: which pairs may weld) -> select welds (nearest first,
// never two vertices of one patch in a cluster) and splits (a vertex well inside another patch's
// edge) -> apply: average welded positions, move split vertices halfway onto the edge (or, where
// two patches meet at a knuckle across the gap, to the corner their surfaces make), replace each
// split triangle by a fan.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/parallel.h"
#include "kernels/weld.h"
#include "unstructured/merge_border.h"
#include "unstructured/merge_steps.h"
#include "unstructured/snap_rules.h"

namespace hm::merge {
namespace {

// A vertex whose nearest point on an edge is this close to an end (as a fraction of the edge)
// lies beyond that end.
constexpr double kBeyondEnd = 1e-3;
// ... and so does one whose nearest point is nearer an end than this share of its distance.
constexpr double kFacesEndShare = 0.25;
// ... unless the border goes on past that end within about 30 degrees of the edge: the vertex
// then lies across a straight run of a border finer than the gap is wide.
constexpr double kStraightCos = 0.866;

// Where the halves of a full hull meet in the centre plane (see kFoldCos in snap_rules.h), the
// vertex's own border edges run along the other border edge within about 25 degrees of it.
constexpr double kAlongCos = 0.9;
// ... or closer, where the vertex lies on the other edge's line (within this share of its
// length): the halves' borders are one curve there, as where a Wigley's stern meets its keel
// and the two halves close to nothing (the property test's seed 1121: its stern's two border
// runs, left apart, were filled by faces with no area).
constexpr double kOnLine = 1e-6;

// A border vertex moves at most this share of its own patch's width across a gap.
constexpr double kWidthShare = 0.5;
// Grid cells of this many median border edges: a vertex's search ball (tol / kWidthShare, one
// local border edge) then meets 8 cells, not 27.
constexpr double kGridMedianEdges = 2;

// A border vertex lies on the way another vertex of its border moved when it is within this
// share of the move from the straight line the move took (see collapse_overrun).
constexpr double kOnMove = 1e-3;

// Per border vertex, in one pass over the border edges near it:
//   - how wide its own patch is there: the distance to the nearest border edge of the same patch
//     that faces it from across the patch (inward directions more than 120 degrees apart, not an
//     edge of the vertex). Its tolerance is cut to kWidthShare of that: a strip narrower than the
//     gap tolerance (a transom cut into thin rows, a keel bar) would otherwise have both its
//     sides snap onto the same neighbour, or one side onto the patch beyond it;
//   - the nearest border edge of another patch, kept when it is within that tolerance.
// tol is the tolerance before the cut, and is cut in place.
std::vector<Split> nearest_edges(const SurfaceMesh& m, const Border& b, std::span<double> tol,
                                 std::span<const Vec3d> inward) {
  const SegmentGrid grid(m.positions, b.edges, 0, kGridMedianEdges);
  std::vector<Vec3d> edge_in(b.edges.size());
  parallel_for(0, b.edges.size(), [&](std::size_t e) { edge_in[e] = edge_inward(m, b.edges[e]); });
  std::vector<Split> out(b.vertices.size());
  parallel_for(0, b.vertices.size(), [&](std::size_t i) {
    const Index v = b.vertices[i];
    const Vec3d& p = m.positions[v];
    const PatchId pv = m.vertex_patch[v];
    // The width matters up to tol / kWidthShare; the nearest other edge, once found within that,
    // is the nearest within any smaller tolerance too.
    const double reach = tol[i] / kWidthShare;
    const double centre_reach = tol[i];  // of the centre plane, for the fold test's exceptions
    double width = reach;
    Split best;
    best.distance = std::numeric_limits<double>::infinity();
    // Other-patch edges refused by the fold test: kept apart until the vertex's own border
    // edges are known (the grid gives edges in no set order).
    Vec3d own[2];
    int own_count = 0;
    Split folded;
    folded.distance = std::numeric_limits<double>::infinity();
    grid.for_each_within(p, reach, [&](Index e) {
      const BorderEdge& be = b.edges[e];
      if (be.v0 == v || be.v1 == v) {
        if (be.patch == pv && own_count < 2) {
          own[own_count++] = m.positions[be.v0 == v ? be.v1 : be.v0] - p;
        }
        return;
      }
      if (be.patch == pv) {
        if (dot(edge_in[e], inward[i]) <= -kFoldCos && grid.may_be_within(e, p, width)) {
          width = std::min(width,
                           closest_on_segment(p, m.positions[be.v0], m.positions[be.v1]).distance);
        }
        return;
      }
      const bool fold = dot(edge_in[e], inward[i]) > kFoldCos;
      if (fold && !(std::abs(p.y) <= centre_reach && inward[i].y * edge_in[e].y < 0)) return;
      Split& slot = fold ? folded : best;
      if (!grid.may_be_within(e, p, slot.distance)) return;
      const Vec3d& a = m.positions[be.v0];
      const Vec3d& c = m.positions[be.v1];
      const SegmentPoint sp = closest_on_segment(p, a, c);
      if (fold) {
        const Vec3d wedge = inward[i] - edge_in[e];
        const double w = norm(wedge);
        if (!(w >= kWedgeMin) && !(sp.distance <= kOnLine * norm(c - a))) return;
        const Vec3d across = p - (a + sp.t * (c - a));
        if (!(sp.distance <= kOnEdgeShare * norm(c - a)) &&
            !(dot(across, wedge) >= kAcrossCos * norm(across) * w)) {
          return;
        }
      }
      if (sp.distance < slot.distance || (sp.distance == slot.distance && e < slot.edge)) {
        slot = {e, sp.t, sp.distance};
      }
    });
    if (folded.edge != kInvalid && folded.distance < best.distance && own_count == 2) {
      const BorderEdge& fe = b.edges[folded.edge];
      const Vec3d along = m.positions[fe.v1] - m.positions[fe.v0];
      const auto runs_along = [&](const Vec3d& d) {
        return std::abs(dot(d, along)) >= kAlongCos * norm(d) * norm(along);
      };
      if (runs_along(own[0]) && runs_along(own[1])) best = folded;
    }
    tol[i] = std::min(tol[i], kWidthShare * width);
    if (best.edge != kInvalid && best.distance <= tol[i]) out[i] = best;
  });
  return out;
}

}  // namespace

double vertex_tolerance(const MergeOptions& options, double border_edge_length) {
  return options.gap_tolerance > 0 ? options.gap_tolerance : 0.5 * border_edge_length;
}

// Each border vertex's border edges and its neighbours along them (border edges join vertices of
// one patch; the first two in edge order kept) and how many border edges meet there (more than
// two where the border touches itself). Built once per snap; the row walks and the straight-run
// test read it.
struct OwnBorder {
  std::vector<std::array<Index, 2>> edge;
  std::vector<std::array<Index, 2>> next;
  std::vector<std::uint8_t> degree;
};

OwnBorder own_border(const Border& b, std::span<const Index> local) {
  const std::size_t nb = b.vertices.size();
  OwnBorder o{std::vector<std::array<Index, 2>>(nb, {kInvalid, kInvalid}),
              std::vector<std::array<Index, 2>>(nb, {kInvalid, kInvalid}),
              std::vector<std::uint8_t>(nb, 0)};
  for (std::size_t k = 0; k < b.edges.size(); ++k) {
    const BorderEdge& e = b.edges[k];
    const Index u = local[e.v0], v = local[e.v1];
    if (o.degree[u] < 2) o.next[u][o.degree[u]] = v;
    if (o.degree[v] < 2) o.next[v][o.degree[v]] = u;
    ++o.degree[u];
    ++o.degree[v];
    for (const Index x : {u, v}) {
      auto& at = o.edge[x];
      if (at[0] == kInvalid) {
        at[0] = Index(k);
      } else if (at[1] == kInvalid) {
        at[1] = Index(k);
      }
    }
  }
  return o;
}

// A weld or a split moves a vertex along its own border past the neighbours it had there when a
// collapsed patch corner opened with a gap: the generated chine hulls' transom comes down to one
// point at the keel, and with a gap in the centre plane that point is a short row across the
// transom's foot. The snap takes the row's end at the keel (the bottom's corner) to the centre
// plane, back over the row, and the transom's faces on the row lay over the one beside it, in
// its plane (full chine hulls of 2 and 3 patches with 0.1 m gaps: 70-364 pairs of faces through
// each other; property seed 2143 in wide mode: 5 pairs of panels). The vertices passed over (the
// row) join the moved vertex, as they were one point in the clean hull; the faces between them
// then have a repeated corner and are dropped. Walks each moved vertex's border both ways while
// the next vertex's place before the snap lies on the straight way the vertex moved (within
// kOnMove of the move, ahead of where it started); serial in border order. `into` is the
// cluster representative per border vertex, updated; `moved_to` the place each will have. A
// cluster that is split into another patch's edge (`inserted`, by representative) stays.
void collapse_overrun(const OwnBorder& own, std::span<const Vec3d> before,
                      std::span<const Vec3d> moved_to, std::span<const std::uint8_t> inserted,
                      double floor, std::vector<Index>& into) {
  const std::size_t nb = own.degree.size();
  const auto& next = own.next;
  const auto& degree = own.degree;
  const auto find = [&](Index i) {
    while (into[i] != i) i = into[i] = into[into[i]];
    return i;
  };
  for (std::size_t k = 0; k < nb; ++k) {
    const Index i = Index(k);
    const Vec3d d = moved_to[i] - before[i];
    const double len2 = squared_norm(d);
    if (!(std::sqrt(len2) > floor) || degree[i] > 2) continue;
    for (Index start : next[i]) {
      Index prev = i, cur = start;
      while (cur != kInvalid && degree[cur] <= 2) {
        const Vec3d x = before[cur] - before[i];
        const double t = dot(x, d) / len2;
        if (!(t > 0 && t <= 1) || norm(x - t * d) > kOnMove * std::sqrt(len2)) break;
        const Index a = find(i), c = find(cur);
        if (a == c || inserted[c]) break;
        into[c] = a;
        const Index after = next[cur][0] == prev ? next[cur][1] : next[cur][0];
        prev = cur;
        cur = after;
      }
    }
  }
  for (std::size_t k = 0; k < nb; ++k) into[k] = find(Index(k));
}

// A welded vertex takes along a short row of its own border that nothing else pairs: where a
// patch's border has a corner collapsed to a point in the clean hull (the chines, keel and stem
// of a chine hull meeting at the bow), a gap opens that point into a row of short border edges
// (0.05 m of 10 vertices, each edge 5 mm, so each vertex's tolerance a few millimetres). The
// row's end at the keel welded to the other half's, the rest stayed, and the hole filler closed
// the slit between the two rows with faces square to the hull: a knot of 6 short knuckle lines
// at the bow of the generated full chine hull of 2 patches with 0.1 m gaps. Walks each welded
// vertex's border both ways over vertices that are not welded, not split into an edge and have
// no other patch's border within their tolerance, up to the first that is not such; when that
// one is not welded either, at least two lay between, and the row is no longer than the welded
// vertex's tolerance, the row and its end join the welded vertex. Serial, in border order.
void collapse_short_rows(const OwnBorder& own, std::span<const Vec3d> before,
                         std::span<const std::uint8_t> welded, std::span<const std::uint8_t> free,
                         std::span<const double> tol, std::vector<Index>& into) {
  const std::size_t nb = own.degree.size();
  const auto& next = own.next;
  const auto& degree = own.degree;
  std::vector<Index> row;
  for (std::size_t k = 0; k < nb; ++k) {
    const Index i = Index(k);
    if (!welded[i] || degree[i] > 2) continue;
    for (Index start : next[i]) {
      row.clear();
      double along = 0;
      Index prev = i, cur = start;
      while (cur != kInvalid && degree[cur] <= 2 && free[cur] && along <= tol[i]) {
        along += norm(before[cur] - before[prev]);
        row.push_back(cur);
        const Index after = next[cur][0] == prev ? next[cur][1] : next[cur][0];
        prev = cur;
        cur = after;
      }
      if (cur == kInvalid || cur == i || degree[cur] > 2 || welded[cur] || free[cur]) continue;
      along += norm(before[cur] - before[prev]);
      if (row.size() < 2 || !(along <= tol[i]) || into[cur] != cur) continue;
      row.push_back(cur);
      bool taken = false;
      for (Index r : row) taken = taken || into[r] != r;
      if (taken) continue;
      for (Index r : row) into[r] = into[i];
    }
  }
}

SnapStats snap_borders(Work& w, const Border& b, const MergeOptions& options, double length,
                       std::span<const double> tol_scale) {
  SurfaceMesh& m = w.mesh;
  const std::size_t nb = b.vertices.size();
  std::vector<double> tol(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    tol[i] = vertex_tolerance(options, b.edge_length[i]) * (tol_scale.empty() ? 1 : tol_scale[i]);
  }
  std::vector<Index> local(m.vertex_count(), kInvalid);  // mesh vertex -> border index
  for (std::size_t i = 0; i < nb; ++i) local[b.vertices[i]] = Index(i);
  const OwnBorder own = own_border(b, local);

  // Collect: nearest other-patch edge of every border vertex, within a tolerance that is at most
  // half its own patch's width there.
  const std::vector<Vec3d> inward = vertex_inward(m, b, local);
  const std::vector<Split> near = nearest_edges(m, b, tol, inward);

  // Score welds (pair_welds.cpp): which border vertices join which.
  std::vector<Vec3d> points(nb);
  std::vector<std::uint32_t> group(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    points[i] = m.positions[b.vertices[i]];
    group[i] = m.vertex_patch[b.vertices[i]];
  }
  const std::vector<ClosePair> pairs =
      weld_pairs(m, b, {tol, near, inward, points, group, local}, length);

  // Select welds.
  const std::vector<Index> rep = weld_clusters(nb, pairs, group);
  // Patches in each cluster (at its representative), to keep splits from folding a patch onto
  // itself.
  std::vector<std::vector<PatchId>> cluster_patches(nb);
  for (std::size_t i = 0; i < nb; ++i) cluster_patches[rep[i]].push_back(group[i]);
  for (auto& c : cluster_patches) std::sort(c.begin(), c.end());
  const auto in_cluster = [&](std::size_t i, PatchId p) {
    const auto& c = cluster_patches[rep[i]];
    return std::binary_search(c.begin(), c.end(), p);
  };

  SnapStats stats;
  const double closed_floor = 1e-9 * length;
  // True when the border goes on straight (within kStraightCos) past the end (v1 if at_v1) of
  // border edge e: a vertex facing that end faces a straight run of the border, not a corner.
  const auto runs_on_straight = [&](Index e, bool at_v1) {
    const BorderEdge& be = b.edges[e];
    const Index end = at_v1 ? be.v1 : be.v0;
    const auto& at = own.edge[local[end]];
    const Index next = at[0] == e ? at[1] : at[0];
    if (next == kInvalid || (at[0] != e && at[1] != e)) return false;
    const BorderEdge& ne = b.edges[next];
    const Vec3d into = m.positions[end] - m.positions[at_v1 ? be.v0 : be.v1];
    const Vec3d on = m.positions[ne.v0 == end ? ne.v1 : ne.v0] - m.positions[end];
    return dot(into, on) >= kStraightCos * norm(into) * norm(on);
  };
  // Select splits: a vertex inside an edge whose ends are not in its cluster.
  struct Insert {
    Index edge;
    double t;
    Index vertex;  // border index of the representative
    double distance;
  };
  std::vector<Insert> inserts;
  // The mesh's edges at border vertices, once per face using them, as they will be once the
  // welds are applied (sorted vertex pairs), to test a split against.
  const auto welded = [&](Index v) { return local[v] == kInvalid ? v : b.vertices[rep[local[v]]]; };
  std::vector<std::uint64_t> border_links;
  for (const Face& f : m.faces) {
    for (int c = 0; c < 3; ++c) {
      const Index u = f[c], v = f[(c + 1) % 3];
      if (local[u] == kInvalid && local[v] == kInvalid) continue;
      const Index wu = welded(u), wv = welded(v);
      border_links.push_back((std::uint64_t{std::min(wu, wv)} << 32) | std::max(wu, wv));
    }
  }
  parallel_sort(border_links.begin(), border_links.end(), std::less<>());
  const auto faces_at = [&](Index u, Index v) {
    const std::uint64_t key = (std::uint64_t{std::min(u, v)} << 32) | std::max(u, v);
    const auto range = std::equal_range(border_links.begin(), border_links.end(), key);
    return range.second - range.first;
  };
  for (std::size_t i = 0; i < nb; ++i) {
    const Split& s = near[i];
    if (s.edge == kInvalid) continue;
    const BorderEdge& e = b.edges[s.edge];
    if (in_cluster(i, e.patch)) continue;
    // Nearest at an end of the edge, or all but at it: the vertex lies beyond the edge, not on
    // it. It joins that end or nothing; a split there would give a face with three corners all
    // but in line. So does a vertex whose nearest point lies much nearer that end than the
    // vertex lies to the edge: it faces the end (a border running off at an angle from it), and
    // a split would stitch its own border onto the edge across that angle.
    const double from_end = std::min(s.t, 1 - s.t);
    const double edge_len = norm(m.positions[e.v1] - m.positions[e.v0]);
    if (from_end <= kBeyondEnd) continue;
    if (from_end * edge_len < kFacesEndShare * s.distance &&
        !runs_on_straight(s.edge, s.t >= 0.5)) {
      continue;
    }
    const Index r = rep[i];
    if (rep[local[e.v0]] == r || rep[local[e.v1]] == r) continue;
    // The split gives the edges from the vertex to both ends one more face. Where the welds have
    // already made such an edge interior (two faces: the vertex's neighbour on its own patch
    // welded to that end), it would get a third.
    if (faces_at(b.vertices[r], welded(e.v0)) >= 2 || faces_at(b.vertices[r], welded(e.v1)) >= 2) {
      continue;
    }
    inserts.push_back({s.edge, s.t, r, s.distance});
  }
  // A cluster enters each other patch's border once, at its nearest edge: two members near one
  // corner of that border would otherwise put it on two of its edges and fold the border.
  std::sort(inserts.begin(), inserts.end(), [&](const Insert& x, const Insert& y) {
    const PatchId px = b.edges[x.edge].patch, py = b.edges[y.edge].patch;
    if (x.vertex != y.vertex) return x.vertex < y.vertex;
    if (px != py) return px < py;
    return x.distance != y.distance ? x.distance < y.distance : x.edge < y.edge;
  });
  inserts.erase(std::unique(inserts.begin(), inserts.end(),
                            [&](const Insert& x, const Insert& y) {
                              return x.vertex == y.vertex &&
                                     b.edges[x.edge].patch == b.edges[y.edge].patch;
                            }),
                inserts.end());
  for (const Insert& in : inserts) {
    stats.widest = std::max(stats.widest, in.distance);
    if (in.distance > closed_floor) ++stats.gaps_closed;
  }
  // By face, then edge, then position along the edge: the order the splits are applied in.
  std::sort(inserts.begin(), inserts.end(), [&](const Insert& x, const Insert& y) {
    const Index fx = b.edges[x.edge].face, fy = b.edges[y.edge].face;
    if (fx != fy) return fx < fy;
    return x.edge != y.edge ? x.edge < y.edge : (x.t != y.t ? x.t < y.t : x.vertex < y.vertex);
  });
  std::vector<std::uint8_t> is_inserted(nb, 0);
  for (const Insert& in : inserts) is_inserted[in.vertex] = 1;

  // Apply welds: the representative takes the mean position of its cluster.
  std::vector<Vec3d> sum(nb, Vec3d{});
  std::vector<std::uint32_t> count(nb, 0);
  for (std::size_t i = 0; i < nb; ++i) {
    sum[rep[i]] += points[i];
    ++count[rep[i]];
  }
  std::vector<Index> vert_rep(m.vertex_count());
  for (std::size_t v = 0; v < vert_rep.size(); ++v) vert_rep[v] = Index(v);
  for (std::size_t i = 0; i < nb; ++i) {
    vert_rep[b.vertices[i]] = b.vertices[rep[i]];
    if (rep[i] != i) {
      ++stats.welded;
      // The gap is the distance across to the other border, not along it to the vertex joined.
      const double across = near[i].edge != kInvalid ? near[i].distance : 0.0;
      stats.widest = std::max(stats.widest, across);
      if (across > closed_floor) ++stats.gaps_closed;
    }
  }
  // A cluster of two (one vertex of each of two patches) closes at the corner the two make. At
  // three or more patches the planes are of a junction (a chine running into a seam with gaps in
  // both, a stem), whose corner the gaps leave too far from true to be worth the fold it risks.
  const std::vector<CornerSide> sides = corner_sides(m, b, local, inward);
  // True when border vertex i has no other patch's border nearer than patch q's: a corner is of
  // two patches, and a third between or beside them (an overlap's remnant strip along a chine,
  // the property test's seed 2122 in wide mode) is not in its planes.
  const auto faces_only = [&](Index i, PatchId q) {
    return near[i].edge == kInvalid || b.edges[near[i].edge].patch == q;
  };
  // Faces at each border vertex (count -> scan -> scatter), to test a corner against: a vertex
  // taken to the corner while its neighbours stay (receded, unpaired) may turn a face over (the
  // property test's seed 2143 in wide mode: a full chine hull's keel restored 0.03 m down at the
  // stem, under the slivers beside it). Built at the first corner: most snaps have none.
  std::vector<Index> face_start, faces_of;
  const auto index_faces = [&] {
    if (!face_start.empty()) return;
    face_start.assign(nb + 1, 0);
    for (const Face& f : m.faces) {
      for (int k = 0; k < 3; ++k) {
        if (local[f[k]] != kInvalid) ++face_start[local[f[k]] + 1];
      }
    }
    for (std::size_t i = 0; i < nb; ++i) face_start[i + 1] += face_start[i];
    faces_of.resize(face_start[nb]);
    std::vector<Index> fill(face_start.begin(), face_start.end() - 1);
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      for (int k = 0; k < 3; ++k) {
        if (local[m.faces[f][k]] != kInvalid) faces_of[fill[local[m.faces[f][k]]]++] = Index(f);
      }
    }
  };
  const auto points_before = [&](Index v) {
    return local[v] != kInvalid ? points[local[v]] : m.positions[v];
  };
  // True when no face at border vertex i turns by 90 degrees or more with i at x (the other
  // corners where they were before the snap).
  const auto keeps_facing = [&](Index i, const Vec3d& x) {
    index_faces();
    const Index v = b.vertices[i];
    for (Index k = face_start[i]; k < face_start[i + 1]; ++k) {
      const Face& f = m.faces[faces_of[k]];
      Vec3d q[3];
      for (int c = 0; c < 3; ++c) q[c] = f[c] == v ? x : points_before(f[c]);
      const Vec3d was = cross(points_before(f[1]) - points_before(f[0]),
                              points_before(f[2]) - points_before(f[0]));
      if (!(dot(cross(q[1] - q[0], q[2] - q[0]), was) > 0)) return false;
    }
    return true;
  };
  std::vector<Index> partner(nb, kInvalid);
  for (std::size_t i = 0; i < nb; ++i) {
    if (rep[i] != i && count[rep[i]] == 2) partner[rep[i]] = Index(i);
  }
  for (std::size_t i = 0; i < nb; ++i) {
    if (count[i] <= 1) continue;
    const Vec3d mean = sum[i] / double(count[i]);
    const Index j = partner[i];
    if (j == kInvalid) {
      m.positions[b.vertices[i]] = mean;
      continue;
    }
    if (!faces_only(Index(i), group[j]) || !faces_only(j, group[i])) {
      m.positions[b.vertices[i]] = mean;
      continue;
    }
    const double edge = std::min(b.edge_length[i], b.edge_length[j]);
    const Vec3d x = close_at_corner({sides[i], sides[j]}, mean, edge);
    m.positions[b.vertices[i]] =
        x != mean && keeps_facing(Index(i), x) && keeps_facing(j, x) ? x : mean;
  }
  // Split vertices that joined no cluster move halfway across the gap (each side gives half), or
  // to the corner the two sides make.
  for (std::size_t i = 0; i < nb; ++i) {
    const Split& s = near[i];
    if (s.edge == kInvalid || count[rep[i]] > 1) continue;
    if (!is_inserted[i]) continue;
    const BorderEdge& e = b.edges[s.edge];
    const Vec3d e0 = m.positions[e.v0], e1 = m.positions[e.v1];
    const Vec3d on_edge = e0 + s.t * (e1 - e0);
    const Vec3d mid = 0.5 * (points[i] + on_edge);
    m.positions[b.vertices[i]] = mid;
    if (!faces_only(local[e.v0], group[i]) || !faces_only(local[e.v1], group[i])) continue;
    // The edge's side: its face's plane, and its border running on both ways along the edge.
    const CornerSide across{on_edge,
                            face_normal(m.positions, m.faces[e.face]),
                            edge_inward(m, e),
                            {normalized(e0 - on_edge), normalized(e1 - on_edge)}};
    const double edge = std::min(b.edge_length[i], norm(e1 - e0));
    const Vec3d x = close_at_corner({sides[i], across}, mid, edge);
    if (x == mid) continue;
    // The edge's face becomes a fan from its third corner through x: both pieces keep facing.
    const Vec3d pa = m.positions[edge_apex(m, e)];
    const Vec3d was = cross(e1 - e0, pa - e0);
    if (dot(cross(x - e0, pa - e0), was) > 0 && dot(cross(e1 - x, pa - x), was) > 0 &&
        keeps_facing(Index(i), x)) {
      m.positions[b.vertices[i]] = x;
    }
  }
  {
    std::vector<Vec3d> moved_to(nb);
    for (std::size_t i = 0; i < nb; ++i) moved_to[i] = m.positions[b.vertices[rep[i]]];
    std::vector<Index> into(rep.begin(), rep.end());
    collapse_overrun(own, points, moved_to, is_inserted, closed_floor, into);
    // Free: not welded, not split into an edge, no edge of its split into (a row must not
    // collapse an edge that a split is about to cut) and no other patch's border near.
    std::vector<std::uint8_t> welded(nb), free(nb, 1);
    for (const Insert& in : inserts) {
      free[local[b.edges[in.edge].v0]] = 0;
      free[local[b.edges[in.edge].v1]] = 0;
    }
    for (std::size_t i = 0; i < nb; ++i) {
      welded[i] = count[rep[i]] > 1;
      free[i] = free[i] && !welded[i] && !is_inserted[i] && near[i].edge == kInvalid;
    }
    collapse_short_rows(own, points, welded, free, tol, into);
    for (std::size_t i = 0; i < nb; ++i) vert_rep[b.vertices[i]] = b.vertices[into[i]];
  }
  for (Face& f : m.faces) {
    for (int c = 0; c < 3; ++c) f[c] = vert_rep[f[c]];
  }

  // Apply splits: each split edge's triangle becomes a fan from its opposite corner; a triangle
  // with several split edges is split edge by edge, each time in the piece holding that edge.
  std::size_t k = 0;
  std::vector<Face> pieces;
  while (k < inserts.size()) {
    const Index face = b.edges[inserts[k].edge].face;
    pieces.assign(1, m.faces[face]);
    std::size_t end = k;
    while (end < inserts.size() && b.edges[inserts[end].edge].face == face) ++end;
    std::size_t q = k;
    while (q < end) {
      const Index edge = inserts[q].edge;
      std::vector<Index> mids;
      for (; q < end && inserts[q].edge == edge; ++q) {
        const Index v = b.vertices[inserts[q].vertex];
        if (mids.empty() || mids.back() != v) mids.push_back(v);
      }
      const Index a = vert_rep[b.edges[edge].v0], c = vert_rep[b.edges[edge].v1];
      for (std::size_t pi = 0; pi < pieces.size(); ++pi) {
        const Face f = pieces[pi];
        int at = -1;
        for (int s = 0; s < 3; ++s) {
          if (f[s] == a && f[(s + 1) % 3] == c) at = s;
        }
        if (at < 0) continue;
        const Index apex = f[(at + 2) % 3];
        std::vector<Index> chain{a};
        for (Index v : mids) {
          if (v != a && v != c && v != apex) chain.push_back(v);
        }
        chain.push_back(c);
        pieces.erase(pieces.begin() + std::ptrdiff_t(pi));
        for (std::size_t s = 0; s + 1 < chain.size(); ++s) {
          pieces.push_back({chain[s], chain[s + 1], apex, kInvalid});
        }
        stats.split += chain.size() - 2;
        break;
      }
    }
    m.faces[face] = pieces[0];
    for (std::size_t pi = 1; pi < pieces.size(); ++pi) {
      m.faces.push_back(pieces[pi]);
      m.face_patch.push_back(m.face_patch[face]);
      w.face_old.push_back(w.face_old[face]);
    }
    k = end;
  }
  return stats;
}

}  // namespace hm::merge
