#include "wetted_surface.h"

#include <cmath>
#include <utility>

namespace hm::test {

std::unique_ptr<WettedSurface> prepare_surface(std::vector<Patch> patches, double waterline_z,
                                               double edge_length) {
  auto w = std::make_unique<WettedSurface>();
  w->patches = std::move(patches);
  TessellateOptions o;
  o.edge_length = edge_length;
  w->tess = tessellate(w->patches, o, silent_progress());
  w->merged = merge_patches(w->patches, w->tess.mesh, {}, silent_progress());
  if (std::isnan(waterline_z)) {
    w->cut.mesh = w->merged.mesh;
  } else {
    PlaneCutOptions co;
    co.value = waterline_z;
    w->cut = cut_at_plane(w->patches, w->merged.mesh, co);
  }
  w->adj = build_edge_adjacency(w->cut.mesh.faces, w->cut.mesh.vertex_count());
  FeatureOptions fo;
  fo.waterline_z = waterline_z;
  w->features = find_features(w->cut.mesh, w->adj, w->patches, fo);
  w->query = std::make_unique<HullQuery>(w->patches, w->cut.mesh);
  return w;
}

}  // namespace hm::test
