// Internal to src/quality: the surface integrals both hydrostatics paths accumulate, and the step
// that turns them into hydrostatic figures.
#pragma once

#include <array>

#include "quality/hydrostatics.h"

namespace hm {

// Integrals over the wetted surface S_w (outward normal n, waterplane z = z0). Each is the
// divergence theorem applied to a field that vanishes on the centre plane and the waterplane, or
// (the fluxes) a divergence-free field whose waterplane flux is the wanted waterplane moment:
//   volume = int (z - z0) n_z dS           F = (0, 0, z - z0),            div F = 1
//   mx     = int x (z - z0) n_z dS         F = (0, 0, x (z - z0)),        div F = x
//   my     = int y (z - z0) n_z dS         F = (0, 0, y (z - z0)),        div F = y
//   mz     = int (z^2 - z0^2) / 2 n_z dS   F = (0, 0, (z^2 - z0^2) / 2),  div F = z
//   awp    = -int n_z dS                   F = (0, 0, 1), div F = 0, flux through the waterplane
//   sx, sy = -int x n_z dS, -int y n_z dS     (first moments of the waterplane)
//   sxx, syy = -int x^2 n_z dS, -int y^2 n_z dS (second moments about the y and x axes)
struct SurfaceIntegrals {
  enum : int { kArea, kVolume, kMx, kMy, kMz, kAwp, kSx, kSy, kSxx, kSyy, kCount };
  std::array<double, kCount> v{};

  SurfaceIntegrals& operator+=(const SurfaceIntegrals& o) {
    for (int i = 0; i < kCount; ++i) v[i] += o.v[i];
    return *this;
  }
};

// Area moments of the waterplane (one side only for a half hull): int dA, x dA, y dA, x^2 dA,
// y^2 dA.
struct WaterplaneMoments {
  double area = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
};

// Volume figures from s, waterplane figures from w; applies the half-hull doubling.
Hydrostatics finish_hydrostatics(const SurfaceIntegrals& s, const WaterplaneMoments& w,
                                 bool half_hull);

}  // namespace hm
