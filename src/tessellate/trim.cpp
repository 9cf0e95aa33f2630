#include "tessellate/trim.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"
#include "tessellate/cdt.h"
#include "tessellate/degenerate.h"
#include "tessellate/flip_edges.h"

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

// The sides of the domain as one counter-clockwise loop through the grid lines' ends, each side
// walked so that a sample is kept only when skipping it would make a step longer than h in 3D: a
// sheared patch's grid crowds along some sides. Corners are always kept.
std::vector<Vec2d> domain_loop(const NurbsSurface& s, const GridLines& lines, double h) {
  const std::size_t nu = lines.u.size(), nv = lines.v.size();
  std::vector<std::vector<Vec2d>> sides(4);
  for (std::size_t i = 0; i < nu; ++i) sides[0].push_back({lines.u[i], s.v0});
  for (std::size_t j = 0; j < nv; ++j) sides[1].push_back({s.u1, lines.v[j]});
  for (std::size_t i = nu; i-- > 0;) sides[2].push_back({lines.u[i], s.v1});
  for (std::size_t j = nv; j-- > 0;) sides[3].push_back({s.u0, lines.v[j]});
  std::vector<Vec2d> loop;
  for (const auto& side : sides) {
    std::vector<Vec3d> at(side.size());
    for (std::size_t k = 0; k < side.size(); ++k) at[k] = evaluate(s, side[k].x, side[k].y);
    const std::size_t last = side.size() - 1;
    loop.push_back(side[0]);
    for (std::size_t k = 0; k < last;) {
      std::size_t next = k + 1;
      while (next < last && norm(at[next + 1] - at[k]) <= h) ++next;
      if (next < last) loop.push_back(side[next]);
      k = next;
    }
  }
  return loop;
}

// Of the candidates (in order), those at least `radius` in 3D from every fixed point and from every
// candidate kept before them: a greedy, serial thinning on a hash grid of cell `radius`.
std::vector<std::uint8_t> thin_in_3d(std::span<const Vec3d> fixed, std::span<const Vec3d> cand,
                                     double radius) {
  struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell&) const = default;
  };
  const auto cell_of = [&](const Vec3d& p) {
    return Cell{std::int64_t(std::floor(p.x / radius)), std::int64_t(std::floor(p.y / radius)),
                std::int64_t(std::floor(p.z / radius))};
  };
  const auto hash = [](const Cell& c) {
    return std::uint64_t(c.x) * 73856093u ^ std::uint64_t(c.y) * 19349663u ^
           std::uint64_t(c.z) * 83492791u;
  };
  std::vector<std::vector<Vec3d>> buckets;
  const std::size_t nb = std::max<std::size_t>(64, 2 * (fixed.size() + cand.size()));
  buckets.resize(nb);
  const auto insert = [&](const Vec3d& p) { buckets[hash(cell_of(p)) % nb].push_back(p); };
  const double r2 = radius * radius;
  const auto clear = [&](const Vec3d& p) {
    const Cell c = cell_of(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz)
          for (const Vec3d& q : buckets[hash({c.x + dx, c.y + dy, c.z + dz}) % nb])
            if (squared_norm(q - p) < r2) return false;
    return true;
  };
  for (const Vec3d& p : fixed) insert(p);
  std::vector<std::uint8_t> keep(cand.size(), 0);
  for (std::size_t i = 0; i < cand.size(); ++i) {
    if (!clear(cand[i])) continue;
    keep[i] = 1;
    insert(cand[i]);
  }
  return keep;
}

// A plane on which a sheared patch is a graph: through the centre of its samples, normal to their
// area-weighted mean normal (su x sv), valid when the normals are within 75 degrees of it, but
// for samples that carry at most kChartFoldShare of the total |su x sv|: a patch with two sides
// in line folds over by a hair where its Jacobian vanishes (ship_449's keel plate, DE 8385), and
// the loop's samples and the thinning keep the mesh out of the fold.
constexpr double kChartCosTilt = 0.26;  // cos 75 degrees
constexpr double kChartFoldShare = 0.02;

struct PlaneChart {
  Vec3d origin, e1, e2;
  Vec2d operator()(const Vec3d& p) const { return {dot(p - origin, e1), dot(p - origin, e2)}; }
};

