// The metric and the row-curve helpers every structured step uses.
#include <algorithm>
#include <cmath>
#include <limits>

#include "structured/structured_steps.h"

namespace hm::structured {

Vec3d Metric::size_at(const Vec3d& p) const {
  for (const SizeBox& b : boxes) {
    if (p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z &&
        p.z <= b.hi.z) {
      return b.size;
    }
  }
  // Outside every box: each box's size ramps to the global one over its transition zone, by
  // kBoxGrading per metre from the box's faces, so that a panel beside a box's panels is at most
  // about that share larger or smaller and the area-ratio rule holds across the faces. The first
  // box whose zone holds p wins, as inside.
  for (const SizeBox& b : boxes) {
    const Vec3d out{std::max({b.lo.x - p.x, 0.0, p.x - b.hi.x}),
                    std::max({b.lo.y - p.y, 0.0, p.y - b.hi.y}),
                    std::max({b.lo.z - p.z, 0.0, p.z - b.hi.z})};
    const double d = norm(out);
    const Vec3d step = b.size - size;
    const double widest = std::max({std::abs(step.x), std::abs(step.y), std::abs(step.z)});
    if (!(d < widest / kBoxGrading)) continue;
    auto ramp = [&](double box, double global) {
      const double dir = global > box ? 1.0 : -1.0;
      const double v = box + dir * kBoxGrading * d;
      return dir > 0 ? std::min(v, global) : std::max(v, global);
    };
    return {ramp(b.size.x, size.x), ramp(b.size.y, size.y), ramp(b.size.z, size.z)};
  }
  return size;
}

double Metric::length(const Vec3d& a, const Vec3d& b) const {
  // The size at the midpoint: boxes change the measure across their faces, halfway is fair.
  const Vec3d h = size_at((a + b) * 0.5);
  const Vec3d d = b - a;
  return std::sqrt((d.x / h.x) * (d.x / h.x) + (d.y / h.y) * (d.y / h.y) +
                   (d.z / h.z) * (d.z / h.z));
}

std::string to_string(const BreakLabel& b) {
  switch (b.kind) {
    case BreakKind::kLow:
      return "lower end";
    case BreakKind::kHigh:
      return "upper end";
    case BreakKind::kKnuckle:
      return "knuckle " + std::to_string(b.id);
    case BreakKind::kPlane:
      return "plane " + std::to_string(b.id);
  }
  return "?";
}

void RowCurve::locate(double t, std::size_t& seg, double& frac) const {
  if (points.size() < 2) {
    seg = 0;
    frac = 0;
    return;
  }
  t = std::clamp(t, 0.0, s.back());
  const auto it = std::upper_bound(s.begin(), s.end(), t);
  std::size_t k = it == s.begin() ? 0 : static_cast<std::size_t>(it - s.begin()) - 1;
  k = std::min(k, points.size() - 2);
  const double len = s[k + 1] - s[k];
  seg = k;
  frac = len > 0 ? std::clamp((t - s[k]) / len, 0.0, 1.0) : 0.0;
}

Vec3d RowCurve::at(double t) const {
  if (points.size() == 1) return points[0];
  std::size_t k;
  double f;
  locate(t, k, f);
  return points[k] * (1 - f) + points[k + 1] * f;
}

double RowCurve::crossing(const Vec3d& p, const Vec3d& n, double t0) const {
  // Of all sign changes of n.(P - p) along the curve, the one nearest t0 in arc length: a row
  // may cross a tilted plane more than once (a bulb, a tumblehome), and the walk is local.
  double best = std::numeric_limits<double>::quiet_NaN();
  double best_dist = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const double da = dot(n, points[k] - p);
    const double db = dot(n, points[k + 1] - p);
    if ((da > 0 && db > 0) || (da < 0 && db < 0)) continue;
    const double f = da == db ? 0.0 : da / (da - db);
    const double t = s[k] + f * (s[k + 1] - s[k]);
    if (std::abs(t - t0) < best_dist) {
      best_dist = std::abs(t - t0);
      best = t;
    }
  }
  return best;
}

}  // namespace hm::structured
