// After the collapses: edge flips (serial, in face order) and tangential smoothing (in parallel
// over independent sets of vertices). Smooth vertices move toward the area-weighted centre of
// their panels within the tangent plane and are projected back onto their NURBS patch; vertices
// on a feature line move along the fine line to halfway (by arc length) between their line
// neighbours, landing on a fine vertex so that they stay exactly on the knuckle or boundary.
// Every move is checked like a collapse: no fold, no worse panel, witnesses within the bound.
// Before and after the passes, panels lying back to back with a neighbour are parted by flips.
#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "kernels/collapse_cost.h"
#include "kernels/independent_set.h"
#include "nurbs/nurbs_surface.h"
#include "unstructured/coarsen_state.h"

namespace hm::coarsen_detail {
namespace {

// A flip must raise the worse of its two panels' shapes by this much (no flipping back and forth).
constexpr double kFlipGain = 0.02;
// The two panels of a flipped edge may stand at most this far from coplanar (cos 20 degrees).
constexpr double kFlipCoplanarCos = 0.94;
// A flip that parts panels lying back to back may leave a panel this bad, when none was worse
// before: a little below the collapses' sliver shape (0.25), since a pair back to back breaks a
// panel code's rule and one poor panel only lowers a share.
constexpr double kApartShape = 0.2;
// A slide apart may leave the worst panel around the moved corner worse than it was when that
// was a sliver already (shape under kSliverShape), down to kSliverShareKept of its old shape: a
// sliver across the gap between a full hull's two stems, whose shape moves by tens of per cent
// with any move of its corners, and which stays a sliver either way.
constexpr double kSliverShape = 0.05;
constexpr double kSliverShareKept = 0.5;

Vec3d tri_cross(const State& s, const std::array<Index, 3>& t) {
  return cross(s.position[t[1]] - s.position[t[0]], s.position[t[2]] - s.position[t[0]]);
}

double tri_shape(const State& s, const std::array<Index, 3>& t) {
  return kernel::triangle_shape(s.position[t[0]], s.position[t[1]], s.position[t[2]]);
}

// The corner after `a` in face t (its winding).
Index next_corner(const std::array<Index, 3>& t, Index a) {
  return t[0] == a ? t[1] : (t[1] == a ? t[2] : t[0]);
}

bool adjacent(const State& s, Index a, Index b) {
  for (Index f : s.vertex_faces[a]) {
    if (has_corner(s.faces[f], b)) return true;
  }
  return false;
}

// Tries to flip edge a -> b of face f1. Returns true when flipped. Neither new panel may lie back
// to back with a neighbour. Normally a flip must raise the worse panel's shape by kFlipGain;
// `apart` (f1 lies back to back with a neighbour) asks only that the worse shape stay at least
// the old one's or kApartShape.
bool try_flip(State& s, Index f1, Index a, Index b, double& deviation, bool apart = false) {
  if (is_feature_edge(s, a, b)) return false;
  Index f2 = kInvalid;
  for (Index g : s.vertex_faces[b]) {
    if (g != f1 && has_corner(s.faces[g], a)) {
      if (f2 != kInvalid) return false;
      f2 = g;
    }
  }
  if (f2 == kInvalid || next_corner(s.faces[f2], b) != a) return false;
  const Index c = next_corner(s.faces[f1], b);
  const Index d = next_corner(s.faces[f2], a);
  if (c == d || s.vertex_faces[a].size() < 4 || s.vertex_faces[b].size() < 4 || adjacent(s, c, d)) {
    return false;
  }
  const std::array<Index, 3> old1 = s.faces[f1], old2 = s.faces[f2];
  const std::array<Index, 3> new1{a, d, c}, new2{d, b, c};
  const double old_min = std::min(tri_shape(s, old1), tri_shape(s, old2));
  const double new_min = std::min(tri_shape(s, new1), tri_shape(s, new2));
  if (new_min < (apart ? std::min(old_min, kApartShape) : old_min + kFlipGain)) return false;
  const Index pair[2] = {f1, f2};
  if (back_to_back_across(s, new1, pair) || back_to_back_across(s, new2, pair)) return false;
  const Vec3d n_old = tri_cross(s, old1) + tri_cross(s, old2);
  const Vec3d m1 = tri_cross(s, new1), m2 = tri_cross(s, new2);
  const double l1 = norm(m1), l2 = norm(m2), lo = norm(n_old);
  if (!(l1 > 0 && l2 > 0) || dot(m1, m2) < kFlipCoplanarCos * l1 * l2 ||
      dot(m1, n_old) < s.cos_normal_change * l1 * lo ||
      dot(m2, n_old) < s.cos_normal_change * l2 * lo) {
    return false;
  }
  s.faces[f1] = new1;
  s.faces[f2] = new2;
  const Index both[2] = {f1, f2};
  if (!reassign_witnesses(s, both, kInvalid, both, deviation)) {
    s.faces[f1] = old1;
    s.faces[f2] = old2;
    return false;
  }
  auto drop = [&](Index v, Index f) {
    auto& l = s.vertex_faces[v];
    l.erase(std::find(l.begin(), l.end(), f));
  };
  drop(a, f2);
  drop(b, f1);
  s.vertex_faces[c].push_back(f2);
  s.vertex_faces[d].push_back(f1);
  return true;
}

std::size_t flip_pass(State& s) {
  std::size_t flips = 0;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (!s.face_alive[f]) continue;
    for (int e = 0; e < 3; ++e) {
      const auto t = s.faces[f];
      double deviation = 0;
      if (try_flip(s, static_cast<Index>(f), t[e], t[(e + 1) % 3], deviation)) {
        ++flips;
        s.max_witness_distance = std::max(s.max_witness_distance, deviation);
        break;  // the face changed; its other edges come again next pass
      }
    }
  }
  return flips;
}

// Panels lying back to back with a neighbour (see back_to_back) form where the hull's halves are
// tangent: the fine mesh brings them (a fine panel at a full Wigley's stem foot with its corners
// on the stem and the keel), and collapses make them, unchecked (a guard that refused such
// collapses left pairs of panels that share no edge; see the README). Flipping one of their free
// edges gives each side a corner off the centre plane, where the halves part.
std::size_t flip_apart(State& s) {
  // Found in parallel (each face writes its own flag), parted serially in face order.
  std::vector<std::uint8_t> found(s.faces.size(), 0);
  parallel_for(0, s.faces.size(), [&](std::size_t f) {
    const Index self[1] = {static_cast<Index>(f)};
    found[f] = s.face_alive[f] && back_to_back_across(s, s.faces[f], self);
  });
  std::size_t flips = 0;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    // A flip of an earlier face may have parted this one already (flips make no new pair).
    const Index self[1] = {static_cast<Index>(f)};
    if (!found[f] || !s.face_alive[f] || !back_to_back_across(s, s.faces[f], self)) continue;
    for (int e = 0; e < 3; ++e) {
      const auto t = s.faces[f];
      double deviation = 0;
      if (try_flip(s, static_cast<Index>(f), t[e], t[(e + 1) % 3], deviation, true)) {
        ++flips;
        s.max_witness_distance = std::max(s.max_witness_distance, deviation);
        break;
      }
    }
  }
  return flips;
}

