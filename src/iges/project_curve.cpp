#include "iges/project_curve.h"

#include <algorithm>
#include <cmath>

namespace hm::iges {
namespace {

constexpr std::size_t kMaxSamples = 20000;

// Distinct knot values inside [t0, t1], ends included; thinned to at most kMaxSamples values so
// that a hostile curve with millions of spans cannot make projection run for minutes.
std::vector<double> breaks(const NurbsCurve& c) {
  std::vector<double> b{c.t0};
  for (double k : c.knots) {
    if (k > b.back() && k < c.t1) b.push_back(k);
  }
  b.push_back(c.t1);
  if (b.size() > kMaxSamples) {
    std::vector<double> thin;
    const std::size_t step = b.size() / kMaxSamples + 1;
    for (std::size_t i = 0; i + 1 < b.size(); i += step) thin.push_back(b[i]);
    thin.push_back(b.back());
    b.swap(thin);
  }
  return b;
}

struct Sample {
  double t;
  Vec3d uv;
  double distance;  // from the curve point to its projection (model units)
};

}  // namespace

std::vector<Vec3d> sample_points(const NurbsCurve& c, int per_span) {
  if (c.degree == 1 && c.t0 == c.knots.front() && c.t1 == c.knots.back()) return c.points;
  const std::vector<double> b = breaks(c);
  const int n = b.size() * static_cast<std::size_t>(per_span) > kMaxSamples ? 1 : per_span;
  std::vector<Vec3d> out;
  for (std::size_t i = 0; i + 1 < b.size(); ++i) {
    for (int k = 0; k < n; ++k) out.push_back(evaluate(c, b[i] + (b[i + 1] - b[i]) * k / n));
  }
  out.push_back(evaluate(c, c.t1));
  return out;
}

NurbsCurve project_to_uv(const NurbsSurface& s, const NurbsCurve& c, double tol,
                         double& max_distance, std::uint64_t& budget) {
  const std::vector<double> b = breaks(c);
  const int per_span = b.size() * 4 > kMaxSamples ? 1 : 4;
  std::vector<double> ts;
  for (std::size_t i = 0; i + 1 < b.size(); ++i) {
    for (int k = 0; k < per_span; ++k) ts.push_back(b[i] + (b[i + 1] - b[i]) * k / per_span);
  }
  ts.push_back(c.t1);
  double u = 0, v = 0;
  bool have = false;
  SurfaceProjector projector(s);
  // Local Newton from the previous sample; a global search where that fails or lands far from
  // the curve. A curve that lies off its surface (a broken file) keeps its offset from sample to
  // sample, so "far" is measured beyond the previous sample's own distance.
  double last_distance = 0;
  auto project = [&](double t) {
    if (budget > 0) --budget;
    const Vec3d q = evaluate(c, t);
    SurfaceProjection pr = have ? projector.project(q, u, v) : projector.project(q);
    if (have && (!pr.converged || pr.distance > 10 * tol + 2 * last_distance)) {
      const SurfaceProjection g = projector.project(q);
      if (g.distance < pr.distance) pr = g;
    }
    u = pr.u;
    v = pr.v;
    have = true;
    last_distance = pr.distance;
    max_distance = std::max(max_distance, pr.distance);
    return Sample{t, Vec3d{pr.u, pr.v, 0}, pr.distance};
  };
  std::vector<Sample> pts;
  pts.reserve(ts.size());
  for (double t : ts) {
    if (budget == 0) break;
    pts.push_back(project(t));
  }
  if (pts.size() < 2) {
    budget = 0;
    pts.assign(2, Sample{c.t0, Vec3d{}, 0});
  }
  // Refine each segment where the straight (u, v) segment leaves the curve by more than the
  // curve's own offset from the surface at the segment's ends.
  std::vector<Sample> out{pts.front()};
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    std::vector<std::pair<Sample, int>> stack{{pts[i + 1], 0}};
    Sample a = pts[i];
    while (!stack.empty()) {
      const auto [bs, depth] = stack.back();
      const double tm = 0.5 * (a.t + bs.t);
      const Vec3d mid_uv = 0.5 * (a.uv + bs.uv);
      const Vec3d on_curve = evaluate(c, tm);
      const double dev =
          norm(evaluate(s, mid_uv.x, mid_uv.y) - on_curve) - std::max(a.distance, bs.distance);
      if (depth < 8 && budget > 0 && out.size() + stack.size() < kMaxSamples && dev > tol) {
        u = a.uv.x;
        v = a.uv.y;
        last_distance = a.distance;
        stack.push_back({project(tm), depth + 1});
        continue;
      }
      out.push_back(bs);
      a = bs;
      stack.pop_back();
    }
  }
  std::vector<Vec3d> uv(out.size());
  for (std::size_t i = 0; i < out.size(); ++i) uv[i] = out[i].uv;
  NurbsCurve r;
  r.degree = 1;
  r.knots.push_back(0);
  for (std::size_t i = 0; i < uv.size(); ++i) r.knots.push_back(static_cast<double>(i));
  r.knots.push_back(static_cast<double>(uv.size() - 1));
  r.points = std::move(uv);
  r.weights.assign(r.points.size(), 1.0);
  r.t0 = 0;
  r.t1 = static_cast<double>(r.points.size() - 1);
  return r;
}

}  // namespace hm::iges
