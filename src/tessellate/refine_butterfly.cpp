#include "tessellate/refine_butterfly.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "tessellate/butterfly.h"
#include "tessellate/chord_error.h"

namespace hm {
namespace {

constexpr std::uint64_t kNoEdge = ~std::uint64_t{0};
// How far a projected midpoint may move from the middle of its edge: along the edge, as a
// fraction of it; across, as a fraction of the adjacent triangle's height (both in (u, v)).
constexpr double kMaxSlideAlong = 0.25;
constexpr double kMaxSlideAcross = 0.25;
constexpr int kProjectionSteps = 6;
// Projection stops when its step is below this fraction of the edge's parameter length.
constexpr double kResolution = 1e-10;
constexpr int kExtraLevels = 4;
constexpr int kGreenRounds = 16;

Index key_lo(std::uint64_t k) { return Index(k >> 32); }
Index key_hi(std::uint64_t k) { return Index(k & 0xffffffffu); }

// Signed double area of (a, b, c) in (u, v).
double orient(const Vec2d& a, const Vec2d& b, const Vec2d& c) { return cross(b - a, c - a); }

// Borders of the pieces of one direction inside which the surface is smooth, sorted: the domain
// ends and every interior knot of multiplicity >= degree (the surface is only C0 there: a
// knuckle, which the initial grid always follows with a grid line).
std::vector<double> c0_breaks(const std::vector<double>& knots, int degree, double lo, double hi) {
  std::vector<double> out{lo};
  for (std::size_t k = 0; k < knots.size(); ++k) {
    const double t = knots[k];
    if (t <= lo || t >= hi || (k > 0 && knots[k - 1] == t)) continue;
    if (std::count(knots.begin(), knots.end(), t) >= degree) out.push_back(t);
  }
  out.push_back(hi);
  return out;
}

bool is_break(const std::vector<double>& breaks, double t) {
  return std::binary_search(breaks.begin(), breaks.end(), t);
}

// The parameter box a new vertex is projected in (u0..u1 x v0..v1 of one C0 piece).
struct Box {
  double u0, u1, v0, v1;
};

// The piece [lo, hi] between consecutive breaks that holds the middle of (a, b), when it holds
// both ends too; else (an edge across a knuckle, which a trimmed patch's triangulation may make)
// the whole range.
std::pair<double, double> piece_of(const std::vector<double>& breaks, double a, double b) {
  const auto it = std::upper_bound(breaks.begin() + 1, breaks.end() - 1, 0.5 * (a + b));
  const double lo = *(it - 1), hi = *it;
  if (std::min(a, b) < lo || std::max(a, b) > hi) return {breaks.front(), breaks.back()};
  return {lo, hi};
}

struct NewMid {
  Index a, b;    // edge ends
  Index corner;  // creating triangle's half-edge
};

class Refiner {
 public:
  Refiner(const NurbsSurface& s, PatchMesh& m, const RefineOptions& o)
      : s_(s),
        m_(m),
        o_(o),
        breaks_u_(c0_breaks(s.knots_u, s.degree_u, s.u0, s.u1)),
        breaks_v_(c0_breaks(s.knots_v, s.degree_v, s.v0, s.v1)) {
    level_.assign(m.tri_count(), 0);
    fresh_.assign(m.tri_count(), 1);
    parent_edge_.assign(m.vertex_count(), kNoEdge);
  }

  RefineStats run() {
    // Marks stop at max_levels; the 1-irregular closure may add a few levels past it. Every
    // level ends with at most one hanging node per triangle, so stopping anywhere is valid.
    // A green (1 -> 2) split is only a closure: when its halves would miss the tolerance the
    // triangle is split red instead and refinement resumes.
    for (int round = 0; round < kGreenRounds; ++round) {
      for (int l = 0; l < o_.max_levels + kExtraLevels; ++l) {
        if (!run_level()) break;
        ++stats_.levels;
      }
      forced_ = failing_greens();
      if (forced_.empty()) break;
    }
    forced_.clear();
    close_green();
    return stats_;
  }