std::optional<PlaneChart> plane_chart(const NormalSamples& ns) {
  const double len = norm(ns.sum);
  if (!(len > 0) || ns.at.empty()) return std::nullopt;
  const Vec3d n = ns.sum / len;
  if (ns.share_beyond(n, kChartCosTilt) > kChartFoldShare) return std::nullopt;
  Vec3d centre{};
  for (const Vec3d& q : ns.at) centre += q;
  // Any unit vector normal to n, then the third by the right-hand rule (counter-clockwise in the
  // chart is counter-clockwise seen from the side su x sv points to).
  const Vec3d t = std::abs(n.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  const Vec3d e1 = cross(t, n) / norm(cross(t, n));
  return PlaneChart{centre / double(ns.at.size()), e1, cross(n, e1)};
}

}  // namespace

PatchMesh trimmed_mesh(const Patch& p, const GridLines& lines, double h, double tol,
                       const NormalSamples* sheared) {
  const NurbsSurface& s = p.surface;
  const double speed = std::max({lines.speed_u, lines.speed_v, 1e-300});
  const double tol_uv = 0.5 * tol / speed;
  std::vector<std::vector<Vec2d>> loops = clean_loops(sample_loops_uv(p, tol_uv), s);
  if (loops.empty() && !p.loops.empty())
    throw GeometryError("tessellate: patch " + p.name + " has no usable trim loop");
  // Holes only: the outer loop was the natural boundary of the domain (dropped on import).
  bool has_outer = false;
  for (const TrimLoop& l : p.loops) has_outer = has_outer || l.outer;
  if (p.loops.empty())
    loops.push_back(domain_loop(s, lines, h));
  else if (!has_outer)
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
  std::vector<Vec2d> inner;
  for (std::size_t k = 0; k < nu * nv; ++k)
    if (keep[k]) inner.push_back({lines.u[k % nu], lines.v[k / nu]});
  const std::size_t n_loop = uv.size();
  std::vector<Vec3d> xyz(n_loop + inner.size());
  for (std::size_t k = 0; k < inner.size(); ++k) uv.push_back(inner[k]);
  parallel_for(0, uv.size(), [&](std::size_t v) { xyz[v] = evaluate(s, uv[v].x, uv[v].y); });
  // Sheared: the grid's lines crowd in 3D where the parameter lines run side by side; keep the
  // grid points about an edge apart in 3D.
  std::vector<std::uint8_t> inner_keep(inner.size(), 1);
  if (sheared) {
    inner_keep = thin_in_3d(std::span(xyz).first(n_loop), std::span(xyz).subspan(n_loop),
                            kShearedSpacing * h);
  }
  std::size_t out = n_loop;
  for (std::size_t k = 0; k < inner.size(); ++k) {
    if (!inner_keep[k]) continue;
    uv[out] = inner[k];
    xyz[out++] = xyz[n_loop + k];
    xy.push_back(scaled(inner[k]));
    flags.push_back(side_flags(s, inner[k]));
  }
  uv.resize(out);
  xyz.resize(out);
  // A Delaunay triangulation in a sheared parameter plane is far from one in 3D: such a patch is
  // triangulated on a plane it is a graph over where it has one, and its edges are flipped for 3D
  // angles either way. A chart whose loops cross (a patch curling past 75 degrees from its mean
  // normal was not caught by the samples) falls back to the parameter plane.
  std::vector<Tri> tris;
  std::vector<Vec2d> chart_xy;
  if (const std::optional<PlaneChart> chart = sheared ? plane_chart(*sheared) : std::nullopt) {
    for (const Vec3d& q : xyz) chart_xy.push_back((*chart)(q));
    try {
      tris = triangulate_region(chart_xy, segments);
    } catch (const GeometryError&) {
      chart_xy.clear();
    }
  }
  if (chart_xy.empty()) tris = triangulate_region(xy, segments);
  PatchMesh m;
  m.uv = std::move(uv);
  m.flags = std::move(flags);
  m.xyz = std::move(xyz);
  for (const Tri& t : tris) m.add_tri(t, {m.uv[t[0]], m.uv[t[1]], m.uv[t[2]]});
  if (sheared) flip_edges_3d(m, chart_xy.empty() ? std::span<const Vec2d>(xy) : chart_xy);
  compact_vertices(m);
  return m;
}

}  // namespace hm
