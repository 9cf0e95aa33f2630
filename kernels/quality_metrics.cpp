#include "kernels/quality_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/parallel.h"

namespace hm::kernel {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
const double kSqrt3 = std::sqrt(3.0);
// Ratios with a zero denominator saturate here instead of becoming infinite (JSON and VTU stay
// finite); any real mesh is far below.
constexpr double kHugeRatio = 1e30;

double ratio(double num, double den) { return den > num / kHugeRatio ? num / den : kHugeRatio; }

double angle_deg(const Vec3d& a, const Vec3d& b) {
  return std::atan2(norm(cross(a, b)), dot(a, b)) * kRadToDeg;
}

Vec3d newell(const Vec3d* p, int n) {
  Vec3d s;
  for (int i = 0; i < n; ++i) {
    const Vec3d& a = p[i];
    const Vec3d& b = p[(i + 1) % n];
    s += Vec3d{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  return s;
}

// Corner positions with collapsed consecutive corners removed; returns the corner count.
int gather(std::span<const Vec3d> positions, const std::array<Index, 4>& f, Vec3d* p) {
  const int raw = f[3] == kInvalid ? 3 : 4;
  std::array<Index, 4> ids{};
  int n = 0;
  for (int i = 0; i < raw; ++i)
    if (n == 0 || f[i] != ids[n - 1]) ids[n++] = f[i];
  if (n > 1 && ids[n - 1] == ids[0]) --n;
  for (int i = 0; i < n; ++i) p[i] = positions[ids[i]];
  return n;
}

void quad_metrics(const Vec3d* p, const Vec3d& unit_n, FaceMetricArrays& o, std::size_t f) {
  const Vec3d c = 0.25 * (p[0] + p[1] + p[2] + p[3]);
  double dmax = 0;
  for (int i = 0; i < 4; ++i) dmax = std::max(dmax, std::abs(dot(p[i] - c, unit_n)));
  const double mean_diag = 0.5 * (norm(p[2] - p[0]) + norm(p[3] - p[1]));
  o.warp[f] = ratio(dmax, mean_diag);
  const Vec3d n012 = cross(p[1] - p[0], p[2] - p[0]), n023 = cross(p[2] - p[0], p[3] - p[0]);
  const Vec3d n123 = cross(p[2] - p[1], p[3] - p[1]), n130 = cross(p[3] - p[1], p[0] - p[1]);
  o.warp_angle_deg[f] = std::max(angle_deg(n012, n023), angle_deg(n123, n130));
  o.convex[f] = !o.zero_area[f] && dot(n012, unit_n) > 0 && dot(n023, unit_n) > 0 &&
                dot(n123, unit_n) > 0 && dot(n130, unit_n) > 0;
  const double m1 = norm(0.5 * (p[1] + p[2]) - 0.5 * (p[3] + p[0]));
  const double m2 = norm(0.5 * (p[2] + p[3]) - 0.5 * (p[0] + p[1]));
  o.aspect_ratio[f] = ratio(std::max(m1, m2), std::min(m1, m2));
  o.equilateral[f] = -1;
}

void one_face(std::span<const Vec3d> positions, const std::array<Index, 4>& face,
              double zero_area_rel, FaceMetricArrays& o, std::size_t f) {
  Vec3d p[4];
  const int n = gather(positions, face, p);
  o.warp[f] = 0;
  o.warp_angle_deg[f] = 0;
  o.convex[f] = 1;
  o.is_quad[f] = n == 4;
  if (n < 3) {  // a face collapsed to an edge or a point
    o.area[f] = 0;
    o.normal[f] = {};
    o.centroid[f] = n > 0 ? (n == 1 ? p[0] : 0.5 * (p[0] + p[1])) : Vec3d{};
    o.min_angle_deg[f] = o.max_angle_deg[f] = 0;
    o.equilateral[f] = 0;
    o.side_ratio[f] = o.aspect_ratio[f] = kHugeRatio;
    o.convex[f] = 0;
    o.zero_area[f] = 1;
    return;
  }
  Vec3d c;
  double lmin = std::numeric_limits<double>::max(), lmax = 0, lsum = 0, l2sum = 0;
  double amin = 180, amax = 0;
  for (int i = 0; i < n; ++i) {
    c += p[i];
    const Vec3d e = p[(i + 1) % n] - p[i];
    const double l = norm(e);
    lmin = std::min(lmin, l);
    lmax = std::max(lmax, l);
    lsum += l;
    l2sum += l * l;
    const double a = angle_deg(p[(i + n - 1) % n] - p[i], e);
    amin = std::min(amin, a);
    amax = std::max(amax, a);
  }
  o.centroid[f] = c / n;
  double area = 0.5 * norm(cross(p[1] - p[0], p[2] - p[0]));
  if (n == 4) area += 0.5 * norm(cross(p[2] - p[0], p[3] - p[0]));
  o.area[f] = area;
  o.zero_area[f] = lmax == 0 || area <= zero_area_rel * lmax * lmax;
  const Vec3d nn = newell(p, n);
  o.normal[f] = o.zero_area[f] ? Vec3d{} : normalized(nn);
  o.min_angle_deg[f] = amin;
  o.max_angle_deg[f] = amax;
  o.side_ratio[f] = ratio(lmax, lmin);
  if (n == 3) {
    o.equilateral[f] = l2sum > 0 ? 4 * kSqrt3 * area / l2sum : 0;
    o.aspect_ratio[f] = ratio(lmax * lsum, 4 * kSqrt3 * area);
    o.convex[f] = !o.zero_area[f];
  } else {
    quad_metrics(p, normalized(nn), o, f);
  }
}

}  // namespace

void FaceMetricArrays::resize(std::size_t n) {
  for (auto* v : {&area, &min_angle_deg, &max_angle_deg, &equilateral, &side_ratio, &warp,
                  &warp_angle_deg, &aspect_ratio})
    v->assign(n, 0.0);
  normal.assign(n, Vec3d{});
  centroid.assign(n, Vec3d{});
  convex.assign(n, 0);
  zero_area.assign(n, 0);
  is_quad.assign(n, 0);
}

void face_metrics(std::span<const Vec3d> positions, std::span<const std::array<Index, 4>> faces,
                  double zero_area_rel, FaceMetricArrays& out) {
  out.resize(faces.size());
  parallel_for(0, faces.size(),
               [&](std::size_t f) { one_face(positions, faces[f], zero_area_rel, out, f); });
}

}  // namespace hm::kernel