 private:
  bool run_level();
  std::vector<std::uint8_t> failing_greens() const;
  // The corner indices (a, b, c) of t's green split when exactly one edge (a, b) has a midpoint.
  bool green_split(Index t, int& a, Index& mid) const;
  std::vector<std::uint8_t> criteria() const;
  std::vector<std::uint8_t> propagate(const std::vector<std::uint8_t>& mark) const;
  void place_midpoints(const std::vector<NewMid>& mids, Index first_id);
  void place_one(const VertexRings& rings, const std::vector<std::uint8_t>& boundary,
                 const NewMid& nm, Index id);
  void split_red(const std::vector<std::uint8_t>& in_r);
  void close_green();

  std::uint64_t coarse_of(Index x, Index y) const;
  // The unsplit triangle whose edge has (x, y) as one half (a hanging node between), or kInvalid.
  Index coarse_leaf(Index x, Index y) const {
    const std::uint64_t coarse = coarse_of(x, y);
    if (coarse == kNoEdge) return kInvalid;
    const Index ce = table_.find(coarse);
    if (ce == kInvalid || table_.size(ce) != 1) return kInvalid;
    return table_.he[table_.first[ce]].corner / 3;
  }
  int hanging_count(Index t, const std::vector<std::uint8_t>& in_r) const;
  Vec2d sheared_midpoint(const Box& box, const Vec3d& q, const Vec2d& p, const Vec2d& start,
                         Index a, Index b, Index c, Index d) const;
  Vec2d corner_uv(Index mid, const Vec2d& wa, const Vec2d& wb) const;
  Index mid_of(std::uint64_t key) const {
    auto it = mid_.find(key);
    return it == mid_.end() ? kInvalid : it->second;
  }
  Index other_tri(Index e, Index t) const {
    for (Index k = table_.first[e]; k < table_.first[e + 1]; ++k)
      if (table_.he[k].corner / 3 != t) return table_.he[k].corner / 3;
    return kInvalid;
  }

