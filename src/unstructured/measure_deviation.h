// How far a panel mesh strays from the NURBS: every panel is sampled at its centroid and every
// edge at its midpoint (once, however many panels share it), and each sample's distance to the hull
// comes from the closest-point query (Embree on the fine triangulation, refined on the NURBS).
// Metres, model frame.
#pragma once

#include "mesh/surface_mesh.h"
#include "query/hull_query.h"

namespace hm {

struct DeviationMeasure {
  double max = 0;   // m, the largest distance of a sample to the hull
  double mean = 0;  // m, over all samples
  Vec3d where;      // the sample with the largest distance
  std::size_t samples = 0;
};

// Deterministic for any thread count.
DeviationMeasure measure_deviation(const HullQuery& hull, const SurfaceMesh& panels);

}  // namespace hm
