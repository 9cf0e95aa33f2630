#include "nurbs/nurbs_curve.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "nurbs/basis.h"

namespace hm {
namespace {

// Refinement stops at this depth below an initial interval, or when the output holds this many
// points, so that a tiny tolerance cannot allocate without bound.
constexpr int kMaxSampleDepth = 30;
constexpr std::size_t kMaxSamplePoints = std::size_t{1} << 22;
constexpr double kCheckedFraction = 0.8;

double distance_to_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double len2 = squared_norm(ab);
  double t = len2 > 0 ? dot(p - a, ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return norm(p - (a + t * ab));
}

// Appends the points of (ta, tb] (pb is C(tb)) after checking the chord pa-pb against the curve
// at the quarter points; splits in half where the chord is farther than kCheckedFraction * tol.
// The margin covers a maximum deviation that falls between the checked points (the deviation is
// close to a parabola over a piece small against the curvature radius).
void refine(const NurbsCurve& c, double ta, const Vec3d& pa, double tb, const Vec3d& pb, double tol,
            int depth, std::vector<Vec3d>& out) {
  double err = 0;
  for (const double f : {0.25, 0.5, 0.75}) {
    err = std::max(err, distance_to_segment(evaluate(c, ta + f * (tb - ta)), pa, pb));
  }
  const double tm = 0.5 * (ta + tb);
  const bool split = !(err <= kCheckedFraction * tol) && depth < kMaxSampleDepth && tm > ta &&
                     tm < tb && out.size() < kMaxSamplePoints;
  if (split) {
    const Vec3d pm = evaluate(c, tm);
    refine(c, ta, pa, tm, pm, tol, depth + 1, out);
    refine(c, tm, pm, tb, pb, tol, depth + 1, out);
    return;
  }
  out.push_back(pb);
}

}  // namespace

void validate_curve(const NurbsCurve& c) {
  check_direction("NURBS curve", c.degree, c.count(), c.knots, c.t0, c.t1);
  check_net("NURBS curve", c.points, c.weights, c.count());
}

Vec3d evaluate(const NurbsCurve& c, double t) {
  Vec3d p;
  kernel::curve_derivs(c.degree, c.knots, c.points, c.weights, t, 0, &p);
  return p;
}

void evaluate_derivs(const NurbsCurve& c, double t, Vec3d& p, Vec3d& dp) {
  Vec3d d[2];
  kernel::curve_derivs(c.degree, c.knots, c.points, c.weights, t, 1, d);
  p = d[0];
  dp = d[1];
}

std::vector<Vec3d> sample_curve(const NurbsCurve& c, double tol, int min_segments) {
  if (!(tol > 0)) throw GeometryError("sample_curve: the chord tolerance must be positive");
  // Initial parameters: span boundaries, each polynomial span halved (a span of degree >= 2 can
  // bulge on both sides of a chord), and a uniform partition of at least min_segments pieces.
  std::vector<double> ts = span_breaks(c.knots, c.t0, c.t1);
  const std::size_t spans = ts.size() - 1;
  if (c.degree > 1) {
    for (std::size_t i = 0; i < spans; ++i) ts.push_back(0.5 * (ts[i] + ts[i + 1]));
  }
  const int uniform = std::clamp(min_segments, 1, 1 << 20);
  for (int i = 1; i < uniform; ++i) ts.push_back(c.t0 + (c.t1 - c.t0) * i / uniform);
  std::sort(ts.begin(), ts.end());
  ts.erase(std::unique(ts.begin(), ts.end()), ts.end());

  std::vector<Vec3d> out;
  out.reserve(ts.size());
  Vec3d prev = evaluate(c, ts[0]);
  out.push_back(prev);
  for (std::size_t i = 1; i < ts.size(); ++i) {
    const Vec3d next = evaluate(c, ts[i]);
    refine(c, ts[i - 1], prev, ts[i], next, tol, 0, out);
    prev = next;
  }
  return out;
}

NurbsCurve make_line(const Vec3d& a, const Vec3d& b) { return make_polyline({a, b}); }

NurbsCurve make_polyline(const std::vector<Vec3d>& pts) {
  if (pts.size() < 2) throw GeometryError("make_polyline: a polyline needs at least two points");
  NurbsCurve c;
  c.degree = 1;
  c.points = pts;
  c.weights.assign(pts.size(), 1.0);
  // Parameter i at point i: degree 1, clamped, knots 0, 0, 1, ..., n - 2, n - 1, n - 1.
  const int n = static_cast<int>(pts.size());
  c.knots.reserve(pts.size() + 2);
  c.knots.push_back(0.0);
  for (int i = 0; i < n; ++i) c.knots.push_back(i);
  c.knots.push_back(n - 1);
  c.t0 = 0;
  c.t1 = n - 1;
  return c;
}

NurbsCurve make_circular_arc(const Vec3d& c, const Vec3d& a, const Vec3d& b) {
  const Vec2d ra{a.x - c.x, a.y - c.y};
  const Vec2d rb{b.x - c.x, b.y - c.y};
  const double r = norm(ra);
  if (!(r > 0) || !std::isfinite(r)) {
    throw GeometryError("make_circular_arc: the start point lies on the centre");
  }
  // Counter-clockwise sweep in (0, 2 pi]; a == b gives the full circle.
  double sweep = std::atan2(cross(ra, rb), dot(ra, rb));
  if (sweep <= 0) sweep += 2 * std::numbers::pi;
  const int pieces =
      std::max(1, static_cast<int>(std::ceil(sweep / (0.5 * std::numbers::pi) - 1e-12)));
  const double step = sweep / pieces;
  const double start = std::atan2(ra.y, ra.x);
  const double w_mid = std::cos(0.5 * step);

  NurbsCurve arc;
  arc.degree = 2;
  arc.knots = {0.0, 0.0, 0.0};
  for (int i = 0; i < pieces; ++i) {
    const double phi = start + step * i;
    const Vec3d p_end = (i == 0) ? a : Vec3d{c.x + r * std::cos(phi), c.y + r * std::sin(phi), c.z};
    if (i > 0) arc.knots.insert(arc.knots.end(), 2, static_cast<double>(i) / pieces);
    const double mid = phi + 0.5 * step;
    const double rm = r / w_mid;
    arc.points.push_back(p_end);
    arc.weights.push_back(1.0);
    arc.points.push_back({c.x + rm * std::cos(mid), c.y + rm * std::sin(mid), c.z});
    arc.weights.push_back(w_mid);
  }
  arc.points.push_back(b);
  arc.weights.push_back(1.0);
  arc.knots.insert(arc.knots.end(), 3, 1.0);
  arc.t0 = 0;
  arc.t1 = 1;
  return arc;
}

}  // namespace hm