  const NurbsSurface& s_;
  PatchMesh& m_;
  RefineOptions o_;
  std::vector<double> breaks_u_, breaks_v_;  // C0 piece borders (see c0_breaks)
  RefineStats stats_;
  std::vector<std::uint8_t> level_, fresh_;
  std::vector<std::uint64_t> parent_edge_;  // per vertex: the edge it is the midpoint of
  std::unordered_map<std::uint64_t, Index> mid_;
  EdgeTable table_;
  std::vector<std::uint8_t>
      forced_;  // triangles to split red at the next level, whatever the criteria
};

std::uint64_t Refiner::coarse_of(Index x, Index y) const {
  for (const auto& [half_end, other] : {std::pair{y, x}, std::pair{x, y}}) {
    const std::uint64_t pe = parent_edge_[half_end];
    if (pe != kNoEdge && (key_lo(pe) == other || key_hi(pe) == other)) return pe;
  }
  return kNoEdge;
}

// Edges of t that carry a midpoint after this level: already split by a neighbour, or shared
// with a triangle that is about to split.
int Refiner::hanging_count(Index t, const std::vector<std::uint8_t>& in_r) const {
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const Tri& v = m_.tris[t];
    if (mid_of(edge_key(v[i], v[(i + 1) % 3])) != kInvalid) {
      ++n;
      continue;
    }
    const Index e = table_.edge_of_corner[3 * t + i];
    const Index nb = table_.size(e) == 2 ? other_tri(e, t) : kInvalid;
    if (nb != kInvalid && in_r[nb]) ++n;
  }
  return n;
}

// The chord samples are those of measure_chord_error (edge middles and centroid in (u, v), their
// distance to the flat triangle), so a triangle that passes here measures within tolerance.
std::vector<std::uint8_t> Refiner::criteria() const {
  const std::size_t nt = m_.tri_count();
  auto wanted = [&](Index t) { return fresh_[t] && level_[t] < o_.max_levels; };
  std::vector<Vec3d> edge_point(table_.count());  // the surface at each edge's middle (u, v)
  parallel_for(0, table_.count(), [&](std::size_t e) {
    bool needed = false;
    for (Index k = table_.first[e]; k < table_.first[e + 1]; ++k)
      needed = needed || wanted(table_.he[k].corner / 3);
    if (!needed || o_.chord_sampling != ChordSampling::kParametric) return;
    const Index c = table_.he[table_.first[e]].corner, t = c / 3, i = c % 3;
    const Vec2d w = o_.collapsed.edge_middle(m_.tri_uv[t][i], m_.tri_uv[t][(i + 1) % 3]);
    edge_point[e] = evaluate(s_, w.x, w.y);
  });
  std::vector<std::uint8_t> mark(nt, 0);
  const double c2 = o_.collapse_tolerance * o_.collapse_tolerance;
  parallel_for(0, nt, [&](std::size_t t) {
    if (!wanted(Index(t))) return;
    const Tri& v = m_.tris[t];
    const Vec3d &a = m_.xyz[v[0]], &b = m_.xyz[v[1]], &c = m_.xyz[v[2]];
    // A triangle with a collapsed edge vanishes when coincident vertices merge; its own error is
    // not that of the surface (its neighbour covers that region), so it only splits for closure.
    if (squared_norm(b - a) <= c2 || squared_norm(c - b) <= c2 || squared_norm(a - c) <= c2) return;
    bool split = o_.max_area > 0 && 0.5 * norm(cross(b - a, c - a)) > o_.max_area;
    if (o_.chord_sampling == ChordSampling::kFromTriangle) {
      mark[t] = split || triangle_chord_error(s_, a, b, c, m_.tri_uv[t], o_.collapsed,
                                              o_.chord_sampling) > o_.chord_tolerance;
      return;
    }
    for (int i = 0; i < 3 && !split; ++i) {
      const Vec3d& q = edge_point[table_.edge_of_corner[3 * t + i]];
      split = point_triangle_distance(q, a, b, c) > o_.chord_tolerance;
    }
    if (!split) {
      const Vec2d g = o_.collapsed.centroid(m_.tri_uv[t]);
      split = point_triangle_distance(evaluate(s_, g.x, g.y), a, b, c) > o_.chord_tolerance;
    }
    mark[t] = split;
  });
  return mark;
}

// The least set of triangles, containing the marked ones, whose red split keeps the mesh
// 1-irregular (a coarse neighbour of a splitting fine triangle splits too) and leaves no
// unsplit triangle with two or more hanging nodes. Monotone rules: the fixpoint is unique.
std::vector<std::uint8_t> Refiner::propagate(const std::vector<std::uint8_t>& mark) const {
  std::vector<std::uint8_t> in_r(m_.tri_count(), 0);
  std::vector<Index> stack;
  auto add = [&](Index t) {
    if (!in_r[t]) {
      in_r[t] = 1;
      stack.push_back(t);
    }
  };
  for (Index t = 0; t < m_.tri_count(); ++t)
    if (mark[t]) add(t);
  while (!stack.empty()) {
    const Index t = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const Index x = m_.tris[t][i], y = m_.tris[t][(i + 1) % 3];
      const Index e = table_.edge_of_corner[3 * t + i];
      if (table_.size(e) == 2) {
        const Index nb = other_tri(e, t);
        if (!in_r[nb] && hanging_count(nb, in_r) >= 2) add(nb);
        continue;
      }
      if (mid_of(edge_key(x, y)) != kInvalid) continue;  // t is the coarse side
      const Index coarse = coarse_leaf(x, y);
      if (coarse != kInvalid) add(coarse);
    }
  }
  return in_r;
}

