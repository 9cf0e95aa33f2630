// How a patch's normal su x sv spreads over its domain, from a uniform grid of samples: the
// area-weighted mean direction, and the share of |su x sv| pointing away from a direction. Tells
// a sheared patch that folds over itself, and gives the plane it is a graph over.
#pragma once

#include <vector>

#include "core/vec.h"
#include "nurbs/nurbs_surface.h"

namespace hm {

inline constexpr int kNormalSamples = 33;  // per direction

struct NormalSamples {
  std::vector<Vec3d> jac;  // su x sv at each sample (m^2 per parameter unit^2)
  std::vector<Vec3d> at;   // the surface point of each sample (m)
  Vec3d sum;               // sum of jac: the area-weighted mean normal, not normalised
  double total = 0;        // sum of |jac|

  // The share of `total` carried by samples whose su x sv is more than acos(cos_limit) from the
  // unit vector dir.
  double share_beyond(const Vec3d& dir, double cos_limit) const;
};

// su x sv on kNormalSamples^2 points spaced evenly in (u, v) over the whole domain.
NormalSamples sample_normals(const NurbsSurface& s);

}  // namespace hm
