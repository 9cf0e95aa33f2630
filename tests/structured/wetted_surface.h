// The surface the structured tests mesh, prepared as `hullmesh structured` prepares it:
// tessellated, merged, cut at a waterline (or not), with its adjacency, features and query.
#pragma once

#include <memory>
#include <vector>

#include "mesh/adjacency.h"
#include "nurbs/patch.h"
#include "query/hull_query.h"
#include "tessellate/tessellate.h"
#include "unstructured/cut_at_plane.h"
#include "unstructured/features.h"
#include "unstructured/merge.h"

namespace hm::test {

struct WettedSurface {
  std::vector<Patch> patches;
  Tessellation tess;
  MergedSurface merged;
  PlaneCut cut;  // cut.mesh is the surface meshed (the merged one when not cut)
  EdgeAdjacency adj;
  FeatureSet features;
  std::unique_ptr<HullQuery> query;
};

// patches tessellated to `edge_length` (m), merged, cut at z = waterline_z (NaN: not cut).
std::unique_ptr<WettedSurface> prepare_surface(std::vector<Patch> patches, double waterline_z,
                                               double edge_length);

}  // namespace hm::test
