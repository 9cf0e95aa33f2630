// Axis-aligned bounding box.
#pragma once

#include <algorithm>
#include <limits>

#include "core/vec.h"

namespace hm {

// Whether the closed boxes [alo, ahi] and [blo, bhi] share a point (touching counts).
inline bool boxes_meet(const Vec3d& alo, const Vec3d& ahi, const Vec3d& blo, const Vec3d& bhi) {
  return alo.x <= bhi.x && blo.x <= ahi.x && alo.y <= bhi.y && blo.y <= ahi.y && alo.z <= bhi.z &&
         blo.z <= ahi.z;
}

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
  bool meets(const BBox3d& b) const { return boxes_meet(lo, hi, b.lo, b.hi); }
};

}  // namespace hm
