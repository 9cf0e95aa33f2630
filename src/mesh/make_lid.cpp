// The lid in four steps: collect the waterline (edges on z = 0 bounding the wet faces, chained
// in the faces' direction; a half hull's open chain closed along y = 0), cut each closed waterline
// into triangles by ear clipping, make them Delaunay by edge flips (the waterline edges fixed),
// then insert the points of a hexagonal lattice of the target spacing, each followed by the flips
// that keep the triangulation Delaunay. The lattice gives near-equilateral triangles inside;
// the flips grade them to the waterline's own spacing. Serial and in a fixed order: the same
// lid on every run.
#include "mesh/make_lid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/bbox.h"
#include "core/error.h"
#include "mesh/adjacency.h"

namespace hm {
namespace {

struct P2 {
  double x = 0, y = 0;
};

// Twice the signed area of (o, a, b): positive when counter-clockwise.
double cross(const P2& o, const P2& a, const P2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

// Positive when d lies inside the circle through the counter-clockwise a, b, c.
double incircle(const P2& a, const P2& b, const P2& c, const P2& d) {
  const double adx = a.x - d.x, ady = a.y - d.y;
  const double bdx = b.x - d.x, bdy = b.y - d.y;
  const double cdx = c.x - d.x, cdy = c.y - d.y;
  const double ad = adx * adx + ady * ady, bd = bdx * bdx + bdy * bdy, cd = cdx * cdx + cdy * cdy;
  return adx * (bdy * cd - bd * cdy) - ady * (bdx * cd - bd * cdx) + ad * (bdx * cdy - bdy * cdx);
}

std::string where(double x, double y) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(x = %.4g, y = %.4g)", x, y);
  return buf;
}
std::string where(const Vec3d& p) { return where(p.x, p.y); }
std::string where(const P2& p) { return where(p.x, p.y); }

// One closed waterline: its corners counter-clockwise seen from above, each with the hull
// vertex it is (kInvalid for the points added on y = 0).
struct Loop {
  std::vector<P2> pts;
  std::vector<Index> hull;
};

struct Waterlines {
  std::vector<Loop> loops;
  std::size_t centre_vertices = 0;
  bool half = false;
};

// Edges of the hull with both ends on the plane, in the direction their wet face runs them: a
// boundary edge's one face, or, where the hull goes on above the waterline, the one of an
// interior edge's two faces that lies below the plane.
std::vector<std::array<Index, 2>> waterline_edges(const SurfaceMesh& m, double plane_tol) {
  const EdgeAdjacency adj = build_edge_adjacency(m.faces, m.vertex_count());
  auto on_plane = [&](Index v) { return std::abs(m.positions[v].z) <= plane_tol; };
  auto wet = [&](Index f) {
    const Face& face = m.faces[f];
    for (int c = 0; c < corner_count(face); ++c) {
      if (m.positions[face[c]].z > plane_tol) return false;
    }
    return true;
  };
  auto run = [&](Index slot) -> std::array<Index, 2> {
    const Face& f = m.faces[slot / 4];
    return {f[slot % 4], f[(slot % 4 + 1) % corner_count(f)]};
  };
  std::vector<std::array<Index, 2>> out;
  for (const MeshEdge& e : adj.edges) {
    if (!on_plane(e.v0) || !on_plane(e.v1)) continue;
    if (e.uses == 1) {
      out.push_back(run(e.first_slot));
    } else if (e.uses == 2) {
      const Index f0 = e.first_slot / 4, f1 = adj.opposite_face[e.first_slot];
      if (f1 == kInvalid || wet(f0) == wet(f1)) continue;  // inside the lid's plane, or dry
      out.push_back(wet(f0) ? run(e.first_slot) : run(4 * f1 + adj.opposite_corner[e.first_slot]));
    }
  }
  return out;
}

Waterlines collect_waterlines(const SurfaceMesh& m, double plane_tol, double centre_tol,
                              double spacing) {
  const std::vector<std::array<Index, 2>> edges = waterline_edges(m, plane_tol);
  if (edges.empty()) {
    throw GeometryError(
        "lid: the mesh has no waterline (no edge on z = 0 bounding its wet panels); a lid needs a "
        "hull cut at its "
        "waterplane (--draft or --waterline-z)");
  }
  const std::size_t n = m.vertex_count();
  std::vector<Index> next(n, kInvalid);
  std::vector<char> has_in(n, 0);
  for (const auto& [a, b] : edges) {
    if (next[a] != kInvalid || has_in[b]) {
      throw GeometryError("lid: the waterline branches at " + where(m.positions[a]) +
                          " (more than two free edges meet there)");
    }
    next[a] = b;
    has_in[b] = 1;
  }
  Waterlines w;
  std::vector<char> seen(n, 0);
  std::vector<std::vector<Index>> open, closed;
  auto walk = [&](Index s) {
    std::vector<Index> chain;
    for (Index v = s; v != kInvalid && !seen[v]; v = next[v]) {
      seen[v] = 1;
      chain.push_back(v);
    }
    return chain;
  };
  for (Index v = 0; v < n; ++v) {
    if (next[v] != kInvalid && !has_in[v]) open.push_back(walk(v));
  }
  for (Index v = 0; v < n; ++v) {
    if (next[v] != kInvalid && !seen[v]) closed.push_back(walk(v));
  }
  auto to_loop = [&](const std::vector<Index>& chain) {
    Loop l;
    for (Index v : chain) {
      l.pts.push_back({m.positions[v].x, m.positions[v].y});
      l.hull.push_back(v);
    }
    return l;
  };
  for (const auto& chain : closed) {
    w.loops.push_back(to_loop(chain));
  }
  if (open.size() > 1 || (open.size() == 1 && !closed.empty())) {
    throw GeometryError("lid: the waterline is broken into " +
                        std::to_string(open.size() + closed.size()) +
                        " pieces; one open waterline (a half hull) or closed ones are needed");
  }
  if (open.size() == 1) {
    // A half hull: both ends on the centre plane, closed by points along y = 0.
    const auto& chain = open.front();
    const Vec3d s = m.positions[chain.front()], e = m.positions[chain.back()];
    for (const Vec3d& p : {s, e}) {
      if (std::abs(p.y) > centre_tol) {
        throw GeometryError("lid: the waterline ends at " + where(p) +
                            ", off the centre plane: the hull has an opening there");
      }
    }
    Loop l = to_loop(chain);
    const double len = std::abs(s.x - e.x);
    const int segments = std::max(1, static_cast<int>(std::lround(len / spacing)));
    for (int k = 1; k < segments; ++k) {
      const double t = static_cast<double>(k) / segments;
      l.pts.push_back({e.x + t * (s.x - e.x), 0.0});
      l.hull.push_back(kInvalid);
    }
    w.centre_vertices = static_cast<std::size_t>(segments - 1);
    w.half = true;
    w.loops.push_back(std::move(l));
  }
  for (Loop& l : w.loops) {
    double area2 = 0;
    for (std::size_t k = 0; k < l.pts.size(); ++k)
      area2 += cross({0, 0}, l.pts[k], l.pts[(k + 1) % l.pts.size()]);
    if (area2 < 0) {
      std::reverse(l.pts.begin(), l.pts.end());
      std::reverse(l.hull.begin(), l.hull.end());
    }
  }
  return w;
}

bool inside_polygon(const std::vector<P2>& poly, const P2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const P2& a = poly[i];
    const P2& b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

double distance_to_segment(const P2& p, const P2& a, const P2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy);
}

// A triangle and its neighbours: nb[k] lies across the edge opposite v[k] (-1 on the border).
struct Tri {
  std::array<int, 3> v;
  std::array<int, 3> nb;
};

int index_of(const Tri& t, int v) { return t.v[0] == v ? 0 : (t.v[1] == v ? 1 : 2); }

class Triangulation {
 public:
  explicit Triangulation(std::vector<P2> pts) : p_(std::move(pts)) {}