bool Refiner::run_level() {
  table_.build(m_.tris);
  std::vector<std::uint8_t> mark = criteria();
  for (std::size_t t = 0; t < forced_.size(); ++t) mark[t] = mark[t] || forced_[t];
  forced_.clear();
  const std::vector<std::uint8_t> in_r = propagate(mark);
  std::vector<NewMid> mids;
  const Index first_id = Index(m_.vertex_count());
  for (Index t = 0; t < m_.tri_count(); ++t) {
    if (!in_r[t]) continue;
    for (int i = 0; i < 3; ++i) {
      const Index a = m_.tris[t][i], b = m_.tris[t][(i + 1) % 3];
      auto [it, inserted] = mid_.try_emplace(edge_key(a, b), Index(first_id + mids.size()));
      if (inserted) mids.push_back({a, b, Index(3 * t + i)});
    }
  }
  bool any = false;
  for (std::uint8_t r : in_r) any = any || r;
  if (!any) return false;
  place_midpoints(mids, first_id);
  split_red(in_r);
  return true;
}

void Refiner::place_midpoints(const std::vector<NewMid>& mids, Index first_id) {
  const std::size_t nv = m_.vertex_count();
  const VertexRings rings = build_rings(m_.tris, nv);
  std::vector<std::uint8_t> boundary(nv);
  for (std::size_t v = 0; v < nv; ++v)
    boundary[v] = (m_.flags[v] & (kOnDomainSide | kOnTrimLoop)) != 0;
  const std::size_t n = nv + mids.size();
  m_.xyz.resize(n);
  m_.uv.resize(n);
  m_.flags.resize(n, 0);
  parent_edge_.resize(n, kNoEdge);
  parallel_for(0, mids.size(),
               [&](std::size_t k) { place_one(rings, boundary, mids[k], Index(first_id + k)); });
}

// Gauss-Newton projection of q onto the surface near `start` (first derivatives only: q is within
// about a chord error of the surface, so a few steps converge), clamped to `box`: one C0 piece,
// since across a knuckle the derivatives jump and the closest point may lie on the wrong face.
// Stops when a (clamped) move is below `resolution` parameter units; returns false when a step is
// not finite.
bool project_local(const NurbsSurface& s, const Box& box, const Vec3d& q, Vec2d& w,
                   double resolution) {
  for (int it = 0; it < kProjectionSteps; ++it) {
    const SurfaceDerivs d = evaluate_derivs(s, w.x, w.y, 1);
    const Vec3d r = q - d.p;
    const double a = dot(d.su, d.su), b = dot(d.su, d.sv), c = dot(d.sv, d.sv);
    const double gu = dot(r, d.su), gv = dot(r, d.sv);
    const double det = a * c - b * b;
    if (!(det > 0)) return false;
    const Vec2d step{(gu * c - gv * b) / det, (gv * a - gu * b) / det};
    if (!std::isfinite(step.x) || !std::isfinite(step.y)) return false;
    const Vec2d next{std::clamp(w.x + step.x, box.u0, box.u1),
                     std::clamp(w.y + step.y, box.v0, box.v1)};
    const Vec2d moved = next - w;
    w = next;
    if (std::abs(moved.x) + std::abs(moved.y) <= resolution) return true;
  }
  return true;
}

// The same along an iso-line (fixed u when fixed_u, else fixed v): a domain side or a knuckle.
bool project_on_iso(const NurbsSurface& s, const Box& box, bool fixed_u, const Vec3d& q, Vec2d& w,
                    double resolution) {
  for (int it = 0; it < kProjectionSteps; ++it) {
    const SurfaceDerivs d = evaluate_derivs(s, w.x, w.y, 1);
    const Vec3d& dt = fixed_u ? d.sv : d.su;
    const double h = dot(dt, dt);
    if (!(h > 0)) return false;
    const double step = dot(q - d.p, dt) / h;
    if (!std::isfinite(step)) return false;
    double& t = fixed_u ? w.y : w.x;
    const double next =
        fixed_u ? std::clamp(t + step, box.v0, box.v1) : std::clamp(t + step, box.u0, box.u1);
    const double moved = next - t;
    t = next;
    if (std::abs(moved) <= resolution) return true;
  }
  return true;
}

