// Wave resolution: the Kelvin transverse wavelength against the panel length along the hull.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "quality/quality_steps.h"

namespace hm {

WaveFigures wave_resolution(const SurfaceMesh& mesh, const WaveOptions& w,
                            const ResolvedSettings& s) {
  WaveFigures out;
  if (!w.speed && !w.froude) return out;
  out.requested = true;
  if (w.speed && w.froude) throw UsageError("give either a speed or a Froude number, not both");
  // The waterline length: the x-extent of the vertices on the waterline (else of the mesh).
  double xlo = INFINITY, xhi = -INFINITY, alo = INFINITY, ahi = -INFINITY;
  for (const Vec3d& p : mesh.positions) {
    alo = std::min(alo, p.x);
    ahi = std::max(ahi, p.x);
    if (std::abs(p.z - s.waterline_z) <= s.tol) {
      xlo = std::min(xlo, p.x);
      xhi = std::max(xhi, p.x);
    }
  }
  const double lwl = xhi > xlo ? xhi - xlo : (ahi > alo ? ahi - alo : 0);
  out.length = w.length.value_or(lwl);
  if (w.froude) {
    if (!(out.length > 0)) throw UsageError("a Froude number needs a positive length");
    out.froude = *w.froude;
    out.speed = *w.froude * std::sqrt(w.gravity * out.length);
  } else {
    out.speed = *w.speed;
    out.froude = out.length > 0 ? out.speed / std::sqrt(w.gravity * out.length) : 0;
  }
  if (!(out.speed > 0) || !std::isfinite(out.speed))
    throw UsageError("the speed must be positive and finite");
  out.wavelength = 2 * std::numbers::pi * out.speed * out.speed / w.gravity;
  // Panels touching the waterline; if none does (a deeply submerged body), the top tenth.
  double zlo = INFINITY;
  for (const Vec3d& p : mesh.positions) zlo = std::min(zlo, p.z);
  const double band = std::max(s.tol, 0.1 * (s.waterline_z - zlo));
  std::vector<double> lengths;
  for (double reach : {s.tol, band}) {
    for (const Face& f : mesh.faces) {
      double lo = INFINITY, hi = -INFINITY, dz = INFINITY;
      for (int c = 0; c < corner_count(f); ++c) {
        const Vec3d& p = mesh.positions[f[c]];
        lo = std::min(lo, p.x);
        hi = std::max(hi, p.x);
        dz = std::min(dz, std::abs(p.z - s.waterline_z));
      }
      if (dz <= reach && hi > lo) lengths.push_back(hi - lo);
    }
    if (!lengths.empty()) break;
  }
  if (!lengths.empty()) {
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    out.panel_length_x = lengths[lengths.size() / 2];
    out.panels_per_wavelength = out.wavelength / out.panel_length_x;
  }
  out.warn = out.panels_per_wavelength < 10;
  return out;
}

}  // namespace hm