  // Ear clipping of the polygon 0, 1, ..., n - 1 (counter-clockwise, simple): O(n^2).
  void clip_ears() {
    const int n = static_cast<int>(p_.size());
    std::vector<int> prev(n), next(n);
    for (int i = 0; i < n; ++i) {
      prev[i] = (i + n - 1) % n;
      next[i] = (i + 1) % n;
    }
    std::vector<std::array<int, 3>> tris;
    int remaining = n, v = 0, stall = 0;
    while (remaining > 3) {
      const int a = prev[v], c = next[v];
      if (is_ear(a, v, c, next)) {
        tris.push_back({a, v, c});
        next[a] = c;
        prev[c] = a;
        --remaining;
        v = c;
        stall = 0;
      } else {
        v = next[v];
        if (++stall > remaining) {
          throw GeometryError("lid: the waterline crosses itself near " + where(p_[v]));
        }
      }
    }
    tris.push_back({prev[v], v, next[v]});
    connect(tris);
  }

  // Lawson flips until every interior edge is locally Delaunay.
  void make_delaunay() {
    for (int pass = 0; pass < 64; ++pass) {
      bool flipped = false;
      for (int t = 0; t < static_cast<int>(t_.size()); ++t) {
        for (int k = 0; k < 3; ++k) {
          if (should_flip(t, k)) {
            flip(t, k);
            flipped = true;
          }
        }
      }
      if (!flipped) return;
    }
  }

