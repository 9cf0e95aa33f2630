// Surfaces with known geometry for the NURBS tests, and an independent reference evaluator.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "nurbs/nurbs_surface.h"

namespace hm::test {

inline const double kHalfSqrt2 = std::sqrt(2.0) / 2.0;

// A clamped knot vector of `count` + degree + 1 values over [a, b] with the given interior knots.
inline std::vector<double> clamped_knots(int degree, const std::vector<double>& interior, double a,
                                         double b) {
  std::vector<double> k(degree + 1, a);
  k.insert(k.end(), interior.begin(), interior.end());
  k.insert(k.end(), degree + 1, b);
  return k;
}

inline NurbsSurface make_surface(int pu, int pv, int nu, int nv, std::vector<double> ku,
                                 std::vector<double> kv, std::vector<Vec3d> pts,
                                 std::vector<double> w = {}) {
  NurbsSurface s;
  s.degree_u = pu;
  s.degree_v = pv;
  s.count_u = nu;
  s.count_v = nv;
  s.knots_u = std::move(ku);
  s.knots_v = std::move(kv);
  s.points = std::move(pts);
  s.weights = w.empty() ? std::vector<double>(s.points.size(), 1.0) : std::move(w);
  s.u0 = s.knots_u[pu];
  s.u1 = s.knots_u[nu];
  s.v0 = s.knots_v[pv];
  s.v1 = s.knots_v[nv];
  return s;
}

// S(u, v) = (2u, 3v, uv) on [0, 1]^2.
inline NurbsSurface bilinear() {
  return make_surface(1, 1, 2, 2, {0, 0, 1, 1}, {0, 0, 1, 1},
                      {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}, {2, 3, 1}});
}

// Flat a x b rectangle in z = 0.
inline NurbsSurface flat_rectangle(double a, double b) {
  return make_surface(1, 1, 2, 2, {0, 0, 1, 1}, {0, 0, 1, 1},
                      {{0, 0, 0}, {a, 0, 0}, {0, b, 0}, {a, b, 0}});
}

// Quarter cylinder of radius r and height h about the z axis, from +x to +y (u), z = 0..h (v).
// Su x Sv points outwards.
inline NurbsSurface quarter_cylinder(double r, double h) {
  std::vector<Vec3d> pts;
  std::vector<double> w;
  for (int j = 0; j < 2; ++j) {
    pts.insert(pts.end(), {{r, 0, j * h}, {r, r, j * h}, {0, r, j * h}});
    w.insert(w.end(), {1.0, kHalfSqrt2, 1.0});
  }
  return make_surface(2, 1, 3, 2, {0, 0, 0, 1, 1, 1}, {0, 0, 1, 1}, pts, w);
}

// A quarter-circle profile (x_i, z_i) with weights, revolved 90 degrees about z from +x to +y.
// u runs along the profile, v around the axis.
inline NurbsSurface revolve_quarter(const std::vector<Vec3d>& profile,
                                    const std::vector<double>& pw) {
  const double ax[3] = {1, 1, 0};
  const double ay[3] = {0, 1, 1};
  const double aw[3] = {1, kHalfSqrt2, 1};
  std::vector<Vec3d> pts;
  std::vector<double> w;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      pts.push_back({profile[i].x * ax[j], profile[i].x * ay[j], profile[i].z});
      w.push_back(pw[i] * aw[j]);
    }
  }
  return make_surface(2, 2, 3, 3, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1}, pts, w);
}

// Sphere octant of radius r: u from the equator (+x) to the north pole, where the edge u = 1
// collapses to the point (0, 0, r). Su x Sv points inwards (towards the centre).
inline NurbsSurface sphere_octant(double r) {
  return revolve_quarter({{r, 0, 0}, {r, 0, r}, {0, 0, r}}, {1, kHalfSqrt2, 1});
}

// Inner upper quarter of a torus (tube radius r, centre circle radius rc): tube angle 90..180
// degrees, where the Gaussian curvature is negative.
inline NurbsSurface torus_inner_quarter(double rc, double r) {
  return revolve_quarter({{rc, 0, r}, {rc - r, 0, r}, {rc - r, 0, 0}}, {1, kHalfSqrt2, 1});
}

// A random rational bicubic graph-like surface over [0, 4] x [0, 3] (x, y), heights in
// [-amp, amp], weights in [0.5, 2], with interior knots.
inline NurbsSurface random_bicubic(std::uint32_t seed, double amp = 0.3, bool rational = true) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> z(-amp, amp), w(0.5, 2.0), jitter(-0.1, 0.1);
  const int nu = 6, nv = 5;
  std::vector<Vec3d> pts;
  std::vector<double> ws;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      pts.push_back({4.0 * i / (nu - 1) + jitter(rng), 3.0 * j / (nv - 1) + jitter(rng), z(rng)});
      ws.push_back(rational ? w(rng) : 1.0);
    }
  }
  return make_surface(3, 3, nu, nv, clamped_knots(3, {0.3, 0.6}, 0, 1),
                      clamped_knots(3, {0.45}, 0, 1), pts, ws);
}

// Cox-de Boor recursion over the whole knot vector: an evaluator sharing no code with the
// library. At the end of the knot range the last non-empty span is used.
inline double cox_de_boor(const std::vector<double>& k, int i, int p, double t) {
  if (p == 0) {
    if (k[i] <= t && t < k[i + 1]) return 1.0;
    // t at the top end: the last non-empty span holds it.
    if (t == k.back() && k[i] < k[i + 1] && k[i + 1] == k.back()) return 1.0;
    return 0.0;
  }
  double a = 0, b = 0;
  if (k[i + p] > k[i]) a = (t - k[i]) / (k[i + p] - k[i]) * cox_de_boor(k, i, p - 1, t);
  if (k[i + p + 1] > k[i + 1]) {
    b = (k[i + p + 1] - t) / (k[i + p + 1] - k[i + 1]) * cox_de_boor(k, i + 1, p - 1, t);
  }
  return a + b;
}

inline Vec3d reference_point(const NurbsSurface& s, double u, double v) {
  Vec3d num;
  double den = 0;
  for (int j = 0; j < s.count_v; ++j) {
    const double bj = cox_de_boor(s.knots_v, j, s.degree_v, v);
    if (bj == 0) continue;
    for (int i = 0; i < s.count_u; ++i) {
      const double b = cox_de_boor(s.knots_u, i, s.degree_u, u) * bj * s.weight(i, j);
      num += b * s.point(i, j);
      den += b;
    }
  }
  return num / den;
}

}  // namespace hm::test
