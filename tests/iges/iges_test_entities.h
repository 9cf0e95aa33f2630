// Parameter lists of common IGES entities for the reader tests.
#pragma once

#include <string>
#include <vector>

#include "core/vec.h"
#include "iges_text_builder.h"

namespace hm::test {

inline std::vector<std::string> line_110(const Vec3d& a, const Vec3d& b) {
  return {num(a.x), num(a.y), num(a.z), num(b.x), num(b.y), num(b.z)};
}

// 126 of degree 1 through the points (a polyline), parameter 0..n-1.
inline std::vector<std::string> polyline_126(const std::vector<Vec3d>& pts) {
  const int k = static_cast<int>(pts.size()) - 1;
  std::vector<std::string> p{num(k), "1", "0", "0", "1", "0", "0."};
  for (int i = 0; i <= k; ++i) p.push_back(num(static_cast<double>(i)));
  p.push_back(num(static_cast<double>(k)));
  for (int i = 0; i <= k; ++i) p.push_back("1.");
  for (const Vec3d& q : pts) {
    p.push_back(num(q.x));
    p.push_back(num(q.y));
    p.push_back(num(q.z));
  }
  p.push_back("0.");
  p.push_back(num(static_cast<double>(k)));
  p.insert(p.end(), {"0.", "0.", "1."});
  return p;
}

struct Surface128 {
  int k1 = 1, k2 = 1, m1 = 1, m2 = 1;
  std::vector<double> knots_u{0, 0, 1, 1}, knots_v{0, 0, 1, 1};
  std::vector<double> weights{1, 1, 1, 1};
  std::vector<Vec3d> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
  bool polynomial = true;

  std::vector<std::string> params() const {
    std::vector<std::string> p{num(k1), num(k2), num(m1), num(m2), "0", "0", polynomial ? "1" : "0",
                               "0",     "0"};
    for (double k : knots_u) p.push_back(num(k));
    for (double k : knots_v) p.push_back(num(k));
    for (double w : weights) p.push_back(num(w));
    for (const Vec3d& q : points) {
      p.push_back(num(q.x));
      p.push_back(num(q.y));
      p.push_back(num(q.z));
    }
    p.insert(p.end(), {num(u0), num(u1), num(v0), num(v1)});
    return p;
  }
};

// A flat square patch [x0, x0 + size] x [y0, y0 + size] at z.
inline Surface128 square(double x0, double y0, double size, double z = 0) {
  Surface128 s;
  s.points = {{x0, y0, z}, {x0 + size, y0, z}, {x0, y0 + size, z}, {x0 + size, y0 + size, z}};
  return s;
}

}  // namespace hm::test