  // Inserts q (strictly inside the polygon), keeping the triangulation Delaunay.
  void insert(P2 q) {
    int t = locate(q);
    if (t < 0) return;  // outside every triangle (on the border, by rounding): skipped
    const Tri old = t_[t];
    // A point on an edge would leave a flat triangle: move it a hair into this triangle.
    const P2 &a = p_[old.v[0]], &b = p_[old.v[1]], &c = p_[old.v[2]];
    const double area2 = cross(a, b, c);
    const double margin = 1e-6 * area2;
    if (cross(a, b, q) < margin || cross(b, c, q) < margin || cross(c, a, q) < margin) {
      const P2 g{(a.x + b.x + c.x) / 3, (a.y + b.y + c.y) / 3};
      q = {q.x + 1e-3 * (g.x - q.x), q.y + 1e-3 * (g.y - q.y)};
    }
    const int p = static_cast<int>(p_.size());
    p_.push_back(q);
    const int t1 = static_cast<int>(t_.size());
    const int t2 = t1 + 1;
    const int va = old.v[0], vb = old.v[1], vc = old.v[2];
    t_[t] = {{p, va, vb}, {old.nb[2], t1, t2}};
    t_.push_back({{p, vb, vc}, {old.nb[0], t2, t}});
    t_.push_back({{p, vc, va}, {old.nb[1], t, t1}});
    if (old.nb[0] >= 0) replace_nb(old.nb[0], t, t1);
    if (old.nb[1] >= 0) replace_nb(old.nb[1], t, t2);
    last_ = t;
    for (int s : {t, t1, t2}) legalize(s, p);
  }

  // Laplacian smoothing of the points from `first` on (the waterline stays): each moves to the
  // mean of its neighbours unless that would fold one of its triangles. Then flips again.
  void smooth(int first, int iterations) {
    const int n = static_cast<int>(p_.size());
    for (int it = 0; it < iterations; ++it) {
      std::vector<P2> sum(n);
      std::vector<int> count(n, 0);
      std::vector<std::vector<int>> around(n);
      for (int t = 0; t < static_cast<int>(t_.size()); ++t) {
        for (int k = 0; k < 3; ++k) {
          const int a = t_[t].v[k], b = t_[t].v[(k + 1) % 3];
          sum[a].x += p_[b].x;
          sum[a].y += p_[b].y;
          ++count[a];
          around[a].push_back(t);
        }
      }
      for (int v = first; v < n; ++v) {
        if (count[v] == 0) continue;
        const P2 old = p_[v];
        p_[v] = {sum[v].x / count[v], sum[v].y / count[v]};
        for (int t : around[v]) {
          const Tri& tr = t_[t];
          if (!(cross(p_[tr.v[0]], p_[tr.v[1]], p_[tr.v[2]]) > 0)) {
            p_[v] = old;
            break;
          }
        }
      }
      make_delaunay();
    }
  }

