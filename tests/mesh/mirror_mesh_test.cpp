// Mirroring a half hull about y = 0: the centre-plane vertices are shared, so the open side
// closes; every mirrored face is the reflection of its source with the winding reversed.
#include "mesh/mirror_mesh.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "mesh/adjacency.h"

namespace hm {
namespace {

// A half box open at y = 0: the port side (y = 1), bottom and top (z = 0, z = 1) and the two
// ends (x = 0, x = 2), as quads and triangles, normals out of the box.
SurfaceMesh half_box() {
  SurfaceMesh m;
  // 0..5 at y = 0 (1e-12 off, within tolerance), 6..11 at y = 1.
  for (double y : {1e-12, 1.0}) {
    for (double z : {0.0, 1.0}) {
      for (double x : {0.0, 1.0, 2.0}) m.positions.push_back({x, y, z});
    }
  }
  auto id = [](int x, int y, int z) { return static_cast<Index>(x + 3 * z + 6 * y); };
  // Port side (normal +y), as quads.
  m.faces.push_back({id(0, 1, 0), id(1, 1, 0), id(1, 1, 1), id(0, 1, 1)});
  m.faces.push_back({id(1, 1, 0), id(2, 1, 0), id(2, 1, 1), id(1, 1, 1)});
  // Bottom (normal -z) and top (normal +z), as triangles.
  for (int x = 0; x < 2; ++x) {
    m.faces.push_back({id(x, 0, 0), id(x + 1, 0, 0), id(x + 1, 1, 0), kInvalid});
    m.faces.push_back({id(x, 0, 0), id(x + 1, 1, 0), id(x, 1, 0), kInvalid});
    m.faces.push_back({id(x, 0, 1), id(x + 1, 1, 1), id(x + 1, 0, 1), kInvalid});
    m.faces.push_back({id(x, 0, 1), id(x, 1, 1), id(x + 1, 1, 1), kInvalid});
  }
  // Ends (normals -x and +x).
  m.faces.push_back({id(0, 0, 0), id(0, 1, 0), id(0, 1, 1), id(0, 0, 1)});
  m.faces.push_back({id(2, 0, 0), id(2, 0, 1), id(2, 1, 1), id(2, 1, 0)});
  m.face_patch.assign(m.faces.size(), 0);
  m.face_patch[0] = 3;
  return m;
}

TEST(MirrorHalfHull, ClosesTheOpenSideAndKeepsNormalsOutward) {
  const SurfaceMesh half = half_box();
  const EdgeAdjacency before = build_edge_adjacency(half.faces, half.vertex_count());
  ASSERT_FALSE(before.boundary_edges.empty());
  ASSERT_TRUE(before.inconsistent_edges.empty());

  const MirroredMesh full = mirror_half_hull(half, 1e-9);
  const SurfaceMesh& m = full.mesh;
  EXPECT_EQ(m.vertex_count(), 18u);  // 12, of which the 6 at y = 1 are repeated
  EXPECT_EQ(m.face_count(), 2 * half.face_count());
  const EdgeAdjacency after = build_edge_adjacency(m.faces, m.vertex_count());
  EXPECT_TRUE(after.boundary_edges.empty());
  EXPECT_TRUE(after.nonmanifold_edges.empty());
  EXPECT_TRUE(after.inconsistent_edges.empty());
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    const Vec3d& p = m.positions[v];
    const Vec3d& q = half.positions[full.vert_new2old[v]];
    EXPECT_EQ(p.x, q.x);
    EXPECT_EQ(p.z, q.z);
    EXPECT_EQ(std::abs(p.y), std::abs(q.y) <= 1e-9 ? 0.0 : std::abs(q.y));
  }
  // Each mirrored face's normal is its source's reflected (y negated): still outward.
  for (std::size_t f = half.face_count(); f < m.face_count(); ++f) {
    const Index g = full.face_new2old[f];
    const Vec3d n = face_normal(m.positions, m.faces[f]);
    const Vec3d s = face_normal(half.positions, half.faces[g]);
    EXPECT_NEAR(n.x, s.x, 1e-12);
    EXPECT_NEAR(n.y, -s.y, 1e-12);
    EXPECT_NEAR(n.z, s.z, 1e-12);
    EXPECT_EQ(m.face_patch[f], half.face_patch[g]);
  }
}

TEST(MirrorHalfHull, RefusesAMeshOnBothSides) {
  SurfaceMesh m = half_box();
  m.positions[6].y = -0.5;
  EXPECT_THROW(mirror_half_hull(m, 1e-9), GeometryError);
}

}  // namespace
}  // namespace hm