void Refiner::place_one(const VertexRings& rings, const std::vector<std::uint8_t>& boundary,
                        const NewMid& nm, Index id) {
  const Index t = nm.corner / 3, i = nm.corner % 3;
  const Vec2d wa = m_.tri_uv[t][i], wb = m_.tri_uv[t][(i + 1) % 3];
  const Vec2d wc = m_.tri_uv[t][(i + 2) % 3];
  Vec2d ea = wa, eb = wb;
  o_.collapsed.edge_ends(ea, eb);
  const Vec2d start = 0.5 * (ea + eb);  // edge_middle
  // The new vertex stays in the C0 piece of its edge: across a knuckle the surface turns away.
  const auto [pu0, pu1] = piece_of(breaks_u_, ea.x, eb.x);
  const auto [pv0, pv1] = piece_of(breaks_v_, ea.y, eb.y);
  const Box box{pu0, pu1, pv0, pv1};
  const Index e = table_.edge_of_corner[nm.corner];
  const Index count = table_.size(e);
  const bool side_u = wa.x == wb.x && (wa.x == s_.u0 || wa.x == s_.u1);
  const bool side_v = wa.y == wb.y && (wa.y == s_.v0 || wa.y == s_.v1);
  // An interior edge along a knuckle keeps its midpoint exactly on the knot line.
  const bool knot_u = count == 2 && wa.x == wb.x && is_break(breaks_u_, wa.x);
  const bool knot_v = count == 2 && wa.y == wb.y && is_break(breaks_v_, wa.y);
  std::uint8_t flags = 0;
  Vec2d w = start;
  if (side_u || side_v || knot_u || knot_v) {
    // A domain side (or a seam) or a knuckle: the new point slides along that line only.
    const bool fixed_u = side_u || (!side_v && knot_u);
    if (side_u || side_v) flags = kOnDomainSide | kSideMidpoint;
    const Vec3d q = butterfly_midpoint(rings, m_.xyz, boundary, nm.a, nm.b, count == 1, o_.tension);
    Vec2d p = start;
    const double ta = fixed_u ? wa.y : wa.x, tb = fixed_u ? wb.y : wb.x;
    if (project_on_iso(s_, box, fixed_u, q, p, kResolution * std::abs(tb - ta))) {
      const double f = ((fixed_u ? p.y : p.x) - ta) / (tb - ta);
      if (std::isfinite(f) && std::abs(f - 0.5) <= kMaxSlideAlong) w = p;
    }
  } else if (count == 2) {
    const Index t2 = other_tri(e, t);
    int i2 = 0;
    while (i2 < 2 && m_.tris[t2][i2] != nm.b) ++i2;
    const bool same_uv = m_.tris[t2][(i2 + 1) % 3] == nm.a && m_.tri_uv[t2][i2] == wb &&
                         m_.tri_uv[t2][(i2 + 1) % 3] == wa;
    if (same_uv) {
      const Vec2d wd = m_.tri_uv[t2][(i2 + 2) % 3];
      const Vec3d q = butterfly_midpoint(rings, m_.xyz, boundary, nm.a, nm.b, false, o_.tension);
      Vec2d p = start;
      const bool ok = project_local(s_, box, q, p, kResolution * norm(wb - wa));
      if (o_.chord_sampling == ChordSampling::kFromTriangle) {
        const Index c = m_.tris[t][(i + 2) % 3], d = m_.tris[t2][(i2 + 2) % 3];
        w = sheared_midpoint(box, q, ok ? p : start, start, nm.a, nm.b, c, d);
      } else {
        // Keep the point well inside the union of the two triangles, so no child inverts.
        const double along = dot(p - wa, wb - wa) / dot(wb - wa, wb - wa);
        const double side_c = orient(wa, wb, p) / orient(wa, wb, wc);
        const double side_d = orient(wb, wa, p) / orient(wb, wa, wd);
        if (ok && std::isfinite(along) && std::abs(along - 0.5) <= kMaxSlideAlong &&
            side_c <= kMaxSlideAcross && side_d <= kMaxSlideAcross)
          w = p;
      }
    }
  } else if ((m_.flags[nm.a] & kOnTrimLoop) && (m_.flags[nm.b] & kOnTrimLoop) &&
             coarse_leaf(nm.a, nm.b) == kInvalid) {
    flags = kOnTrimLoop;  // stays on the sampled loop, which is within tolerance of the curve
  }
  m_.uv[id] = w;
  m_.xyz[id] = evaluate(s_, w.x, w.y);
  m_.flags[id] = flags;
  parent_edge_[id] = edge_key(nm.a, nm.b);
}

