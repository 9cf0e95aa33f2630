// Where the two halves of a full hull meet in the centre plane at angles too fine for the snap's
// fold test: the halves' border runs must be stitched, not left for the hole filler.
#include <gtest/gtest.h>

#include <string>

#include "support/hull_spec.h"
#include "unstructured/merge_support.h"

namespace hm::test {
namespace {

std::size_t zero_area_faces(const SurfaceMesh& m, double length) {
  std::size_t n = 0;
  for (const Face& f : m.faces) n += face_area(m.positions, f) <= 1e-12 * length * length;
  return n;
}

// The property test's seed 1121: a full Wigley hull of 5 patches, 72.7 m. At the stern, near
// the keel, the two halves' border runs lie on one line (x = 0, y = 0) and their inward
// directions differ by less than the 5 degrees the snap's centre-plane exception asked, so they
// were left apart, and the slit between them was filled with faces of no area (8 of them under
// the unstructured mesher at 1,100 panels, 47,868 fine triangles: --validate refused the cut).
// A vertex lying on the other half's border line is stitched whatever the angle.
TEST(MergeCentrePlane, HalvesMeetingOnOneLineAtTheSternAreStitched) {
  const HullSpec spec =
      hull_spec(HullKind::kWigley, 72.6888, 6.99683, 2.26431, 2.87619, 5, /*full=*/true);
  const std::vector<Patch> patches = generate_hull(spec).patches;
  const Merged m = merge_of(patches, edge_length_for_triangles(patches, 48000));
  EXPECT_EQ(zero_area_faces(m.merged.mesh, 72.6888), 0u);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);  // the deck edge
  EXPECT_GT(m.merged.report.enclosed_volume, 0.0);
}

}  // namespace
}  // namespace hm::test
