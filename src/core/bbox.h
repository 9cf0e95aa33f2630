// Axis-aligned bounding box.
#pragma once

#include <algorithm>
#include <limits>

#include "core/vec.h"

namespace hm {

struct BBox3d {
  Vec3d lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity()};
  Vec3d hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity()};

  bool empty() const { return lo.x > hi.x; }
  void add(const Vec3d& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void add(const BBox3d& b) {
    if (!b.empty()) {
      add(b.lo);
      add(b.hi);
    }
  }
  Vec3d extent() const { return empty() ? Vec3d{} : hi - lo; }
  Vec3d center() const { return empty() ? Vec3d{} : 0.5 * (lo + hi); }
  double diagonal() const { return empty() ? 0.0 : norm(hi - lo); }
};

}  // namespace hm