// A sheared patch was triangulated on a plane chart, not in (u, v): its parameter lines run side
// by side, so an edge's (u, v) middle can map far off the edge in 3D, and tests in (u, v) say
// nothing of 3D (the generated 100-patch round-bilge hull with gaps, at 40,000 triangles: its
// transom's foot, a patch whose u runs across the transom and back, had an edge 0.28 m long split
// at a point 0.75 m off it, and one child turned over its neighbours). The new point is the
// first of these that lies along the middle half of the edge (a, b) in 3D and leaves the four
// children of (a, b, c) and (b, a, d) facing as their parents do: the projection `p` of the
// butterfly point q, then the surface's nearest point to q from the edge's (u, v) middle. Else
// the (u, v) middle, as before.
Vec2d Refiner::sheared_midpoint(const Box& box, const Vec3d& q, const Vec2d& p, const Vec2d& start,
                                Index a, Index b, Index c, Index d) const {
  const Vec3d &xa = m_.xyz[a], &xb = m_.xyz[b], &xc = m_.xyz[c], &xd = m_.xyz[d];
  const Vec3d ab = xb - xa;
  const Vec3d n_abc = cross(ab, xc - xa), n_bad = cross(xa - xb, xd - xb);
  const auto fits = [&](const Vec2d& w) {
    if (!(w.x >= box.u0 && w.x <= box.u1 && w.y >= box.v0 && w.y <= box.v1)) return false;
    const Vec3d x = evaluate(s_, w.x, w.y);
    const double along = dot(x - xa, ab) / dot(ab, ab);
    return std::isfinite(along) && std::abs(along - 0.5) <= kMaxSlideAlong &&
           dot(cross(x - xa, xc - xa), n_abc) > 0 && dot(cross(xb - x, xc - x), n_abc) > 0 &&
           dot(cross(x - xb, xd - xb), n_bad) > 0 && dot(cross(xa - x, xd - x), n_bad) > 0;
  };
  if (fits(p)) return p;
  const SurfaceProjection near = closest_point(s_, q, start.x, start.y);
  const Vec2d w{near.u, near.v};
  if (near.converged && fits(w)) return w;
  return start;
}

Vec2d Refiner::corner_uv(Index mid, const Vec2d& wa, const Vec2d& wb) const {
  if (!(m_.flags[mid] & kSideMidpoint)) return m_.uv[mid];
  const Vec2d w = m_.uv[mid];
  return wa.x == wb.x ? Vec2d{wa.x, w.y} : Vec2d{w.x, wa.y};
}

