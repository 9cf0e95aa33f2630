#include "tessellate/cdt.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <unordered_set>

#include "core/error.h"

namespace hm {
namespace {

constexpr double kSuperRadius = 50;  // super triangle around the unit box, in normalised units
constexpr double kSamePoint = 1e-12;
constexpr double kCollinear = 1e-13;

double orient(const Vec2d& a, const Vec2d& b, const Vec2d& c) { return cross(b - a, c - a); }

// > 0 when d is inside the circle through the counter-clockwise a, b, c.
double incircle(const Vec2d& a, const Vec2d& b, const Vec2d& c, const Vec2d& d) {
  const double ax = a.x - d.x, ay = a.y - d.y, bx = b.x - d.x, by = b.y - d.y;
  const double cx = c.x - d.x, cy = c.y - d.y;
  const double a2 = ax * ax + ay * ay, b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  return ax * (by * c2 - b2 * cy) - ay * (bx * c2 - b2 * cx) + a2 * (bx * cy - by * cx);
}

struct CTri {
  Index v[3];
  Index n[3];  // n[i]: neighbour across the edge opposite v[i]
  bool alive = true;
};

class Triangulator {
 public:
  explicit Triangulator(std::span<const Vec2d> input);
  std::vector<Tri> run(std::span<const Segment> segments);

 private:
  Index insert(Index p);
  Index locate(const Vec2d& p) const;
  void replace_neighbour(Index t, Index old_nb, Index new_nb);
  bool has_edge(Index a, Index b) const;
  void recover(Index a, Index b, std::vector<Segment>& pending);
  bool flip(Index u, Index w);
  int index_of(Index t, Index v) const {
    for (int i = 0; i < 3; ++i)
      if (tris_[t].v[i] == v) return i;
    return -1;
  }
  const Vec2d& pt(Index v) const { return pts_[v]; }

