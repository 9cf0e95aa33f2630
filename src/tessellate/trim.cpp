#include "tessellate/trim.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "tessellate/cdt.h"
#include "tessellate/degenerate.h"

namespace hm {
namespace {

// Loops closed without the repeated last point and clamped into the domain.
std::vector<std::vector<Vec2d>> clean_loops(std::vector<std::vector<Vec2d>> loops,
                                            const NurbsSurface& s) {
  std::vector<std::vector<Vec2d>> out;
  for (auto& l : loops) {
    for (Vec2d& w : l) w = {std::clamp(w.x, s.u0, s.u1), std::clamp(w.y, s.v0, s.v1)};
    std::vector<Vec2d> c;
    for (const Vec2d& w : l)
      if (c.empty() || !(w == c.back())) c.push_back(w);
    while (c.size() > 1 && c.back() == c.front()) c.pop_back();
    if (c.size() >= 3) out.push_back(std::move(c));
  }
  return out;
}

// Splits loop segments longer than edge_length in 3D (points on the polygon's chords, which lie
// within the sampling tolerance of the trim curve).
std::vector<Vec2d> split_long(const NurbsSurface& s, const std::vector<Vec2d>& l, double h) {
  std::vector<Vec2d> out;
  for (std::size_t i = 0; i < l.size(); ++i) {
    const Vec2d a = l[i], b = l[(i + 1) % l.size()];
    const double len = norm(evaluate(s, b.x, b.y) - evaluate(s, a.x, a.y));
    const int n = std::max(1, static_cast<int>(std::ceil(len / h)));
    for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (double(k) / n));
  }
  return out;
}

double segment_distance(const Vec2d& p, const Vec2d& a, const Vec2d& b) {
  const Vec2d ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
  return norm(p - (a + ab * t));
}

std::uint8_t side_flags(const NurbsSurface& s, const Vec2d& w) {
  return (w.x == s.u0 || w.x == s.u1 || w.y == s.v0 || w.y == s.v1) ? kOnDomainSide : 0;
}

}  // namespace

PatchMesh trimmed_mesh(const Patch& p, const GridLines& lines, double h, double tol) {
  const NurbsSurface& s = p.surface;
  const double speed = std::max({lines.speed_u, lines.speed_v, 1e-300});
  const double tol_uv = 0.5 * tol / speed;
  std::vector<std::vector<Vec2d>> loops = clean_loops(sample_loops_uv(p, tol_uv), s);
  if (loops.empty())
    throw GeometryError("tessellate: patch " + p.name + " has no usable trim loop");
  // Holes only: the outer loop was the natural boundary of the domain (dropped on import).
  bool has_outer = false;
  for (const TrimLoop& l : p.loops) has_outer = has_outer || l.outer;
  if (!has_outer)
    loops.insert(loops.begin(), {{s.u0, s.v0}, {s.u1, s.v0}, {s.u1, s.v1}, {s.u0, s.v1}});
  for (auto& l : loops) l = split_long(s, l, h);
  // Scaled (u, v): about metres, so that Delaunay angles and clearances mean something in 3D.
  const double su = lines.mean_speed_u > 0 ? lines.mean_speed_u : 1.0;
  const double sv = lines.mean_speed_v > 0 ? lines.mean_speed_v : 1.0;
  auto scaled = [&](const Vec2d& w) { return Vec2d{(w.x - s.u0) * su, (w.y - s.v0) * sv}; };

  std::vector<Vec2d> uv, xy;
  std::vector<std::uint8_t> flags;
  std::vector<Segment> segments;
  std::vector<std::vector<Vec2d>> scaled_loops;
  for (const auto& l : loops) {
    const Index base = Index(uv.size());
    std::vector<Vec2d> sl;
    for (std::size_t i = 0; i < l.size(); ++i) {
      uv.push_back(l[i]);
      xy.push_back(scaled(l[i]));
      sl.push_back(xy.back());
      flags.push_back(kOnTrimLoop | side_flags(s, l[i]));
      segments.push_back({Index(base + i), Index(base + (i + 1) % l.size())});
    }
    scaled_loops.push_back(std::move(sl));
  }
  // Interior grid points, kept where inside and clear of the loops.
  const std::size_t nu = lines.u.size(), nv = lines.v.size();
  std::vector<std::uint8_t> keep(nu * nv, 0);
  const double clearance = kLoopClearance * h;
  // A grid point is kept when it is inside the region by the even-odd rule (an odd number of
  // loop edges cross its row to its right) and clear of every loop edge. Row by row: every point
  // of a grid row has the same scaled v, so the edges that cross the row and those that come
  // within the clearance of it are found once per row, not once per point; the points kept are
  // the same as testing every edge.
  parallel_for(
      0, nv,
      [&](std::size_t j) {
        const double y = scaled({s.u0, lines.v[j]}).y;
        std::vector<double> crossings;
        std::vector<std::array<Vec2d, 2>> near;
        for (const auto& l : scaled_loops) {
          for (std::size_t i = 0, prev = l.size() - 1; i < l.size(); prev = i++) {
            const Vec2d& a = l[i];
            const Vec2d& b = l[prev];
            if ((a.y > y) != (b.y > y))
              crossings.push_back((b.x - a.x) * (y - a.y) / (b.y - a.y) + a.x);
            const Vec2d& c = l[(i + 1) % l.size()];
            if (std::min(a.y, c.y) - clearance <= y && y <= std::max(a.y, c.y) + clearance) {
              near.push_back({a, c});
            }
          }
        }
        std::sort(crossings.begin(), crossings.end());
        for (std::size_t i = 0; i < nu; ++i) {
          const Vec2d q = scaled({lines.u[i], lines.v[j]});
          const auto right =
              crossings.end() - std::upper_bound(crossings.begin(), crossings.end(), q.x);
          if (right % 2 == 0) continue;
          bool clear = true;
          for (const auto& [a, c] : near) {
            if (std::min(a.x, c.x) - clearance <= q.x && q.x <= std::max(a.x, c.x) + clearance &&
                segment_distance(q, a, c) < clearance) {
              clear = false;
              break;
            }
          }
          keep[i + nu * j] = clear;
        }
      },
      1, 2);
  for (std::size_t k = 0; k < nu * nv; ++k) {
    if (!keep[k]) continue;
    const Vec2d w{lines.u[k % nu], lines.v[k / nu]};
    uv.push_back(w);
    xy.push_back(scaled(w));
    flags.push_back(side_flags(s, w));
  }
  const std::vector<Tri> tris = triangulate_region(xy, segments);
  PatchMesh m;
  m.uv = std::move(uv);
  m.flags = std::move(flags);
  m.xyz.resize(m.uv.size());
  parallel_for(0, m.uv.size(),
               [&](std::size_t v) { m.xyz[v] = evaluate(s, m.uv[v].x, m.uv[v].y); });
  for (const Tri& t : tris) m.add_tri(t, {m.uv[t[0]], m.uv[t[1]], m.uv[t[2]]});
  compact_vertices(m);
  return m;
}

}  // namespace hm