  const std::vector<P2>& points() const { return p_; }
  const std::vector<Tri>& triangles() const { return t_; }

 private:
  bool is_ear(int a, int v, int c, const std::vector<int>& next) const {
    const P2 &pa = p_[a], &pv = p_[v], &pc = p_[c];
    if (!(cross(pa, pv, pc) > 0)) return false;
    for (int w = next[c]; w != a; w = next[w]) {
      const P2& q = p_[w];
      if (cross(pa, pv, q) >= 0 && cross(pv, pc, q) >= 0 && cross(pc, pa, q) >= 0) return false;
    }
    return true;
  }

  void connect(const std::vector<std::array<int, 3>>& tris) {
    std::vector<std::array<int, 4>> half;  // lo, hi, triangle, k (edge opposite v[k])
    for (int t = 0; t < static_cast<int>(tris.size()); ++t) {
      t_.push_back({tris[t], {-1, -1, -1}});
      for (int k = 0; k < 3; ++k) {
        const int a = tris[t][(k + 1) % 3], b = tris[t][(k + 2) % 3];
        half.push_back({std::min(a, b), std::max(a, b), t, k});
      }
    }
    std::sort(half.begin(), half.end());
    for (std::size_t i = 0; i + 1 < half.size(); ++i) {
      if (half[i][0] == half[i + 1][0] && half[i][1] == half[i + 1][1]) {
        t_[half[i][2]].nb[half[i][3]] = half[i + 1][2];
        t_[half[i + 1][2]].nb[half[i + 1][3]] = half[i][2];
      }
    }
  }

  void replace_nb(int t, int from, int to) {
    for (int& n : t_[t].nb) {
      if (n == from) n = to;
    }
  }

  // The edge opposite v[k] of t is flipped when the far vertex of its neighbour lies inside t's
  // circumcircle and the two triangles form a convex quadrilateral.
  bool should_flip(int t, int k) const {
    const int u = t_[t].nb[k];
    if (u < 0) return false;
    const int d = t_[u].v[(index_of(t_[u], t_[t].v[(k + 1) % 3]) + 1) % 3];
    const P2 &a = p_[t_[t].v[k]], &b = p_[t_[t].v[(k + 1) % 3]], &c = p_[t_[t].v[(k + 2) % 3]];
    const P2& pd = p_[d];
    if (!(cross(a, b, pd) > 0 && cross(a, pd, c) > 0)) return false;
    const double scale = std::max(
        {std::abs(b.x - a.x), std::abs(b.y - a.y), std::abs(c.x - a.x), std::abs(c.y - a.y)});
    return incircle(a, b, c, pd) > 1e-12 * scale * scale * scale * scale;
  }

  // t = (a, b, c) and its neighbour u across bc, holding d: they become (a, b, d) and (a, d, c).
  void flip(int t, int k) {
    const int u = t_[t].nb[k];
    const int a = t_[t].v[k], b = t_[t].v[(k + 1) % 3], c = t_[t].v[(k + 2) % 3];
    const int n_ab = t_[t].nb[(k + 2) % 3];
    const int n_ca = t_[t].nb[(k + 1) % 3];
    const int ib = index_of(t_[u], b), ic = index_of(t_[u], c);
    const int d = t_[u].v[3 - ib - ic];
    const int n_dc = t_[u].nb[ib];  // u's edge d-c lies opposite b
    const int n_bd = t_[u].nb[ic];  // u's edge b-d lies opposite c
    t_[t] = {{a, b, d}, {n_bd, u, n_ab}};
    t_[u] = {{a, d, c}, {n_dc, n_ca, t}};
    if (n_bd >= 0) replace_nb(n_bd, u, t);
    if (n_ca >= 0) replace_nb(n_ca, t, u);
  }

