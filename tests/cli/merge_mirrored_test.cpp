// A heeled half hull made whole: the half merged alone and mirrored with its merged surface.
#include "cli/merge_mirrored.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "cli/prepare_hull.h"
#include "core/progress.h"
#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "nurbs/nurbs_surface.h"

namespace hm {
namespace {

// The generated 12-patch half Wigley and its mirror images, merged at about 6,000 triangles: the
// whole is one closed surface but for the deck edge, every image vertex is its half vertex's
// mirror with the mirrored patch and (u, v), the faces at the ends (where the Wigley has no
// thickness, and fine faces span stem or stern and keel) make no edge with three faces, and the
// volume is the one the patches and their images merged together enclose.
TEST(MergeMirrored, HalfWigleyMirroredIsOneSurfaceOnItsPatches) {
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  spec.patches = 12;
  ImportResult hull;
  hull.patches = generate_hull(spec).patches;
  const std::size_t n = hull.patches.size();
  for (const Patch& p : hull.patches) {
    for (const Vec3d& c : p.surface.points) hull.bbox.add(c);
  }
  cli::add_mirror_image(hull);
  ASSERT_EQ(hull.patches.size(), 2 * n);
  const std::span<const Patch> whole = hull.patches;
  TessellateOptions o;
  o.edge_length = edge_length_for_triangles(whole, 6000);
  const Tessellation half = tessellate(whole.first(n), o, silent_progress());
  FloatingTransform identity;
  const MergedSurface m = cli::merge_mirrored_half(whole, half, {}, identity, silent_progress());
  const SurfaceMesh& s = m.mesh;
  const EdgeAdjacency adj = build_edge_adjacency(s.faces, s.vertex_count());
  EXPECT_TRUE(adj.nonmanifold_edges.empty());
  EXPECT_TRUE(adj.inconsistent_edges.empty());
  EXPECT_EQ(adj.boundary_loops.size(), 1u);  // the deck edge, round both sides
  EXPECT_EQ(m.report.boundary_loops, 1u);
  ASSERT_EQ(s.face_count() % 2, 0u);
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    ASSERT_EQ(s.face_patch[f] >= n, f >= s.face_count() / 2) << f;
  }
  // Each image vertex is its half vertex mirrored (the placement is the identity here, so
  // exactly), and its (u, v) on the image patch is the mirror of the half vertex's on its patch.
  std::map<std::array<double, 3>, Index> half_at;
  for (std::size_t v = 0; v < s.vertex_count(); ++v) {
    if (s.vertex_patch[v] < n) half_at[{s.positions[v].x, s.positions[v].y, s.positions[v].z}] = v;
  }
  double worst = 0;
  std::size_t images = 0;
  for (std::size_t v = 0; v < s.vertex_count(); ++v) {
    if (s.vertex_patch[v] < n) continue;
    ++images;
    const Vec3d& p = s.positions[v];
    const auto it = half_at.find({p.x, -p.y, p.z});
    ASSERT_NE(it, half_at.end()) << v;
    const Index w = it->second;
    EXPECT_EQ(s.vertex_patch[v], s.vertex_patch[w] + n);
    const Vec3d a = evaluate(whole[s.vertex_patch[v]].surface, s.vertex_uv[v].x, s.vertex_uv[v].y);
    const Vec3d b = evaluate(whole[s.vertex_patch[w]].surface, s.vertex_uv[w].x, s.vertex_uv[w].y);
    worst = std::max(worst, norm(a - Vec3d{b.x, -b.y, b.z}));
  }
  EXPECT_LT(worst, 1e-9 * spec.length);
  EXPECT_GT(images, s.vertex_count() / 3);
  // The volume the whole encloses (to the deck), as the patches and their images merged together
  // enclose it.
  const Tessellation both = tessellate(whole, o, silent_progress());
  const MergedSurface together = merge_patches(whole, both.mesh, {}, silent_progress());
  EXPECT_NEAR(m.report.enclosed_volume, together.report.enclosed_volume,
              2e-3 * together.report.enclosed_volume);
}

}  // namespace
}  // namespace hm
