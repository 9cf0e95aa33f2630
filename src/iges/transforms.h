// 124 transformation matrices: each entity's DE pointer names a 124, whose own DE pointer may
// name another (a chain). Resolved once for the whole file, with cycle detection.
#pragma once

#include <string>
#include <unordered_map>

#include "core/vec.h"
#include "iges/iges_model.h"

namespace hm::iges {

// x' = R x + T, in model units.
struct Affine {
  double r[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double t[3] = {0, 0, 0};
  bool identity = true;

  Vec3d apply(const Vec3d& p) const {
    if (identity) return p;
    return {r[0][0] * p.x + r[0][1] * p.y + r[0][2] * p.z + t[0],
            r[1][0] * p.x + r[1][1] * p.y + r[1][2] * p.z + t[1],
            r[2][0] * p.x + r[2][1] * p.y + r[2][2] * p.z + t[2]};
  }
};

// outer after inner: x -> outer(inner(x)).
Affine compose(const Affine& outer, const Affine& inner);

class Transforms {
 public:
  // Resolves every 124 chain. Throws IgesError for a cyclic chain or one deeper than
  // limits.max_pointer_depth, naming the DE.
  explicit Transforms(const IgesModel& m);
  // The transform from entity `index`'s definition space to model space. Throws EntityFault
  // (for that entity) when its pointer dangles or names something that is not a usable 124.
  Affine of(int index) const;

 private:
  const IgesModel* m_;
  std::unordered_map<int, Affine> chain_;     // per 124 directory index: the full chain
  std::unordered_map<int, std::string> bad_;  // 124s that cannot be used, and why
};

}  // namespace hm::iges
