// Scoring one collapse v -> t (v disappears into its neighbour t): the validity rules (features,
// topology, folds, slivers) and the paper's weighted index q of the panels it makes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "kernels/collapse_cost.h"
#include "unstructured/coarsen_state.h"

namespace hm::coarsen_detail {
namespace {

// "No new sliver": a collapse may not make a panel worse than this shape unless the panels it
// replaces already had one as bad.
constexpr double kSliverShape = 0.25;
// ... except by collapsing an edge shorter than this share of the size gate's edge at v. An edge
// that short is left over from the fine mesh, and a row of slivers along it (a strip a few
// millimetres wide along a keel or stem bar) can go only by collapsing it, one sliver for
// another on the way.
constexpr double kShortEdge = 0.1;

// Vertices around v (each once), from its faces.
void ring_of(const State& s, Index v, std::vector<Index>& out) {
  out.clear();
  for (Index f : s.vertex_faces[v]) {
    for (Index w : s.faces[f]) {
      if (w != v && std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
    }
  }
}

// Feature rules: corners never move; a vertex on a line moves only along it, and not so as to
// close a line into a loop of two edges.
bool feature_allows(const State& s, Index v, Index t) {
  switch (s.kind[v]) {
    case Kind::kCorner:
      return false;
    case Kind::kSmooth:
      return true;
    case Kind::kOnLine: {
      const auto& ln = s.line_nbr[v];
      if (ln[0] != t && ln[1] != t) return false;
      const Index c = ln[0] == t ? ln[1] : ln[0];
      // Two on-line vertices joined twice would make a line of two parallel edges. Two corners
      // already joined are fine: that is a sliver between two copies of a line, which the
      // collapse removes.
      auto other = [&](Index x, Index not_this) {
        const auto& n = s.line_nbr[x];
        return n[0] == not_this ? n[1] : n[0];
      };
      if (c == t) return false;
      if (s.kind[t] == Kind::kOnLine && other(t, v) == c) return false;
      if (s.kind[c] == Kind::kOnLine && other(c, v) == t) return false;
      return true;
    }
  }
  return false;
}

}  // namespace

Index region_size(const State& s, Index v, Index t) {
  return static_cast<Index>(3 * (s.vertex_faces[v].size() + s.vertex_faces[t].size()));
}

void collapse_region(const State& s, Index v, Index t, std::span<Index> out) {
  // Every corner of v's and t's faces: v, t and both rings, with repeats (the selection allows
  // them, and skipping the deduplication halves the cost).
  auto at = out.begin();
  for (Index x : {v, t}) {
    for (Index f : s.vertex_faces[x]) at = std::copy(s.faces[f].begin(), s.faces[f].end(), at);
  }
}

namespace {

// What every target of v shares: v's ring, and the shape and normal of each of its faces.
struct Star {
  std::vector<Index> ring;
  std::vector<Vec3d> normal;  // unnormalised, per face of v
  std::vector<double> length;
  double shape_min = 1;
};

void star_of(const State& s, Index v, Star& st) {
  ring_of(s, v, st.ring);
  st.normal.clear();
  st.length.clear();
  st.shape_min = 1;
  for (Index f : s.vertex_faces[v]) {
    const auto& tri = s.faces[f];
    const Vec3d &a = s.position[tri[0]], &b = s.position[tri[1]], &c = s.position[tri[2]];
    st.shape_min = std::min(st.shape_min, kernel::triangle_shape(a, b, c));
    st.normal.push_back(cross(b - a, c - a));
    st.length.push_back(norm(st.normal.back()));
  }
}

// check_link: test the link condition (scoring leaves it to the final check before applying:
// it rarely fails, and it is half the cost of a score).
Candidate score_with(const State& s, Index v, Index t, const Star& st, bool check_link) {
  Candidate out;
  if (!feature_allows(s, v, t)) return out;
  thread_local std::vector<Index> ring_t;
  const auto& star = s.vertex_faces[v];
  int on_edge = 0;
  for (Index f : star) on_edge += has_corner(s.faces[f], t);
  if (on_edge == 0 || on_edge > 2) return out;
  if (star.size() <= static_cast<std::size_t>(on_edge)) return out;
  if (check_link) {
    // Link condition: v and t share exactly the apexes of the faces on edge v-t, so the collapse
    // keeps the surface a manifold.
    ring_of(s, t, ring_t);
    int common = 0;
    for (Index w : st.ring) common += std::find(ring_t.begin(), ring_t.end(), w) != ring_t.end();
    if (common != on_edge) return out;
  }

  // The panels v's faces become, checked one by one. The curvature factor falls as the
  // curvature grows, so the panel's is the smallest of its corners' and v's. Sizes are compared
  // squared (l_eq^2 = 2 |n| / sqrt 3 for a face normal n of length twice the area) and rooted
  // once at the end: this loop is most of the coarsening's time.
  constexpr double kEdge2PerNormal = 2.0 / std::numbers::sqrt3;
  constexpr double kShapePerNormal = 2.0 * std::numbers::sqrt3;
  const bool has_sources = s.field.w_sources > 0 && !s.field.sources.empty();
  double shape_new = 1;
  double r2_curv = 0, r2_src = 0, r2_all = 0;
  // Twice the smallest and largest panel area around t after the collapse (for q2).
  double area2_lo = std::numeric_limits<double>::infinity(), area2_hi = 0;
  for (std::size_t i = 0; i < star.size(); ++i) {
    const auto& tri = s.faces[star[i]];
    if (has_corner(tri, t)) continue;
    Index w[3];
    for (int c = 0; c < 3; ++c) w[c] = tri[c] == v ? t : tri[c];
    const Vec3d &p0 = s.position[w[0]], &p1 = s.position[w[1]], &p2 = s.position[w[2]];
    const Vec3d n_new = cross(p1 - p0, p2 - p0);
    const double len_new = norm(n_new);
    if (!(len_new > 0) || dot(n_new, st.normal[i]) < s.cos_normal_change * len_new * st.length[i]) {
      return out;
    }
    for (int c = 0; c < 3; ++c) {
      if (s.kind[w[c]] == Kind::kSmooth &&
          dot(n_new, s.rest_normal[w[c]]) < kRestNormalCos * len_new) {
        return out;
      }
    }
    const double e01 = squared_norm(p1 - p0), e12 = squared_norm(p2 - p1),
                 e20 = squared_norm(p0 - p2);
    const double l2sum = e01 + e12 + e20;
    shape_new = std::min(shape_new, std::min(1.0, kShapePerNormal * len_new / l2sum));
    area2_lo = std::min(area2_lo, len_new);
    area2_hi = std::max(area2_hi, len_new);
    const double cf = std::min({s.cfactor[v], s.cfactor[w[0]], s.cfactor[w[1]], s.cfactor[w[2]]});
    const double hg = std::min({s.gate_h[v], s.gate_h[w[0]], s.gate_h[w[1]], s.gate_h[w[2]]});
    const double l2 = kEdge2PerNormal * len_new;
    const double hc = s.field.h0 * cf;
    r2_curv = std::max(r2_curv, l2 / (hc * hc));
    // The gate holds the longest edge too: by l_eq alone a panel along a boundary grows long
    // and flat, its line edge outrunning the panels inside.
    r2_all = std::max(r2_all, std::max({l2, e01, e12, e20}) / (hg * hg));
    if (has_sources) {
      const double hs = s.field.h0 * s.field.source_factor((p0 + p1 + p2) / 3.0);
      r2_src = std::max(r2_src, l2 / (hs * hs));
    } else {
      r2_src = std::max(r2_src, l2 / (s.field.h0 * s.field.h0));
    }
  }
  if (shape_new < std::min(kSliverShape, st.shape_min)) {
    const double short_edge = kShortEdge * s.gate_h[v];
    if (squared_norm(s.position[t] - s.position[v]) >= short_edge * short_edge) return out;
  }
  // Neighbouring panels: the rest of t's faces, unchanged by the collapse. Compared squared and
  // rooted once each (the root is monotone: the same extremes).
  double t2_lo = std::numeric_limits<double>::infinity(), t2_hi = -1;
  for (Index f : s.vertex_faces[t]) {
    const auto& tri = s.faces[f];
    if (has_corner(tri, v)) continue;
    const double n2 = squared_norm(
        cross(s.position[tri[1]] - s.position[tri[0]], s.position[tri[2]] - s.position[tri[0]]));
    t2_lo = std::min(t2_lo, n2);
    t2_hi = std::max(t2_hi, n2);
  }
  if (t2_hi >= 0) {
    area2_lo = std::min(area2_lo, std::sqrt(t2_lo));
    area2_hi = std::max(area2_hi, std::sqrt(t2_hi));
  }
  kernel::CollapseQualities q;
  q.shape = shape_new;
  q.area_ratio = kernel::area_ratio_quality(area2_lo, area2_hi);
  q.curvature = kernel::size_quality(std::sqrt(r2_curv));
  q.sources = kernel::size_quality(std::sqrt(r2_src));
  out.target = t;
  out.q = kernel::weighted_index(q, s.weights);
  out.r = std::sqrt(r2_all);
  out.faces_removed = static_cast<std::uint8_t>(on_edge);
  return out;
}

}  // namespace

Candidate score_collapse(const State& s, Index v, Index t) {
  thread_local Star st;
  star_of(s, v, st);
  return score_with(s, v, t, st, true);
}

Candidate score_vertex(const State& s, Index v) {
  Candidate best;
  if (!s.alive[v] || s.kind[v] == Kind::kCorner) return best;
  thread_local Star st;
  thread_local std::vector<Index> targets;
  star_of(s, v, st);
  if (s.kind[v] == Kind::kOnLine) {
    targets.assign(s.line_nbr[v].begin(), s.line_nbr[v].end());
  } else {
    targets = st.ring;
  }
  std::sort(targets.begin(), targets.end());  // ties go to the smaller target
  for (Index t : targets) {
    const Candidate c = score_with(s, v, t, st, false);
    if (c.target != kInvalid && (best.target == kInvalid || c.q > best.q)) best = c;
  }
  return best;
}

Applied apply_collapse(State& s, Index v, Index t, double& deviation,
                       std::array<Index, 2>& joined_corners) {
  deviation = 0;
  joined_corners = {kInvalid, kInvalid};
  if (score_collapse(s, v, t).target == kInvalid) return Applied::kRejectedShape;
  if (s.kind[v] == Kind::kOnLine) {
    // The new line edge t - c must follow the fine line it replaces.
    const bool t_before = s.line_nbr[v][0] == t;
    const Index c = t_before ? s.line_nbr[v][1] : s.line_nbr[v][0];
    const Index kt = line_index(s, v, t, t_before), kc = line_index(s, v, c, !t_before);
    if (kt == kInvalid || kc == kInvalid) return Applied::kRejectedShape;
    const bool ok = t_before
                        ? line_chord_ok(s, s.spot[v].line, kt, kc, s.position[t], s.position[c])
                        : line_chord_ok(s, s.spot[v].line, kc, kt, s.position[c], s.position[t]);
    if (!ok) return Applied::kRejectedDeviation;
  }
  // Final corners first (so that the witnesses are measured against the panels as they will
  // be), then the witnesses; undo the corners if the bound fails.
  thread_local std::vector<Index> from, targets, removed;
  from.assign(s.vertex_faces[v].begin(), s.vertex_faces[v].end());
  targets.clear();
  removed.clear();
  for (Index f : from) {
    auto& tri = s.faces[f];
    if (has_corner(tri, t)) {
      removed.push_back(f);
    } else {
      for (Index& w : tri) w = w == v ? t : w;
      targets.push_back(f);
    }
  }
  for (Index f : s.vertex_faces[t]) {
    if (!has_corner(s.faces[f], v) &&
        std::find(targets.begin(), targets.end(), f) == targets.end()) {
      targets.push_back(f);
    }
  }
  // Witnesses of t's other faces stay where they are; those of v's faces and v itself move.
  if (!reassign_witnesses(s, from, s.source[v], targets, deviation)) {
    for (Index f : from) {
      auto& tri = s.faces[f];
      if (!has_corner(tri, v)) {
        for (Index& w : tri) w = w == t ? v : w;
      }
    }
    return Applied::kRejectedDeviation;
  }
  // Topology: drop the faces on edge v-t from their other corners' lists, move the rest to t.
  for (Index f : removed) {
    s.face_alive[f] = 0;
    for (Index w : s.faces[f]) {
      if (w == v) continue;
      auto& list = s.vertex_faces[w];
      list.erase(std::find(list.begin(), list.end(), f));
    }
  }
  auto& tlist = s.vertex_faces[t];
  for (Index f : from) {
    if (s.face_alive[f]) tlist.push_back(f);
  }
  s.vertex_faces[v].clear();
  s.alive[v] = 0;
  // Feature lines: t takes v's place between its line neighbours.
  if (s.kind[v] == Kind::kOnLine) {
    const auto ln = s.line_nbr[v];
    const Index c = ln[0] == t ? ln[1] : ln[0];
    auto relink = [&](Index x, Index old_nbr, Index new_nbr) {
      if (s.kind[x] != Kind::kOnLine) return;
      for (Index& n : s.line_nbr[x]) n = n == old_nbr ? new_nbr : n;
    };
    relink(t, v, c);
    relink(c, v, t);
    if (s.kind[t] == Kind::kCorner && s.kind[c] == Kind::kCorner) {
      // Two corners now joined by a feature edge: the caller adds it to corner_edges after the
      // batch (a shared sorted list is not written concurrently).
      joined_corners = {std::min(t, c), std::max(t, c)};
    }
  }
  return Applied::kDone;
}

}  // namespace hm::coarsen_detail