// Where a line vertex should go: the fine line index halfway by arc length between its line
// neighbours; the current index when it cannot tell (a wrap of a closed line, a corner that is
// not on this line).
Index line_target(const State& s, Index v) {
  const LineSpot sp = s.spot[v];
  const FineLine& l = s.lines[sp.line];
  const Index kp = line_index(s, v, s.line_nbr[v][0], true);
  const Index kn = line_index(s, v, s.line_nbr[v][1], false);
  if (kp == kInvalid || kn == kInvalid || !(kp < sp.k && sp.k < kn)) return sp.k;
  const double mid = 0.5 * (l.arclength[kp] + l.arclength[kn]);
  const auto first = l.arclength.begin() + kp + 1, last = l.arclength.begin() + kn;
  auto it = std::lower_bound(first, last, mid);
  Index k = static_cast<Index>(it - l.arclength.begin());
  if (k >= kn) k = kn - 1;
  if (k > kp + 1 && mid - l.arclength[k - 1] < l.arclength[k] - mid) --k;
  return k;
}

// Where a vertex would go: its place on the surface, and on a line its fine vertex.
struct Placement {
  Vec3d p;
  Vec2d uv;
  PatchId patch = kInvalid;
  Index source = kInvalid;
  Index k = kInvalid;
};

