// Rows: the hull's sections at the planned stations, refined onto the NURBS, measured in panel
// sizes, and split where knuckle lines and lateral block planes cross them.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// A breakpoint closer than this (in panels) to one already on the curve is the same node.
constexpr double kBreakMerge = 0.3;
// The largest turn of a row across one panel, radians (10 degrees).
constexpr double kMaxTurnPerPanel = 10 * M_PI / 180;
constexpr double kCornerTurn = 25 * M_PI / 180;
constexpr double kTinyStep = 1e-9;  // m

RowCurve make_curve(const SectionPolyline& pl, const Metric& metric) {
  RowCurve c;
  const std::size_t n = pl.points.size() + (pl.closed ? 1 : 0);
  c.points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const SectionPoint& sp = pl.points[i % pl.points.size()];
    c.points.push_back(sp.point);
    c.patch.push_back(sp.patch);
    c.uv.push_back(sp.uv);
  }
  // Each step counts as the larger of its metric length and its share of the turning (half of
  // the turn at either end over kMaxTurnPerPanel): a tight bilge gets panels enough that
  // neighbouring normals stay close.
  std::vector<double> turn(n, 0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const Vec3d a = c.points[i] - c.points[i - 1], b = c.points[i + 1] - c.points[i];
    const double na = norm(a), nb = norm(b);
    if (!(na > kTinyStep && nb > kTinyStep)) continue;  // a doubled point turns nothing
    const double t = std::acos(std::clamp(dot(a, b) / (na * nb), -1.0, 1.0));
    // A sharper turn is a corner (a knuckle, a breakpoint), not curvature to resolve.
    if (t < kCornerTurn) turn[i] = t;
  }
  c.s.assign(n, 0);
  for (std::size_t i = 1; i < n; ++i) {
    const double by_turn = 0.5 * (turn[i - 1] + turn[i]) / kMaxTurnPerPanel;
    c.s[i] = c.s[i - 1] + std::max(metric.length(c.points[i - 1], c.points[i]), by_turn);
  }
  return c;
}

// Inserts a point at arc length t (linear between its neighbours) and returns its index.
Index insert_point(RowCurve& c, double t) {
  std::size_t k;
  double f;
  c.locate(t, k, f);
  if (f < 1e-9) return static_cast<Index>(k);
  if (f > 1 - 1e-9) return static_cast<Index>(k + 1);
  const Vec3d p = c.points[k] * (1 - f) + c.points[k + 1] * f;
  // (u, v) interpolates only within one patch; across a border the nearer corner's is kept.
  const bool same = c.patch[k] == c.patch[k + 1];
  const Vec2d uv = same ? c.uv[k] * (1 - f) + c.uv[k + 1] * f : (f < 0.5 ? c.uv[k] : c.uv[k + 1]);
  const PatchId patch = f < 0.5 || same ? c.patch[k] : c.patch[k + 1];
  c.points.insert(c.points.begin() + static_cast<std::ptrdiff_t>(k + 1), p);
  c.uv.insert(c.uv.begin() + static_cast<std::ptrdiff_t>(k + 1), uv);
  c.patch.insert(c.patch.begin() + static_cast<std::ptrdiff_t>(k + 1), patch);
  c.s.insert(c.s.begin() + static_cast<std::ptrdiff_t>(k + 1), t);
  for (Breakpoint& b : c.breaks)
    if (b.point > k) ++b.point;
  return static_cast<Index>(k + 1);
}

bool near_break(const RowCurve& c, double t) {
  for (const Breakpoint& b : c.breaks)
    if (std::abs(b.s - t) < kBreakMerge) return true;
  return false;
}

void add_knuckle_breaks(RowCurve& c, double x, const SurfaceMesh& surface,
                        const FeatureSet& features, double tol) {
  for (std::size_t k = 0; k < features.knuckles.size(); ++k) {
    const FeatureLine& line = features.knuckles[k];
    const std::size_t n = line.vertices.size();
    const std::size_t segs = line.closed ? n : n - 1;
    for (std::size_t i = 0; i < segs; ++i) {
      const Vec3d& a = surface.positions[line.vertices[i]];
      const Vec3d& b = surface.positions[line.vertices[(i + 1) % n]];
      if ((a.x - x) * (b.x - x) > 0 || a.x == b.x) continue;
      const double f = (x - a.x) / (b.x - a.x);
      const Vec3d p = a * (1 - f) + b * f;
      // The section crosses the knuckle's mesh edge at one of its own points, refined onto the
      // NURBS: that point, not the chord's, is the breakpoint.
      std::size_t best = 0;
      double best_d = std::numeric_limits<double>::infinity();
      for (std::size_t j = 0; j < c.points.size(); ++j) {
        const double d = squared_norm(c.points[j] - p);
        if (d < best_d) {
          best_d = d;
          best = j;
        }
      }
      if (std::sqrt(best_d) > tol || near_break(c, c.s[best])) continue;
      c.breaks.push_back(
          {c.s[best], static_cast<Index>(best), {BreakKind::kKnuckle, static_cast<Index>(k)}});
    }
  }
}

void add_plane_breaks(RowCurve& c, std::span<const BlockPlane> planes) {
  for (std::size_t p = 0; p < planes.size(); ++p) {
    const Vec3d n = normalized(planes[p].normal);
    if (std::abs(std::abs(n.x) - 1) <= 1e-6) continue;  // a cut station
    for (std::size_t k = 0; k + 1 < c.points.size(); ++k) {
      const double da = dot(n, c.points[k] - planes[p].point);
      const double db = dot(n, c.points[k + 1] - planes[p].point);
      if (!((da < 0 && db >= 0) || (da >= 0 && db < 0))) continue;
      const double t = c.s[k] + da / (da - db) * (c.s[k + 1] - c.s[k]);
      if (near_break(c, t)) continue;
      const Index at = insert_point(c, t);
      c.breaks.push_back({t, at, {BreakKind::kPlane, static_cast<Index>(p)}});
      ++k;  // past the inserted point
    }
  }
}

}  // namespace

std::vector<Row> extract_rows(const HullQuery& query, const SurfaceMesh& surface,
                              const FeatureSet& features, std::span<const BlockPlane> planes,
                              const StationPlan& plan, const Metric& metric) {
  std::vector<Plane> cut(plan.x.size());
  for (std::size_t j = 0; j < cut.size(); ++j) cut[j] = Plane{{plan.x[j], 0, 0}, {1, 0, 0}};
  const std::vector<Section> secs = query.sections(cut);
  const double tol = 1e-3 * query.length_scale();
  std::vector<Row> rows(plan.x.size());
  parallel_for_each_item(rows.size(), [&](std::size_t j) {
    Row& row = rows[j];
    row.x = plan.x[j];
    row.border = plan.border[j] != 0;
    for (const SectionPolyline& pl : secs[j].polylines) {
      if (pl.points.size() < 2) continue;
      RowCurve c = make_curve(pl, metric);
      // Slivers of a section (a grazed patch corner) are not rows.
      if (c.length() < 0.05) continue;
      const Index last = static_cast<Index>(c.points.size() - 1);
      c.breaks.push_back({0, 0, {BreakKind::kLow, 0}});
      c.breaks.push_back({c.s.back(), last, {BreakKind::kHigh, 0}});
      add_knuckle_breaks(c, row.x, surface, features, tol);
      add_plane_breaks(c, planes);
      std::sort(c.breaks.begin(), c.breaks.end(),
                [](const Breakpoint& a, const Breakpoint& b) { return a.s < b.s; });
      row.curves.push_back(std::move(c));
    }
  });
  return rows;
}

}  // namespace hm::structured
