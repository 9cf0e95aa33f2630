// Score welds: which border vertices of different patches weld (see snap_rules.h). Close pairs
// from the weld kernel, each held to the tolerances and the rules below, and a vertex near an
// end of its nearest other-patch edge with that end.
#include <algorithm>
#include <cmath>
#include <limits>

#include "unstructured/merge_steps.h"
#include "unstructured/snap_rules.h"

namespace hm::merge {
namespace {

// A third patch lies between two close border vertices when each is within this share of their
// distance from its border and heads into it within 60 degrees.
constexpr double kBetweenShare = 0.5;
constexpr double kIntoCos = 0.5;
// The way between two border vertices runs along their surfaces' normals within 45 degrees.
constexpr double kThroughCos = 0.7;
// A way through a hull that long (share of the hull's length) is its thickness, not a step.
constexpr double kThickness = 1e-3;
// A border vertex lies on another patch's border when within this share of a pair's distance.
constexpr double kHeldShare = 0.1;

}  // namespace

std::vector<ClosePair> weld_pairs(const SurfaceMesh& m, const Border& b, const BorderView& v,
                                  double length) {
  const std::size_t nb = b.vertices.size();
  const std::span<const double> tol = v.tol;
  const std::span<const Split> near = v.near;
  const std::span<const Vec3d> inward = v.inward, points = v.points;
  const std::span<const std::uint32_t> group = v.group;
  const std::span<const Index> local = v.local;
  double reach = 0;
  for (std::size_t i = 0; i < nb; ++i) reach = std::max(reach, tol[i]);
  std::vector<ClosePair> pairs;
  const double coincident_tol = 1e-9 * length;
  // True when border vertices i and j both lie near the border of one third patch (within
  // kBetweenShare of their distance) and the way from each to the other goes into that patch
  // (within 60 degrees of its inward direction): the patch lies between them.
  const auto across_third_patch = [&](Index i, Index j) {
    const Split &si = near[i], &sj = near[j];
    if (si.edge == kInvalid || sj.edge == kInvalid) return false;
    const PatchId c = b.edges[si.edge].patch;
    if (b.edges[sj.edge].patch != c || c == group[i] || c == group[j]) return false;
    const Vec3d ij = points[j] - points[i];
    const double d = norm(ij);
    if (!(si.distance <= kBetweenShare * d && sj.distance <= kBetweenShare * d)) return false;
    return dot(ij, edge_inward(m, b.edges[si.edge])) > kIntoCos * d &&
           dot(-ij, edge_inward(m, b.edges[sj.edge])) > kIntoCos * d;
  };
  // True when border vertex i lies on another patch's border edge (within kHeldShare of its
  // distance to j) that j lies off (farther than half that distance from the edge's line) and
  // is not of: a weld would take i off the border it closes on. The clean full round-bilge hull
  // of 300 patches has a transom strip 0.1-0.14 m tall along the transom's foot; a vertex of the
  // transom patch above it, on the strip's upper border, welded to the bottom's corner below
  // it, across the strip (each lay on the border of a different patch, so the strip was no
  // third patch between them), and the strip's faces passed through the transom's.
  const auto held_off = [&](Index i, Index j) {
    const Split& si = near[i];
    if (si.edge == kInvalid) return false;
    const BorderEdge& e = b.edges[si.edge];
    if (e.patch == group[j]) return false;
    const double d = norm(points[j] - points[i]);
    if (!(si.distance <= kHeldShare * d)) return false;
    if (!(closest_on_segment(points[j], m.positions[e.v0], m.positions[e.v1]).distance > 0.5 * d)) {
      return false;
    }
    return dot(points[j] - points[i], edge_inward(m, e)) > kIntoCos * d;
  };
  // Per border vertex, its surface's normal (up to sign: patches may arrive flipped), from the
  // faces along its border edges.
  std::vector<Vec3d> normal(nb, Vec3d{});
  for (const BorderEdge& e : b.edges) {
    const Vec3d n = normalized(face_normal(m.positions, m.faces[e.face]));
    if (!is_finite(n)) continue;
    normal[local[e.v0]] += n;
    normal[local[e.v1]] += n;
  }
  // True when the way between border vertices i and j runs through the hull's thickness: along
  // both their surfaces' normals (within 45 degrees), over more than kEndFraction of their border
  // edges or kThickness of the hull's length (a step between two patches that continue each
  // other is a chord error, far less: kcs.iges's, 1.9 mm across, is 2.5e-4 L). A
  // full Wigley of 100 patches is 0.17 m thick near its forefoot (x = 4 m), where a seam between
  // two patches crosses each side; each side's seam vertices welded to the other side's across
  // the thickness (inward directions opposite, as of two borders that continue each other), and
  // the forefoot was pinched onto the centre plane: 9 knuckle lines of 118.3 m on the clean
  // hull, where its stem, keel and stern post make 1 of 115.6. At 300 patches its stem is 0.19 m
  // thick at the seams, under 0.3 of their border edges of 0.9 m (5 lines, where it has 1).
  const auto through_thickness = [&](Index i, Index j) {
    const Vec3d ij = points[j] - points[i];
    const double d = norm(ij);
    if (!(d > std::min(kEndFraction * std::min(b.edge_length[i], b.edge_length[j]),
                       kThickness * length))) {
      return false;
    }
    const auto along = [&](Index k) {
      const double n = norm(normal[k]);
      return n > 0 && std::abs(dot(ij, normal[k])) >= kThroughCos * d * n;
    };
    return along(i) && along(j);
  };
  // True when border vertices i and j are the two halves of a full hull, each within its
  // tolerance of the centre plane, leaving it to either side at least kWedgeMin apart, the one
  // across the wedge from the other (as nearest_edges lets an edge through the fold test): a fine
  // stem's top corners at the deck, a gap apart, whose borders turn there into the deck edge so
  // that no edge of the other lies across. Where the two leave the plane less than kWedgeMin
  // apart, back to back as a fin (a Wigley's stern post near the keel), the wedge gives no
  // direction and the way between them must cross the plane instead (within 45 degrees of y):
  // the full Wigley of 6 patches with 0.1 m gaps left its halves 0.016-0.023 m apart there
  // (edges of 0.24 m, so no touching pair either), and the slit's fill made a second line. Such
  // a pair must not lie through the hull's thickness: a Wigley's two deck edges near the stem,
  // 0.39 m apart, leave the plane back to back too, and welding them pinched the deck.
  const auto across_wedge = [&](Index i, Index j) {
    if (!(std::abs(points[i].y) <= tol[i] && std::abs(points[j].y) <= tol[j])) return false;
    if (!(inward[i].y * inward[j].y < 0)) return false;
    const Vec3d wedge = inward[i] - inward[j];
    const double w = norm(wedge);
    const Vec3d across = points[i] - points[j];
    const double d = norm(across);
    // Neither lies on (or near) another patch's border: it belongs there, not on its mirror.
    const auto clear = [&](Index k) {
      return near[k].edge == kInvalid || near[k].distance >= 0.5 * d;
    };
    if (!clear(i) || !clear(j)) return false;
    if (w >= kWedgeMin) return dot(across, wedge) >= kAcrossCos * d * w;
    return std::abs(across.y) >= kAcrossCos * d && !through_thickness(i, j);
  };
  if (nb > 1 && reach > 0) {
    const std::vector<ClosePair> close = find_close_pairs(points, group, reach);
    // A weld is held to a share of the edges at its ends (kEndFraction of twice them), so that it
    // leaves no sliver and a border does not weld along itself in a chain, except between two
    // vertices that are each other's nearest of another patch: they weld up to the tolerance, the
    // two sides of a gap several edges wide on a fine mesh with --gap-tol set, which capped welds
    // left open. (The default tolerance, half the edge, is within the cap almost everywhere.)
    std::vector<double> nearest(nb, std::numeric_limits<double>::infinity());
    for (const ClosePair& p : close) {
      nearest[p.a] = std::min(nearest[p.a], p.distance);
      nearest[p.b] = std::min(nearest[p.b], p.distance);
    }
    for (const ClosePair& p : close) {
      const bool mutual = p.distance <= nearest[p.a] && p.distance <= nearest[p.b];
      const double cap = mutual
                             ? std::numeric_limits<double>::infinity()
                             : kEndFraction * 2 * std::min(b.edge_length[p.a], b.edge_length[p.b]);
      // The two halves of a full hull a gap apart in the centre plane, each within its
      // tolerance of it, each move half their distance onto it: they weld while that half is
      // within both tolerances. At a round-bilge hull's forefoot the borders are refined to
      // edges shorter than the gap (tolerances of 0.06 m across 0.08-0.09 m in the generated
      // 24-patch hull with 0.1 m gaps), and the slit left between the halves, closed by the
      // hole filler, broke the stem line into four pieces.
      const bool wedge = mutual && across_wedge(p.a, p.b);
      const double limit = std::min({(wedge ? 2.0 : 1.0) * std::min(tol[p.a], tol[p.b]), cap});
      // The search reached to the largest tolerance of all; most pairs are beyond their own.
      if (!(p.distance <= limit)) continue;
      // Coincident vertices weld whatever their inward directions: the two halves of a hull meet
      // at a fine stem or keel well inside the fold test's 60 degrees, and a fold does not put
      // two patches' vertices at the same point.
      const bool coincident = p.distance <= coincident_tol;
      // So do two that are each other's nearest within the chord error of their edges, both
      // within their tolerance of the centre plane: the two halves' borders mirrored a hair
      // apart where the hull is a fin of no thickness (the forefoot of a round-bilge hull, the
      // keel ends of a Wigley hull).
      const bool touching =
          mutual && p.distance <= kOnEdgeShare * std::min(b.edge_length[p.a], b.edge_length[p.b]) &&
          std::abs(points[p.a].y) <= tol[p.a] && std::abs(points[p.b].y) <= tol[p.b];
      // Two patches on either side of a strip narrower than the tolerance: each vertex belongs
      // on the strip's border, not on the other's.
      if (!coincident && across_third_patch(p.a, p.b)) continue;
      if (!coincident && (held_off(p.a, p.b) || held_off(p.b, p.a))) continue;
      if (coincident || touching || wedge ||
          (dot(inward[p.a], inward[p.b]) <= kFoldCos && !through_thickness(p.a, p.b))) {
        pairs.push_back(p);
      }
    }
  }
  // The close pairs came sorted by (a, b); the end pairs are sorted on their own and merged in.
  const std::size_t close_count = pairs.size();
  for (std::size_t i = 0; i < nb; ++i) {
    const Split& s = near[i];
    if (s.edge == kInvalid) continue;
    const BorderEdge& e = b.edges[s.edge];
    const Index end = s.t < 0.5 ? e.v0 : e.v1;
    const double len = norm(m.positions[e.v1] - m.positions[e.v0]);
    const double d = norm(points[i] - m.positions[end]);
    // Near the end along the edge, not only near it in space: across a gap wider than the edges
    // (a fine border facing a coarse one), a vertex squarely across from an end lies farther
    // from it than kEndFraction of the edge, and would otherwise be split in a hair from it.
    if (d <= tol[i] && (d <= kEndFraction * len || std::min(s.t, 1 - s.t) <= kEndFraction)) {
      const Index j = local[end];
      pairs.push_back({Index(std::min<std::size_t>(i, j)), Index(std::max<std::size_t>(i, j)), d});
    }
  }
  const auto by_ab = [](const ClosePair& x, const ClosePair& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  };
  std::sort(pairs.begin() + std::ptrdiff_t(close_count), pairs.end(), by_ab);
  std::inplace_merge(pairs.begin(), pairs.begin() + std::ptrdiff_t(close_count), pairs.end(),
                     by_ab);
  pairs.erase(
      std::unique(pairs.begin(), pairs.end(),
                  [](const ClosePair& x, const ClosePair& y) { return x.a == y.a && x.b == y.b; }),
      pairs.end());
  return pairs;
}

}  // namespace hm::merge