// Line vertex v placed on fine vertex k of its line; false when a panel edge along the line
// would then leave it (line_chord_ok on both sides).
bool line_placement(const State& s, Index v, Index k, Placement& to) {
  const Index prev = s.line_nbr[v][0], next = s.line_nbr[v][1];
  const Index line = s.spot[v].line;
  const Index kp = line_index(s, v, prev, true), kn = line_index(s, v, next, false);
  const Vec3d& p = s.fine_positions[s.lines[line].vertices[k]];
  if (!line_chord_ok(s, line, kp, k, s.position[prev], p) ||
      !line_chord_ok(s, line, k, kn, p, s.position[next])) {
    return false;
  }
  to.source = s.lines[line].vertices[k];
  to.p = s.fine_positions[to.source];
  to.uv = s.fine_uv[to.source];
  to.patch = s.fine_vertex_patch[to.source];
  to.k = k;
  return true;
}

// A live face lying back to back with face f: one sharing a corner with it (across an edge or at
// a corner alone), else one sharing a corner with a sliver that shares one with f. The second
// ring is for a thin end whose two halves' stems stay apart, joined by slivers in the stem's
// plane (property seed 5244: a full Wigley's bow foot, the two panels' centres 2 cm apart with
// no corner shared); through slivers alone, it costs next to nothing. kInvalid when none.
Index back_to_back_partner(const State& s, Index f) {
  const auto& t = s.faces[f];
  for (Index v : t) {
    for (Index g : s.vertex_faces[v]) {
      if (g != f && back_to_back(s, t, s.faces[g])) return g;
    }
  }
  for (Index v : t) {
    for (Index h : s.vertex_faces[v]) {
      if (!(tri_shape(s, s.faces[h]) < kSliverShape)) continue;
      for (Index w : s.faces[h]) {
        for (Index g : s.vertex_faces[w]) {
          if (g != f && back_to_back(s, t, s.faces[g])) return g;
        }
      }
    }
  }
  return kInvalid;
}

// Moves v to `to` when its panels allow it; returns true when moved. Normally the panels must
// get better (the worst no worse, or all fair and their sum higher). `apart` (a slide to part
// panels lying back to back) asks instead that no panel of the star lie back to back with a
// neighbour afterwards, and that the worst shape stay at least the old one's or kApartShape
// (or, for a sliver, kSliverShareKept of it).
bool try_place(State& s, Index v, const Placement& to, double& deviation, bool apart = false) {
  const auto& star = s.vertex_faces[v];
  const Vec3d old_p = s.position[v];
  double old_min = 1, new_min = 1, old_sum = 0, new_sum = 0;
  thread_local std::vector<Vec3d> old_normal;
  old_normal.clear();
  for (Index f : star) {
    const double q = tri_shape(s, s.faces[f]);
    old_min = std::min(old_min, q);
    old_sum += q;
    old_normal.push_back(tri_cross(s, s.faces[f]));
  }
  // Whether face t with normal m stands within kRestNormalCos of the hull's normal at each of its
  // smooth corners.
  auto near_rest = [&](const std::array<Index, 3>& t, const Vec3d& m) {
    const double lm = norm(m);
    for (int c = 0; c < 3; ++c) {
      if (s.kind[t[c]] == Kind::kSmooth && dot(m, s.rest_normal[t[c]]) < kRestNormalCos * lm) {
        return false;
      }
    }
    return true;
  };
  s.position[v] = to.p;
  bool ok = true;
  for (std::size_t i = 0; i < star.size() && ok; ++i) {
    const auto& t = s.faces[star[i]];
    const Vec3d m = tri_cross(s, t);
    const double lm = norm(m);
    ok = lm > 0 && dot(m, old_normal[i]) >= s.cos_normal_change * lm * norm(old_normal[i]);
    // A slide apart may keep a panel that stood off the hull's normal already (a sliver across
    // the gap between a full hull's two stems stands square to both halves).
    const bool was_off_rest = apart && !near_rest(t, old_normal[i]);
    if (ok && !was_off_rest) ok = near_rest(t, m);
    if (ok && apart) ok = back_to_back_partner(s, star[i]) == kInvalid;
    const double q = tri_shape(s, t);
    new_min = std::min(new_min, q);
    new_sum += q;
  }
  if (apart) {
    const bool sliver_kept = old_min < kSliverShape && new_min >= kSliverShareKept * old_min;
    ok = ok && (new_min >= std::min(old_min, kApartShape) || sliver_kept);
  } else {
    ok = ok && (new_min >= old_min || (new_min >= 0.5 && new_sum > old_sum));
  }
  const Index old_source = s.source[v];
  const Index extra = to.source != old_source ? old_source : kInvalid;
  if (!ok || !reassign_witnesses(s, star, extra, star, deviation)) {
    s.position[v] = old_p;
    return false;
  }
  s.uv[v] = to.uv;
  s.vpatch[v] = to.patch;
  s.source[v] = to.source;
  s.spot[v].k = to.k;
  return true;
}