void Refiner::split_red(const std::vector<std::uint8_t>& in_r) {
  std::vector<Tri> tris;
  std::vector<TriUv> tri_uv;
  std::vector<std::uint8_t> level, fresh;
  const std::size_t nt = m_.tri_count();
  tris.reserve(nt * 2);
  tri_uv.reserve(nt * 2);
  for (std::size_t t = 0; t < nt; ++t) {
    const Tri& v = m_.tris[t];
    const TriUv& w = m_.tri_uv[t];
    if (!in_r[t]) {
      tris.push_back(v);
      tri_uv.push_back(w);
      level.push_back(level_[t]);
      fresh.push_back(0);
      continue;
    }
    Index mm[3];
    Vec2d mw[3];
    for (int i = 0; i < 3; ++i) {
      mm[i] = mid_of(edge_key(v[i], v[(i + 1) % 3]));
      mw[i] = corner_uv(mm[i], w[i], w[(i + 1) % 3]);
    }
    // Corner children then the middle one, all counter-clockwise.
    tris.push_back({v[0], mm[0], mm[2]});
    tri_uv.push_back({w[0], mw[0], mw[2]});
    tris.push_back({mm[0], v[1], mm[1]});
    tri_uv.push_back({mw[0], w[1], mw[1]});
    tris.push_back({mm[2], mm[1], v[2]});
    tri_uv.push_back({mw[2], mw[1], w[2]});
    tris.push_back({mm[0], mm[1], mm[2]});
    tri_uv.push_back({mw[0], mw[1], mw[2]});
    for (int k = 0; k < 4; ++k) {
      level.push_back(std::uint8_t(level_[t] + 1));
      fresh.push_back(1);
    }
    ++stats_.red;
  }
  m_.tris = std::move(tris);
  m_.tri_uv = std::move(tri_uv);
  level_ = std::move(level);
  fresh_ = std::move(fresh);
}

bool Refiner::green_split(Index t, int& a, Index& mid) const {
  const Tri& v = m_.tris[t];
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    const Index mi = mid_of(edge_key(v[i], v[(i + 1) % 3]));
    if (mi == kInvalid) continue;
    ++count;
    a = i;
    mid = mi;
  }
  if (count > 1) throw InternalError("tessellate: refinement left two hanging nodes on a triangle");
  return count == 1;
}

std::vector<std::uint8_t> Refiner::failing_greens() const {
  std::vector<std::uint8_t> fail(m_.tri_count(), 0);
  std::vector<std::uint8_t> any(1, 0);
  parallel_for(0, m_.tri_count(), [&](std::size_t t) {
    int a = 0;
    Index mid = kInvalid;
    if (level_[t] >= o_.max_levels + kExtraLevels || !green_split(Index(t), a, mid)) return;
    const Tri& v = m_.tris[t];
    const TriUv& w = m_.tri_uv[t];
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const Vec2d mw = corner_uv(mid, w[a], w[b]);
    const Tri halves[2] = {{v[a], mid, v[c]}, {mid, v[b], v[c]}};
    const TriUv hw[2] = {{w[a], mw, w[c]}, {mw, w[b], w[c]}};
    for (int h = 0; h < 2 && !fail[t]; ++h)
      fail[t] =
          triangle_chord_error(s_, m_.xyz[halves[h][0]], m_.xyz[halves[h][1]], m_.xyz[halves[h][2]],
                               hw[h], o_.collapsed, o_.chord_sampling) > o_.chord_tolerance;
  });
  for (std::uint8_t f : fail)
    if (f) return fail;
  return {};
}

void Refiner::close_green() {
  std::vector<Tri> tris;
  std::vector<TriUv> tri_uv;
  tris.reserve(m_.tri_count());
  tri_uv.reserve(m_.tri_count());
  for (std::size_t t = 0; t < m_.tri_count(); ++t) {
    const Tri& v = m_.tris[t];
    const TriUv& w = m_.tri_uv[t];
    int a = 0;
    Index mid = kInvalid;
    if (!green_split(Index(t), a, mid)) {
      tris.push_back(v);
      tri_uv.push_back(w);
      continue;
    }
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const Vec2d mw = corner_uv(mid, w[a], w[b]);
    tris.push_back({v[a], mid, v[c]});
    tri_uv.push_back({w[a], mw, w[c]});
    tris.push_back({mid, v[b], v[c]});
    tri_uv.push_back({mw, w[b], w[c]});
    ++stats_.green;
  }
  m_.tris = std::move(tris);
  m_.tri_uv = std::move(tri_uv);
}

}  // namespace

RefineStats refine_butterfly(const NurbsSurface& s, PatchMesh& m, const RefineOptions& o) {
  if (m.tri_count() == 0) return {};
  Refiner r(s, m, o);
  return r.run();
}

}  // namespace hm