  std::vector<Vec2d> pts_;     // normalised inputs, then the 3 super vertices
  std::vector<Index> merged_;  // input index -> vertex used
  std::vector<CTri> tris_;
  std::vector<Index> vt_;  // a live triangle at each vertex
  std::size_t n_input_ = 0;
  Index last_ = 0;
  std::vector<Index> stamp_;
  Index epoch_ = 0;
  std::vector<Index> fan_at_;  // per vertex: the new triangle starting there (insert's scratch)
};

Triangulator::Triangulator(std::span<const Vec2d> input) : n_input_(input.size()) {
  Vec2d lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const Vec2d& p : input) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  const double ext = std::max({hi.x - lo.x, hi.y - lo.y, 1e-300});
  pts_.reserve(input.size() + 3);
  for (const Vec2d& p : input) pts_.push_back((p - lo) * (1.0 / ext));
  const Vec2d c{0.5, 0.5};
  const double r = kSuperRadius, s3 = std::sqrt(3.0);
  pts_.push_back(c + Vec2d{-s3 * r, -r});
  pts_.push_back(c + Vec2d{s3 * r, -r});
  pts_.push_back(c + Vec2d{0, 2 * r});
  const Index s0 = Index(n_input_);
  tris_.push_back({{s0, s0 + 1, s0 + 2}, {kInvalid, kInvalid, kInvalid}, true});
  vt_.assign(pts_.size(), 0);
  fan_at_.assign(pts_.size(), kInvalid);
  merged_.resize(n_input_);
  for (Index i = 0; i < n_input_; ++i) merged_[i] = insert(i);
}

Index Triangulator::locate(const Vec2d& p) const {
  Index t = last_;
  if (!tris_[t].alive) t = Index(tris_.size() - 1);
  for (std::size_t steps = 0; steps < 4 * tris_.size() + 16; ++steps) {
    const CTri& tr = tris_[t];
    int exit = -1;
    for (int i = 0; i < 3 && exit < 0; ++i)
      if (orient(pt(tr.v[(i + 1) % 3]), pt(tr.v[(i + 2) % 3]), p) < 0 && tr.n[i] != kInvalid)
        exit = i;
    if (exit < 0) return t;
    t = tr.n[exit];
  }
  // A walk that cycles (round-off on nearly collinear points): take the best triangle.
  Index best = 0;
  double best_score = -1e300;
  for (Index k = 0; k < tris_.size(); ++k) {
    if (!tris_[k].alive) continue;
    double worst = 1e300;
    for (int i = 0; i < 3; ++i)
      worst = std::min(worst, orient(pt(tris_[k].v[(i + 1) % 3]), pt(tris_[k].v[(i + 2) % 3]), p));
    if (worst > best_score) best_score = worst, best = k;
  }
  return best;
}

void Triangulator::replace_neighbour(Index t, Index old_nb, Index new_nb) {
  if (t == kInvalid) return;
  for (Index& n : tris_[t].n)
    if (n == old_nb) n = new_nb;
}

Index Triangulator::insert(Index p) {
  const Vec2d& q = pt(p);
  const Index t0 = locate(q);
  for (Index v : tris_[t0].v)
    if (v < n_input_ && norm(pt(v) - q) <= kSamePoint) return v;
  // Cavity: triangles whose circumcircle holds q, grown from the one that contains it.
  ++epoch_;
  stamp_.resize(tris_.size(), 0);
  std::vector<Index> cavity{t0};
  stamp_[t0] = epoch_;
  for (std::size_t k = 0; k < cavity.size(); ++k) {
    for (Index nb : tris_[cavity[k]].n) {
      if (nb == kInvalid || stamp_[nb] == epoch_) continue;
      const CTri& tr = tris_[nb];
      if (incircle(pt(tr.v[0]), pt(tr.v[1]), pt(tr.v[2]), q) > 0) {
        stamp_[nb] = epoch_;
        cavity.push_back(nb);
      }
    }
  }
  struct Border {
    Index a, b, outside, owner;
  };
  std::vector<Border> border;
  // Round-off can admit a triangle whose far edge q does not see: drop it until all edges do.
  for (bool again = true; again;) {
    again = false;
    border.clear();
    for (std::size_t k = 0; k < cavity.size() && !again; ++k) {
      const CTri& tr = tris_[cavity[k]];
      for (int i = 0; i < 3; ++i) {
        const Index nb = tr.n[i];
        if (nb != kInvalid && stamp_[nb] == epoch_) continue;
        const Index a = tr.v[(i + 1) % 3], b = tr.v[(i + 2) % 3];
        if (orient(pt(a), pt(b), q) <= 0 && cavity[k] != t0) {
          stamp_[cavity[k]] = 0;
          cavity.erase(cavity.begin() + std::ptrdiff_t(k));
          again = true;
          break;
        }
        border.push_back({a, b, nb, cavity[k]});
      }
    }
  }
  const Index first = Index(tris_.size());
  for (const Border& e : border) {
    const Index t = Index(tris_.size());
    tris_.push_back({{e.a, e.b, p}, {kInvalid, kInvalid, e.outside}, true});
    replace_neighbour(e.outside, e.owner, t);
    vt_[e.a] = t;
    vt_[e.b] = t;
  }
  // Link the fan around p: new triangle (a, b, p) meets (b, c, p) across (b, p). Each vertex of
  // a simple cavity starts one border edge, so the triangle starting at b is looked up by b (a
  // cavity on a patch's grid has about 13 sides, and comparing every pair of new triangles was
  // most of the insertion). A vertex starting two edges (never seen) takes the pairwise rule,
  // whose last match wins, as it always did.
  bool simple = true;
  for (Index t = first; t < tris_.size(); ++t) {
    Index& at = fan_at_[tris_[t].v[0]];
    simple = simple && at == kInvalid;
    at = t;
  }
  if (simple) {
    for (Index t = first; t < tris_.size(); ++t) {
      const Index u = fan_at_[tris_[t].v[1]];
      if (u == kInvalid) continue;
      tris_[t].n[0] = u;
      tris_[u].n[1] = t;
    }
  } else {
    for (Index t = first; t < tris_.size(); ++t) {
      for (Index u = first; u < tris_.size(); ++u) {
        if (tris_[u].v[0] == tris_[t].v[1]) {
          tris_[t].n[0] = u;
          tris_[u].n[1] = t;
        }
      }
    }
  }
  for (Index t = first; t < tris_.size(); ++t) fan_at_[tris_[t].v[0]] = kInvalid;
  for (Index c : cavity) tris_[c].alive = false;
  vt_[p] = first;
  last_ = first;
  return p;
}

bool Triangulator::has_edge(Index a, Index b) const {
  Index t = vt_[a];
  for (std::size_t k = 0; k < tris_.size(); ++k) {
    const int i = index_of(t, a);
    if (i < 0) return false;
    if (tris_[t].v[(i + 1) % 3] == b || tris_[t].v[(i + 2) % 3] == b) return true;
    t = tris_[t].n[(i + 1) % 3];  // across (v[i + 2], a): next triangle clockwise around a
    if (t == kInvalid || t == vt_[a]) return false;
  }
  return false;
}

// Flips edge (u, w) when its quad is strictly convex; false otherwise.
bool Triangulator::flip(Index u, Index w) {
  Index t = vt_[u];
  int i = -1;
  for (std::size_t k = 0; k < tris_.size(); ++k) {
    const int iu = index_of(t, u);
    if (iu >= 0 && tris_[t].v[(iu + 1) % 3] == w) {
      i = (iu + 2) % 3;  // opposite vertex p
      break;
    }
    t = tris_[t].n[(iu + 1) % 3];
    if (t == kInvalid || t == vt_[u]) return false;
  }
  if (i < 0) return false;
  const Index p = tris_[t].v[i];
  const Index t2 = tris_[t].n[i];
  if (t2 == kInvalid) return false;
  const int j = index_of(t2, u) >= 0 ? (index_of(t2, u) + 1) % 3 : -1;  // opposite vertex q
  if (j < 0) return false;
  const Index q = tris_[t2].v[j];
  if (!(orient(pt(p), pt(u), pt(q)) > 0 && orient(pt(q), pt(w), pt(p)) > 0)) return false;
  // Neighbours of the quad's outer edges, by the vertex opposite them.
  const Index t_pu = tris_[t].n[index_of(t, w)];    // edge (p, u)
  const Index t_wp = tris_[t].n[index_of(t, u)];    // edge (w, p)
  const Index t_uq = tris_[t2].n[index_of(t2, w)];  // edge (u, q)
  const Index t_qw = tris_[t2].n[index_of(t2, u)];  // edge (q, w)
  tris_[t].v[0] = p, tris_[t].v[1] = u, tris_[t].v[2] = q;
  tris_[t].n[0] = t_uq, tris_[t].n[1] = t2, tris_[t].n[2] = t_pu;
  tris_[t2].v[0] = q, tris_[t2].v[1] = w, tris_[t2].v[2] = p;
  tris_[t2].n[0] = t_wp, tris_[t2].n[1] = t, tris_[t2].n[2] = t_qw;
  replace_neighbour(t_uq, t2, t);
  replace_neighbour(t_wp, t, t2);
  vt_[u] = t, vt_[p] = t, vt_[q] = t, vt_[w] = t2;
  return true;
}

bool crosses(const Vec2d& a, const Vec2d& b, const Vec2d& c, const Vec2d& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d);
  const double o3 = orient(c, d, a), o4 = orient(c, d, b);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

void Triangulator::recover(Index a, Index b, std::vector<Segment>& pending) {
  const Vec2d pa = pt(a), pb = pt(b);
  const Vec2d ab = pb - pa;
  const double len2 = dot(ab, ab);
  // A vertex on the segment splits it.
  for (Index v = 0; v < n_input_; ++v) {
    if (v == a || v == b || merged_[v] != v) continue;
    const double f = dot(pt(v) - pa, ab) / len2;
    if (f <= 0 || f >= 1) continue;
    if (std::abs(orient(pa, pb, pt(v))) <= kCollinear * std::sqrt(len2)) {
      pending.push_back({a, v});
      pending.push_back({v, b});
      return;
    }
  }
  std::deque<Segment> crossing;
  for (const CTri& tr : tris_) {
    if (!tr.alive) continue;
    for (int i = 0; i < 3; ++i) {
      const Index u = tr.v[(i + 1) % 3], w = tr.v[(i + 2) % 3];
      if (u < w && crosses(pa, pb, pt(u), pt(w))) crossing.push_back({u, w});
    }
  }
  std::size_t budget = 64 * crossing.size() + 256;
  while (!crossing.empty()) {
    if (budget-- == 0) throw GeometryError("tessellate: a trim loop segment cannot be recovered");
    const Segment e = crossing.front();
    crossing.pop_front();
    if (!flip(e[0], e[1])) {
      crossing.push_back(e);
      continue;
    }
    // The new diagonal is (p, q): the vertices now shared by the two flipped triangles.
    const CTri& tr = tris_[vt_[e[0]]];
    const Index p = tr.v[0], q = tr.v[2];
    if (p != a && p != b && q != a && q != b && crosses(pa, pb, pt(p), pt(q)))
      crossing.push_back({p, q});
  }
}

std::vector<Tri> Triangulator::run(std::span<const Segment> segments) {
  std::vector<Segment> pending;
  for (auto it = segments.rbegin(); it != segments.rend(); ++it)
    pending.push_back({merged_[(*it)[0]], merged_[(*it)[1]]});
  std::unordered_set<std::uint64_t> fixed;
  std::size_t guard = 8 * segments.size() + 64;
  while (!pending.empty()) {
    const Segment s = pending.back();
    pending.pop_back();
    if (s[0] == s[1]) continue;
    if (!has_edge(s[0], s[1])) {
      if (guard-- == 0) throw GeometryError("tessellate: trim loops cross each other");
      const std::size_t before = pending.size();
      recover(s[0], s[1], pending);
      if (pending.size() != before) continue;  // split at a vertex on it
      if (!has_edge(s[0], s[1])) throw GeometryError("tessellate: trim segment not recovered");
    }
    fixed.insert(edge_key(s[0], s[1]));
  }
  // Depth by 0-1 breadth-first search from the super triangle's region.
  std::vector<int> depth(tris_.size(), -1);
  std::deque<Index> queue;
  for (Index t = 0; t < tris_.size(); ++t) {
    if (!tris_[t].alive) continue;
    for (Index v : tris_[t].v)
      if (v >= n_input_ && depth[t] < 0) {
        depth[t] = 0;
        queue.push_back(t);
      }
  }
  while (!queue.empty()) {
    const Index t = queue.front();
    queue.pop_front();
    for (int i = 0; i < 3; ++i) {
      const Index nb = tris_[t].n[i];
      if (nb == kInvalid) continue;
      const bool wall = fixed.count(edge_key(tris_[t].v[(i + 1) % 3], tris_[t].v[(i + 2) % 3]));
      const int d = depth[t] + (wall ? 1 : 0);
      if (depth[nb] >= 0 && depth[nb] <= d) continue;
      depth[nb] = d;
      wall ? queue.push_back(nb) : queue.push_front(nb);
    }
  }
  std::vector<Tri> out;
  for (Index t = 0; t < tris_.size(); ++t) {
    const CTri& tr = tris_[t];
    if (!tr.alive || depth[t] % 2 == 0) continue;
    if (tr.v[0] >= n_input_ || tr.v[1] >= n_input_ || tr.v[2] >= n_input_) continue;
    out.push_back({tr.v[0], tr.v[1], tr.v[2]});
  }
  return out;
}

}  // namespace

std::vector<Tri> triangulate_region(std::span<const Vec2d> points,
                                    std::span<const Segment> segments) {
  if (points.size() < 3) return {};
  Triangulator tr(points);
  return tr.run(segments);
}

}  // namespace hm