// Moves v when that helps; returns true when moved.
bool try_move(State& s, Index v, double& deviation) {
  if (!s.alive[v] || s.kind[v] == Kind::kCorner) return false;
  const auto& star = s.vertex_faces[v];
  if (star.empty()) return false;
  const Vec3d old_p = s.position[v];
  Placement to{old_p, s.uv[v], s.vpatch[v], s.source[v], s.spot[v].k};
  if (s.kind[v] == Kind::kSmooth) {
    Vec3d centre;
    double area = 0;
    for (Index f : star) {
      const auto& t = s.faces[f];
      const double a = 0.5 * norm(tri_cross(s, t));
      centre += a * (s.position[t[0]] + s.position[t[1]] + s.position[t[2]]) / 3.0;
      area += a;
    }
    if (!(area > 0)) return false;
    centre /= area;
    const Vec3d n = s.rest_normal[v];
    const Vec3d step = (centre - old_p) - dot(centre - old_p, n) * n;
    if (squared_norm(step) < 1e-4 * area / static_cast<double>(star.size())) return false;
    const Patch& patch = s.patches[s.vpatch[v]];
    const SurfaceProjection pr =
        closest_point(patch.surface, old_p + step, s.uv[v].x, s.uv[v].y, s.patch_net[s.vpatch[v]]);
    if (!pr.converged || !is_finite(pr.point) || pr.distance > norm(step)) return false;
    to.p = pr.point;
    to.uv = {pr.u, pr.v};
  } else {
    const Index k = line_target(s, v);
    if (k == s.spot[v].k || !line_placement(s, v, k, to)) return false;
  }
  return try_place(s, v, to, deviation);
}

// Slides line vertex v along its line to the nearest fine vertex, on either side and within its
// line neighbours, where it parts every panel around it.
bool slide_on_line(State& s, Index v, double& deviation) {
  const Index kp = line_index(s, v, s.line_nbr[v][0], true);
  const Index kn = line_index(s, v, s.line_nbr[v][1], false);
  const Index k0 = s.spot[v].k;
  if (kp == kInvalid || kn == kInvalid || !(kp < k0 && k0 < kn)) return false;
  for (Index step = 1; step < k0 - kp || step < kn - k0; ++step) {
    for (const Index k : {k0 - std::min(step, k0 - kp), k0 + std::min(step, kn - k0)}) {
      Placement to;
      if (k > kp && k < kn && line_placement(s, v, k, to) && try_place(s, v, to, deviation, true)) {
        return true;
      }
    }
  }
  return false;
}

// Slides smooth vertex v of face f on its patch, in the tangent plane, in the direction that
// takes f's centre away from that of g (back to back with f), by 1.5, 2.5 and 4 times the
// distance the centres must keep, until the panels around it part.
bool slide_on_surface(State& s, Index v, Index f, Index g, double& deviation) {
  auto centre = [&](Index h) {
    const auto& t = s.faces[h];
    return (s.position[t[0]] + s.position[t[1]] + s.position[t[2]]) / 3.0;
  };
  const Vec3d n = s.rest_normal[v];
  Vec3d d = centre(f) - centre(g);
  d -= dot(d, n) * n;
  const double ld = norm(d);
  if (!(ld > 0)) return false;
  d /= ld;
  const double area =
      0.5 * std::min(norm(tri_cross(s, s.faces[f])), norm(tri_cross(s, s.faces[g])));
  // A corner's move shifts its face's centre by a third of it.
  const double keep = 3.0 * kCloseCentreFraction * std::sqrt(area);
  const Patch& patch = s.patches[s.vpatch[v]];
  for (const double factor : {1.5, 2.5, 4.0}) {
    const double step = factor * keep;
    const SurfaceProjection pr = closest_point(patch.surface, s.position[v] + step * d, s.uv[v].x,
                                               s.uv[v].y, s.patch_net[s.vpatch[v]]);
    if (!pr.converged || !is_finite(pr.point) || pr.distance > step) continue;
    const Placement to{pr.point, {pr.u, pr.v}, s.vpatch[v], s.source[v], s.spot[v].k};
    if (try_place(s, v, to, deviation, true)) return true;
  }
  return false;
}

