#include "tessellate/initial_grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "nurbs/evaluate_grid.h"

namespace hm {
namespace {

constexpr int kLengthSegments = 8;  // polyline segments per knot span when measuring a line
constexpr int kSampleLines = 7;     // parameter lines measured across the other direction
constexpr int kMaxCellsPerSpan = 1 << 16;

// Evenly spread values across [a, b], ends included.
std::vector<double> spread(double a, double b, int n) {
  std::vector<double> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) out[i] = a + (b - a) * (n == 1 ? 0.5 : double(i) / (n - 1));
  return out;
}

struct Direction {
  std::vector<double> lines;
  double max_speed = 0;
  double mean_speed = 0;
};

// Points of the iso-parameter lines at the values `across` of the other direction, at the
// parameters `along`: out[i + along.size() * j] lies on line j at along[i]. One grid evaluation
// (each basis computed once), bit-identical to evaluate() point by point.
std::vector<Vec3d> iso_line_points(const NurbsSurface& s, bool along_u,
                                   const std::vector<double>& along,
                                   const std::vector<double>& across) {
  if (along_u) return evaluate_grid(s, along, across).positions;
  const std::vector<Vec3d> grid = evaluate_grid(s, across, along).positions;
  std::vector<Vec3d> out(grid.size());
  for (std::size_t j = 0; j < across.size(); ++j) {
    for (std::size_t i = 0; i < along.size(); ++i)
      out[i + along.size() * j] = grid[j + across.size() * i];
  }
  return out;
}

// Polyline length of line j of iso_line_points over the points [first, last].
double polyline_length(const std::vector<Vec3d>& pts, std::size_t stride, std::size_t j,
                       std::size_t first, std::size_t last) {
  double l = 0;
  for (std::size_t i = first + 1; i <= last; ++i) {
    l += norm(pts[i + stride * j] - pts[i - 1 + stride * j]);
  }
  return l;
}

// The ends of n segments from a to b, b itself last (the parameters iso_line_length evaluates).
void append_segments(double a, double b, int n, std::vector<double>& out) {
  out.push_back(a);
  for (int i = 1; i <= n; ++i) out.push_back(i == n ? b : a + (b - a) * double(i) / n);
}

// Lines of one direction: breaks are its span boundaries, across the samples of the other one.
Direction direction_lines(const NurbsSurface& s, bool along_u, const std::vector<double>& breaks,
                          const std::vector<double>& across, double edge_length, int min_cells) {
  Direction d;
  d.lines.push_back(breaks.front());
  double total = 0;
  const std::size_t spans = breaks.size() - 1;
  std::vector<int> cells(spans, 1);
  std::vector<double> along;
  for (std::size_t k = 0; k < spans; ++k) {
    const double a = breaks[k], b = breaks[k + 1];
    // One span at a time: a patch of a million spans needs no more memory than one of one.
    along.clear();
    append_segments(a, b, kLengthSegments, along);
    const std::vector<Vec3d> pts = iso_line_points(s, along_u, along, across);
    double longest = 0;
    for (std::size_t j = 0; j < across.size(); ++j) {
      const double l = polyline_length(pts, along.size(), j, 0, kLengthSegments);
      longest = std::max(longest, l);
      total += l;
    }
    if (b > a) d.max_speed = std::max(d.max_speed, longest / (b - a));
    const double n = std::ceil(longest / edge_length);
    cells[k] = static_cast<int>(std::clamp(n, 1.0, double(kMaxCellsPerSpan)));
  }
  const double range = breaks.back() - breaks.front();
  d.mean_speed = range > 0 ? total / (range * double(across.size())) : 0;
  // A direction with fewer cells than asked gets its spans split further, widest span first.
  int count = 0;
  for (int c : cells) count += c;
  while (count < min_cells) {
    std::size_t widest = 0;
    for (std::size_t k = 1; k < spans; ++k) {
      if ((breaks[k + 1] - breaks[k]) / cells[k] >
          (breaks[widest + 1] - breaks[widest]) / cells[widest])
        widest = k;
    }
    ++cells[widest];
    ++count;
  }
  for (std::size_t k = 0; k < spans; ++k) {
    const double a = breaks[k], b = breaks[k + 1];
    for (int i = 1; i <= cells[k]; ++i)
      d.lines.push_back(i == cells[k] ? b : a + (b - a) * double(i) / cells[k]);
  }
  return d;
}

// Span breaks closer than min_gap to the previous kept one are dropped, unless the surface is
// only C0 there (a knot of multiplicity >= degree: a crease the grid must follow). Real files
// carry near-duplicate knots (0.1105 and 0.1106 on a 128 m hull); a grid line at each would make
// cells thinner than the welding tolerance.
// min_gap is asked for only when there is an inner break (it costs a few hundred evaluations).
template <class MinGap>
std::vector<double> usable_breaks(const std::vector<double>& breaks,
                                  const std::vector<double>& knots, int degree, MinGap min_gap_of) {
  if (breaks.size() <= 2) return breaks;
  const double min_gap = min_gap_of();
  auto crease = [&](double t) { return std::count(knots.begin(), knots.end(), t) >= degree; };
  std::vector<double> kept{breaks.front()};
  for (std::size_t k = 1; k + 1 < breaks.size(); ++k) {
    const double t = breaks[k];
    if (t - kept.back() >= min_gap) {
      kept.push_back(t);
    } else if (crease(t)) {
      // The crease wins over a smooth break kept just before it (never over the domain start).
      if (kept.size() > 1 && !crease(kept.back()))
        kept.back() = t;
      else if (kept.size() == 1)
        continue;
      else
        kept.push_back(t);
    }
  }
  const double last = breaks.back();
  if (kept.size() > 1 && last - kept.back() < min_gap && !crease(kept.back())) kept.pop_back();
  kept.push_back(last);
  return kept;
}

// Parameter width that one edge_length spans on average along a direction.
double parameter_step(const NurbsSurface& s, bool along_u, const std::vector<double>& across,
                      double edge_length) {
  constexpr int kSegments = 64;
  const double a = along_u ? s.u0 : s.v0, b = along_u ? s.u1 : s.v1;
  std::vector<double> along;
  append_segments(a, b, kSegments, along);
  const std::vector<Vec3d> pts = iso_line_points(s, along_u, along, across);
  double total = 0;
  for (std::size_t j = 0; j < across.size(); ++j) {
    total += polyline_length(pts, along.size(), j, 0, kSegments);
  }
  const double mean_length = total / double(across.size());
  return mean_length > 0 ? (b - a) * edge_length / mean_length : (b - a);
}

}  // namespace

