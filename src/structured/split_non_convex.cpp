// Non-convex quads into triangles. A quad that the repairs and the snap onto the edge curves
// leave with a reflex or flat corner is no panel a panel code can take: its collocation point may
// lie outside it, and the mirrored half's copy may lie on it. It happens where rows converge on a
// boundary line, as at a fine forefoot whose end cap puts three corners of one quad on the stem
// (property seed 1063). Such a quad becomes two triangles along the diagonal through its reflex
// corner, the one whose triangles both keep the quad's orientation. Nothing moves. Serial in face
// order; the second triangle goes to the end, in the same block.
#include <algorithm>

#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// Orientation of triangle (a, b, c) against the quad's normal n: its doubled area, signed.
double turn(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& n) {
  return dot(cross(b - a, c - a), n);
}

}  // namespace

std::size_t split_non_convex(SurfaceMesh& mesh) {
  std::size_t split = 0;
  const std::size_t nf = mesh.faces.size();
  for (std::size_t f = 0; f < nf; ++f) {
    const Face q = mesh.faces[f];
    if (is_triangle(q)) continue;
    Vec3d p[4];
    for (int c = 0; c < 4; ++c) p[c] = mesh.positions[q[c]];
    const Vec3d n = cross(p[2] - p[0], p[3] - p[1]);  // the quad's normal, by its diagonals
    // The two splits: along 0-2 (triangles 012 and 023) and along 1-3 (123 and 130). Each is
    // scored by its worse triangle; a convex quad has both positive and stays.
    const double along02 = std::min(turn(p[0], p[1], p[2], n), turn(p[0], p[2], p[3], n));
    const double along13 = std::min(turn(p[1], p[2], p[3], n), turn(p[1], p[3], p[0], n));
    if (along02 > 0 && along13 > 0) continue;
    const bool first = along02 >= along13;
    const Face a = first ? Face{q[0], q[1], q[2], kInvalid} : Face{q[1], q[2], q[3], kInvalid};
    const Face b = first ? Face{q[0], q[2], q[3], kInvalid} : Face{q[1], q[3], q[0], kInvalid};
    mesh.faces[f] = a;
    mesh.faces.push_back(b);
    if (mesh.face_block.size() == nf + split) mesh.face_block.push_back(mesh.face_block[f]);
    ++split;
  }
  return split;
}

}  // namespace hm::structured
