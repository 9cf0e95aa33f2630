// Small fixed-size vectors in double precision. Plain aggregates so that arrays of them are
// contiguous and trivially copyable (byte-stable outputs, cheap spans).
#pragma once

#include <cmath>

namespace hm {

struct Vec2d {
  double x = 0, y = 0;

  constexpr Vec2d& operator+=(const Vec2d& o) {
    x += o.x;
    y += o.y;
    return *this;
  }
  constexpr Vec2d& operator-=(const Vec2d& o) {
    x -= o.x;
    y -= o.y;
    return *this;
  }
  constexpr Vec2d& operator*=(double s) {
    x *= s;
    y *= s;
    return *this;
  }
  friend constexpr Vec2d operator+(Vec2d a, const Vec2d& b) { return a += b; }
  friend constexpr Vec2d operator-(Vec2d a, const Vec2d& b) { return a -= b; }
  friend constexpr Vec2d operator*(Vec2d a, double s) { return a *= s; }
  friend constexpr Vec2d operator*(double s, Vec2d a) { return a *= s; }
  friend constexpr bool operator==(const Vec2d&, const Vec2d&) = default;
};

struct Vec3d {
  double x = 0, y = 0, z = 0;

  constexpr double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr Vec3d& operator+=(const Vec3d& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3d& operator-=(const Vec3d& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3d& operator*=(double s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
  constexpr Vec3d& operator/=(double s) {
    x /= s;
    y /= s;
    z /= s;
    return *this;
  }
  friend constexpr Vec3d operator+(Vec3d a, const Vec3d& b) { return a += b; }
  friend constexpr Vec3d operator-(Vec3d a, const Vec3d& b) { return a -= b; }
  friend constexpr Vec3d operator-(const Vec3d& a) { return {-a.x, -a.y, -a.z}; }
  friend constexpr Vec3d operator*(Vec3d a, double s) { return a *= s; }
  friend constexpr Vec3d operator*(double s, Vec3d a) { return a *= s; }
  friend constexpr Vec3d operator/(Vec3d a, double s) { return a /= s; }
  friend constexpr bool operator==(const Vec3d&, const Vec3d&) = default;
};

constexpr double dot(const Vec2d& a, const Vec2d& b) { return a.x * b.x + a.y * b.y; }
constexpr double cross(const Vec2d& a, const Vec2d& b) { return a.x * b.y - a.y * b.x; }
constexpr double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec2d& a) { return std::sqrt(dot(a, a)); }
inline double norm(const Vec3d& a) { return std::sqrt(dot(a, a)); }
constexpr double squared_norm(const Vec3d& a) { return dot(a, a); }
// Unit vector, or the zero vector when |a| is zero (callers test for that, never for NaN).
inline Vec3d normalized(const Vec3d& a) {
  const double n = norm(a);
  return n > 0 ? a / n : Vec3d{};
}
inline bool is_finite(const Vec3d& a) {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

}  // namespace hm
