// The acceptance checks on a whole tessellated hull, shared by the hull tests.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tess_fixtures.h"
#include "tessellate/tessellate.h"

namespace hm::test {

// Measured chord error within tolerance, no zero-area triangle, each patch a manifold,
// consistently oriented surface with one boundary loop per trim loop (one more for a seam).
inline void expect_good_tessellation(const std::vector<Patch>& patches, const Tessellation& t,
                                     const std::string& what) {
  EXPECT_LE(t.summary.max_chord_error, t.summary.chord_tolerance) << what;
  ASSERT_GT(t.mesh.face_count(), 0u) << what;
  const double tiny = 1e-10 * t.summary.edge_length * t.summary.edge_length;
  std::size_t zero = 0;
  for (std::size_t f = 0; f < t.mesh.face_count(); ++f) zero += triangle_area(t.mesh, f) <= tiny;
  EXPECT_EQ(zero, 0u) << what;
  for (PatchId p = 0; p < patches.size(); ++p) {
    const Topology top = patch_topology(t.mesh, p);
    EXPECT_TRUE(top.manifold) << what << " patch " << p;
    EXPECT_TRUE(top.oriented) << what << " patch " << p;
    const int loops = patches[p].loops.empty() ? 1 : int(patches[p].loops.size());
    // A closed patch (seam) has one loop more and Euler characteristic 0.
    EXPECT_GE(top.boundary_loops, loops) << what << " patch " << p;
    EXPECT_EQ(top.euler, 2 - top.boundary_loops) << what << " patch " << p;
  }
}

}  // namespace hm::test