double iso_line_length(const NurbsSurface& s, bool along_u, double fixed, double a, double b,
                       int n) {
  double l = 0;
  Vec3d prev = along_u ? evaluate(s, a, fixed) : evaluate(s, fixed, a);
  for (int i = 1; i <= n; ++i) {
    const double t = i == n ? b : a + (b - a) * double(i) / n;
    const Vec3d p = along_u ? evaluate(s, t, fixed) : evaluate(s, fixed, t);
    l += norm(p - prev);
    prev = p;
  }
  return l;
}

GridLines grid_lines(const NurbsSurface& s, double edge_length, const ResourceLimits& limits,
                     int min_cells_u, int min_cells_v) {
  if (!(edge_length > 0)) throw UsageError("tessellate: edge length must be positive");
  std::vector<double> bu = span_breaks_u(s);
  std::vector<double> bv = span_breaks_v(s);
  if (bu.size() < 2) bu = {s.u0, s.u1};
  if (bv.size() < 2) bv = {s.v0, s.v1};
  const std::vector<double> across_v = spread(s.v0, s.v1, kSampleLines);
  const std::vector<double> across_u = spread(s.u0, s.u1, kSampleLines);
  // Breaks closer than a quarter of the wanted cell width are not worth a grid line.
  bu = usable_breaks(bu, s.knots_u, s.degree_u,
                     [&] { return 0.25 * parameter_step(s, true, across_v, edge_length); });
  bv = usable_breaks(bv, s.knots_v, s.degree_v,
                     [&] { return 0.25 * parameter_step(s, false, across_u, edge_length); });
  Direction du = direction_lines(s, true, bu, across_v, edge_length, min_cells_u);
  Direction dv = direction_lines(s, false, bv, across_u, edge_length, min_cells_v);
  const double cells = double(du.lines.size() - 1) * double(dv.lines.size() - 1);
  if (2 * cells > double(limits.max_triangles)) {
    throw LimitError("tessellate: a patch grid of " + std::to_string(du.lines.size() - 1) + " x " +
                     std::to_string(dv.lines.size() - 1) +
                     " cells exceeds the triangle limit; raise the edge length");
  }
  GridLines g;
  g.u = std::move(du.lines);
  g.v = std::move(dv.lines);
  g.speed_u = du.max_speed;
  g.speed_v = dv.max_speed;
  g.mean_speed_u = du.mean_speed;
  g.mean_speed_v = dv.mean_speed;
  return g;
}

PatchMesh grid_mesh(const NurbsSurface& s, const GridLines& lines) {
  const std::size_t nu = lines.u.size(), nv = lines.v.size();
  PatchMesh m;
  m.xyz.resize(nu * nv);
  m.uv.resize(nu * nv);
  m.flags.resize(nu * nv);
  parallel_for(0, nu * nv, [&](std::size_t k) {
    const std::size_t i = k % nu, j = k / nu;
    const Vec2d w{lines.u[i], lines.v[j]};
    m.uv[k] = w;
    m.xyz[k] = evaluate(s, w.x, w.y);
    const bool side = i == 0 || j == 0 || i + 1 == nu || j + 1 == nv;
    m.flags[k] = side ? kOnDomainSide : 0;
  });
  const std::size_t cu = nu - 1, cv = nv - 1;
  m.tris.resize(2 * cu * cv);
  m.tri_uv.resize(2 * cu * cv);
  parallel_for(0, cu * cv, [&](std::size_t c) {
    const std::size_t i = c % cu, j = c / cu;
    // Corners counter-clockwise in (u, v).
    const Index a = Index(i + nu * j), b = a + 1, cc = Index(b + nu), d = Index(a + nu);
    const bool ac = squared_norm(m.xyz[cc] - m.xyz[a]) <= squared_norm(m.xyz[d] - m.xyz[b]);
    const Tri t0 = ac ? Tri{a, b, cc} : Tri{a, b, d};
    const Tri t1 = ac ? Tri{a, cc, d} : Tri{b, cc, d};
    m.tris[2 * c] = t0;
    m.tris[2 * c + 1] = t1;
    m.tri_uv[2 * c] = {m.uv[t0[0]], m.uv[t0[1]], m.uv[t0[2]]};
    m.tri_uv[2 * c + 1] = {m.uv[t1[0]], m.uv[t1[1]], m.uv[t1[2]]};
  });
  return m;
}

}  // namespace hm
