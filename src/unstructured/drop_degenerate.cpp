// Cleanup after welding: faces that collapsed (a repeated corner, or no area) go, and so do the
// vertices no face uses any more.
#include "unstructured/merge_steps.h"

namespace hm::merge {

void compact_faces(Work& w, std::span<const std::uint8_t> keep) {
  SurfaceMesh& m = w.mesh;
  std::size_t kept = 0;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    if (!keep[f]) continue;
    m.faces[kept] = m.faces[f];
    m.face_patch[kept] = m.face_patch[f];
    w.face_old[kept] = w.face_old[f];
    ++kept;
  }
  m.faces.resize(kept);
  m.face_patch.resize(kept);
  w.face_old.resize(kept);
}

std::size_t drop_degenerate(Work& w, double length) {
  SurfaceMesh& m = w.mesh;
  // Area floor: a triangle this small has lost a dimension to welding, not to the geometry.
  const double floor = 1e-14 * length * length;
  std::vector<std::uint8_t> keep(m.face_count());
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const Face& t = m.faces[f];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
    keep[f] = !repeated && face_area(m.positions, t) > floor;
  }
  const std::size_t before = m.face_count();
  compact_faces(w, keep);
  const std::size_t dropped = before - m.face_count();

  std::vector<Index> old2new(m.vertex_count(), kInvalid);
  for (const Face& t : m.faces) {
    for (int c = 0; c < 3; ++c) old2new[t[c]] = 0;
  }
  Index next = 0;
  for (std::size_t v = 0; v < old2new.size(); ++v) {
    if (old2new[v] == kInvalid) continue;
    old2new[v] = next;
    m.positions[next] = m.positions[v];
    m.vertex_patch[next] = m.vertex_patch[v];
    m.vertex_uv[next] = m.vertex_uv[v];
    w.vert_old[next] = w.vert_old[v];
    ++next;
  }
  m.positions.resize(next);
  m.vertex_patch.resize(next);
  m.vertex_uv.resize(next);
  w.vert_old.resize(next);
  for (Face& t : m.faces) {
    for (int c = 0; c < 3; ++c) t[c] = old2new[t[c]];
  }
  return dropped;
}

}  // namespace hm::merge