  // Restores the Delaunay property around the new point p (in triangle t).
  void legalize(int t0, int p) {
    std::vector<int> stack{t0};
    // Flips around one new point are few; the cap only guards against rounding making two
    // flips undo each other forever (the lid is then a little less than Delaunay, not a hang).
    std::size_t budget = 4 * t_.size() + 64;
    while (!stack.empty() && budget-- > 0) {
      const int t = stack.back();
      stack.pop_back();
      const int k = index_of(t_[t], p);
      if (t_[t].v[k] != p || !should_flip(t, k)) continue;
      const int u = t_[t].nb[k];
      flip(t, k);
      stack.push_back(t);
      stack.push_back(u);
    }
  }

  // The triangle holding q: a walk from the last insertion, then a full search.
  int locate(const P2& q) const {
    auto holds = [&](int t) {
      const Tri& tr = t_[t];
      return cross(p_[tr.v[0]], p_[tr.v[1]], q) >= 0 && cross(p_[tr.v[1]], p_[tr.v[2]], q) >= 0 &&
             cross(p_[tr.v[2]], p_[tr.v[0]], q) >= 0;
    };
    int t = last_ >= 0 && last_ < static_cast<int>(t_.size()) ? last_ : 0;
    for (std::size_t step = 0; step < t_.size(); ++step) {
      const Tri& tr = t_[t];
      int next = -1;
      for (int k = 0; k < 3 && next < 0; ++k) {
        if (cross(p_[tr.v[(k + 1) % 3]], p_[tr.v[(k + 2) % 3]], q) < 0) next = tr.nb[k];
      }
      if (next < 0) break;
      t = next;
    }
    if (holds(t)) return t;
    for (int s = 0; s < static_cast<int>(t_.size()); ++s) {
      if (holds(s)) return s;
    }
    return -1;
  }

  std::vector<P2> p_;
  std::vector<Tri> t_;
  int last_ = -1;
};

// The edge of an equilateral triangle with the mean area of the hull's panels (m): the lid gets
// as many panels per square metre as the hull has.
double panel_sized_edge(const SurfaceMesh& m) {
  double area = 0;
  for (const Face& f : m.faces) area += face_area(m.positions, f);
  if (m.faces.empty()) return 0;
  return std::sqrt(area / static_cast<double>(m.faces.size()) / (std::sqrt(3.0) / 4));
}

// Points of a hexagonal lattice of spacing h inside the loop, at least h / 2 from its edges.
std::vector<P2> lattice_points(const Loop& loop, double h) {
  double x0 = loop.pts[0].x, x1 = x0, y0 = loop.pts[0].y, y1 = y0;
  for (const P2& p : loop.pts) {
    x0 = std::min(x0, p.x);
    x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y);
    y1 = std::max(y1, p.y);
  }
  const double dy = h * std::sqrt(3.0) / 2;
  const double rows = (y1 - y0) / dy + 1, cols = (x1 - x0) / h + 2;
  if (rows * cols > 4e6) {
    throw GeometryError("lid: a spacing of " + std::to_string(h) +
                        " m would need more than 4 million lid points");
  }
  std::vector<P2> out;
  const std::size_t n = loop.pts.size();
  for (int j = 0; y0 + j * dy <= y1; ++j) {
    const double y = y0 + j * dy;
    for (int i = 0; x0 + (i - 0.5) * h <= x1; ++i) {
      const P2 q{x0 + (i + 0.5 * (j & 1)) * h, y};
      if (!inside_polygon(loop.pts, q)) continue;
      bool clear = true;
      for (std::size_t k = 0; k < n && clear; ++k) {
        clear = distance_to_segment(q, loop.pts[k], loop.pts[(k + 1) % n]) >= 0.5 * h;
      }
      if (clear) out.push_back(q);
    }
  }
  return out;
}

}  // namespace

