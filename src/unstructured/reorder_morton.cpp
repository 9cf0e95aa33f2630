// Locality: vertices in Morton order of their positions, faces in Morton order of their
// centroids, so that later adjacency builds and BVHs walk memory in order.
#include "core/parallel.h"
#include "kernels/morton.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {

void reorder_morton(Work& w) {
  SurfaceMesh& m = w.mesh;
  const std::vector<Index> vert_new2old = morton_order(m.positions);
  std::vector<Index> vert_old2new(vert_new2old.size());
  // Each index writes its own slot.
  parallel_for(0, vert_new2old.size(),
               [&](std::size_t i) { vert_old2new[vert_new2old[i]] = Index(i); });
  SurfaceMesh out;
  std::vector<Index> vert_old(vert_new2old.size());
  out.positions.resize(vert_new2old.size());
  out.vertex_patch.resize(vert_new2old.size());
  out.vertex_uv.resize(vert_new2old.size());
  parallel_for(0, vert_new2old.size(), [&](std::size_t i) {
    const Index o = vert_new2old[i];
    out.positions[i] = m.positions[o];
    out.vertex_patch[i] = m.vertex_patch[o];
    out.vertex_uv[i] = m.vertex_uv[o];
    vert_old[i] = w.vert_old[o];
  });

  std::vector<Vec3d> centroid(m.face_count());
  parallel_for(0, m.face_count(),
               [&](std::size_t f) { centroid[f] = face_centroid(m.positions, m.faces[f]); });
  const std::vector<Index> face_new2old = morton_order(centroid);
  std::vector<Index> face_old(face_new2old.size());
  out.faces.resize(face_new2old.size());
  out.face_patch.resize(face_new2old.size());
  parallel_for(0, face_new2old.size(), [&](std::size_t i) {
    const Index o = face_new2old[i];
    const Face& t = m.faces[o];
    out.faces[i] = {vert_old2new[t[0]], vert_old2new[t[1]], vert_old2new[t[2]], kInvalid};
    out.face_patch[i] = m.face_patch[o];
    face_old[i] = w.face_old[o];
  });
  w.mesh = std::move(out);
  w.vert_old = std::move(vert_old);
  w.face_old = std::move(face_old);
}

}  // namespace hm::merge
