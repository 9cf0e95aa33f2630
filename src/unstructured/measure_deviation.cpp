#include "unstructured/measure_deviation.h"

#include <vector>

#include "core/parallel.h"

namespace hm {

DeviationMeasure measure_deviation(const HullQuery& hull, const SurfaceMesh& panels) {
  constexpr int kSamples = 4;  // centroid and three edge midpoints (first three edges of a quad)
  const std::size_t nf = panels.face_count();
  std::vector<Vec3d> sample(nf * kSamples);
  parallel_for(0, nf, [&](std::size_t f) {
    const Face& fc = panels.faces[f];
    const int n = corner_count(fc);
    sample[f * kSamples] = face_centroid(panels.positions, fc);
    for (int c = 0; c < 3; ++c) {
      sample[f * kSamples + 1 + c] =
          0.5 * (panels.positions[fc[c]] + panels.positions[fc[(c + 1) % n]]);
    }
  });
  std::vector<ClosestPoint> cp(sample.size());
  hull.closest_points(sample, cp);
  DeviationMeasure m;
  double sum = 0;
  for (std::size_t i = 0; i < cp.size(); ++i) {
    if (!cp[i].valid()) continue;
    ++m.samples;
    sum += cp[i].distance;
    if (cp[i].distance > m.max) {
      m.max = cp[i].distance;
      m.where = sample[i];
    }
  }
  m.mean = m.samples ? sum / static_cast<double>(m.samples) : 0.0;
  return m;
}

}  // namespace hm