Lid make_lid(const SurfaceMesh& hull, const LidOptions& o) {
  BBox3d box;
  for (const Vec3d& p : hull.positions) box.add(p);
  const double size = box.empty() ? 1.0 : std::max(box.diagonal(), 1e-300);
  const double plane_tol = o.plane_tol > 0 ? o.plane_tol : 1e-9 * size;
  const double centre_tol = o.centre_tol > 0 ? o.centre_tol : 1e-6 * size;

  const double h = o.edge_length > 0 ? o.edge_length : panel_sized_edge(hull);
  if (!(h > 0)) throw GeometryError("lid: the hull's panels have no size");

  // Collect: the closed waterlines (a half hull's closed along y = 0 at spacing h).
  const Waterlines w = collect_waterlines(hull, plane_tol, centre_tol, h);
  for (std::size_t i = 0; i < w.loops.size(); ++i) {
    for (std::size_t j = 0; j < w.loops.size(); ++j) {
      if (i != j && inside_polygon(w.loops[i].pts, w.loops[j].pts.front())) {
        throw GeometryError("lid: a waterline lies inside another near " +
                            where(w.loops[j].pts.front()) +
                            " (a moonpool or a second hull inside the first); not supported");
      }
    }
  }

  // Triangulate each loop, then fill it with the lattice.
  Lid lid;
  lid.report.loops = w.loops.size();
  lid.report.centre_vertices = w.centre_vertices;
  lid.report.edge_length = h;
  lid.report.half = w.half;
  for (const Loop& loop : w.loops) {
    Triangulation tri(loop.pts);
    tri.clip_ears();
    tri.make_delaunay();
    for (const P2& q : lattice_points(loop, h)) tri.insert(q);
    tri.smooth(static_cast<int>(loop.pts.size()), 4);

    // Emit: the loop's corners first (the hull's waterline vertices), then the new points.
    const Index base = static_cast<Index>(lid.mesh.positions.size());
    const std::vector<P2>& pts = tri.points();
    for (std::size_t k = 0; k < pts.size(); ++k) {
      lid.mesh.positions.push_back({pts[k].x, pts[k].y, 0.0});
      lid.vert_lid2hull.push_back(k < loop.hull.size() ? loop.hull[k] : kInvalid);
      if (k < loop.hull.size() && loop.hull[k] != kInvalid) ++lid.report.waterline_vertices;
    }
    lid.report.interior_vertices += pts.size() - loop.pts.size();
    for (const Tri& t : tri.triangles()) {
      lid.mesh.faces.push_back({base + static_cast<Index>(t.v[0]),
                                base + static_cast<Index>(t.v[1]),
                                base + static_cast<Index>(t.v[2]), kInvalid});
      lid.report.area += 0.5 * cross(pts[t.v[0]], pts[t.v[1]], pts[t.v[2]]);
    }
  }
  lid.mesh.face_patch.assign(lid.mesh.faces.size(), kInvalid);
  lid.mesh.face_block.assign(lid.mesh.faces.size(), kInvalid);
  return lid;
}

SurfaceMesh append_lid(const SurfaceMesh& hull, const Lid& lid) {
  SurfaceMesh out = hull;
  std::vector<Index> lid2out(lid.mesh.vertex_count());
  for (std::size_t k = 0; k < lid2out.size(); ++k) {
    if (lid.vert_lid2hull[k] != kInvalid) {
      lid2out[k] = lid.vert_lid2hull[k];
    } else {
      lid2out[k] = static_cast<Index>(out.positions.size());
      out.positions.push_back(lid.mesh.positions[k]);
      if (!out.vertex_patch.empty()) out.vertex_patch.push_back(kInvalid);
      if (!out.vertex_uv.empty()) out.vertex_uv.push_back({0, 0});
    }
  }
  if (out.face_patch.size() < out.faces.size()) out.face_patch.resize(out.faces.size(), kInvalid);
  const bool blocks = !out.face_block.empty();
  for (const Face& f : lid.mesh.faces) {
    out.faces.push_back({lid2out[f[0]], lid2out[f[1]], lid2out[f[2]], kInvalid});
    out.face_patch.push_back(kInvalid);
    if (blocks) out.face_block.push_back(kInvalid);
  }
  return out;
}

}  // namespace hm