// Panels back to back that no flip parts (a full Wigley's bow foot, where each half's stem runs
// down beside the other's, a gap's width apart, to a keel the two share: the two panels there
// have the keel edge and a stem vertex each) are parted by moving one of their corners that is
// not a feature corner: along its line to a fine vertex, or on its patch away from the other
// panel. Serial, in face order.
std::size_t slide_apart(State& s) {
  std::size_t slides = 0;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    if (!s.face_alive[f]) continue;
    for (int c = 0; c < 3; ++c) {
      const Index g = back_to_back_partner(s, static_cast<Index>(f));
      if (g == kInvalid) break;
      const Index v = s.faces[f][c];
      double deviation = 0;
      bool moved = false;
      if (s.kind[v] == Kind::kOnLine) moved = slide_on_line(s, v, deviation);
      if (s.kind[v] == Kind::kSmooth) {
        moved = slide_on_surface(s, v, static_cast<Index>(f), g, deviation);
      }
      if (moved) {
        s.max_witness_distance = std::max(s.max_witness_distance, deviation);
        ++slides;
        break;
      }
    }
  }
  return slides;
}

std::size_t smooth_pass(State& s, std::vector<std::uint8_t>& held) {
  std::vector<Index> pending;
  for (std::size_t v = 0; v < s.position.size(); ++v) {
    if (s.alive[v] && s.kind[v] != Kind::kCorner) pending.push_back(static_cast<Index>(v));
  }
  std::size_t moves = 0;
  std::vector<Index> offsets, region;
  std::vector<std::uint64_t> keys;
  while (!pending.empty()) {
    // A move writes v (its place and its panels' witnesses) and reads its ring, so moves of
    // vertices that are not neighbours run together. Keys: a fixed hash of v, so that the sets
    // are the same for any thread count.
    offsets.assign(pending.size() + 1, 0);
    keys.resize(pending.size());
    for (std::size_t i = 0; i < pending.size(); ++i) {
      const Index v = pending[i];
      std::uint64_t h = (v + 1) * 0x9E3779B97F4A7C15ull;
      h ^= h >> 29;
      keys[i] = kernel::priority_key(static_cast<double>(h & 0xffffff) / 16777216.0, v);
      offsets[i + 1] = offsets[i] + 3 * static_cast<Index>(s.vertex_faces[v].size());
    }
    region.resize(offsets.back());
    parallel_for(0, pending.size(), [&](std::size_t i) {
      Index k = offsets[i];
      for (Index f : s.vertex_faces[pending[i]]) {
        for (Index w : s.faces[f]) region[k++] = w;
      }
    });
    const std::vector<Index> chosen =
        kernel::select_greedy_apart(keys, pending, offsets, region, held);
    std::vector<std::uint8_t> moved(chosen.size(), 0);
    std::vector<double> deviation(chosen.size(), 0.0);
    parallel_for(
        0, chosen.size(),
        [&](std::size_t i) { moved[i] = try_move(s, pending[chosen[i]], deviation[i]); }, 8);
    for (std::size_t i = 0; i < chosen.size(); ++i) {
      moves += moved[i];
      s.max_witness_distance = std::max(s.max_witness_distance, deviation[i]);
    }
    // Drop the chosen from the pending list (both ascending).
    std::vector<Index> rest;
    rest.reserve(pending.size() - chosen.size());
    std::size_t c = 0;
    for (std::size_t i = 0; i < pending.size(); ++i) {
      if (c < chosen.size() && chosen[c] == i) {
        ++c;
      } else {
        rest.push_back(pending[i]);
      }
    }
    pending.swap(rest);
  }
  return moves;
}

}  // namespace

ImproveCounts improve_panels(State& s, int passes) {
  ImproveCounts counts;
  std::vector<std::uint8_t> held(s.position.size(), 0);
  // Apart first, so that the passes work on parted panels; and last, since a smoothing move is
  // not checked against the faces beyond its ring (their far corners may move in the same round).
  counts.flips += flip_apart(s);
  for (int p = 0; p < passes; ++p) {
    counts.flips += flip_pass(s);
    counts.moves += smooth_pass(s, held);
  }
  counts.flips += flip_apart(s);
  counts.moves += slide_apart(s);
  return counts;
}

}  // namespace hm::coarsen_detail
