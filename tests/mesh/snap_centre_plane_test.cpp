// The open side of a half hull put on y = 0: only boundary vertices within the tolerance move.
#include "mesh/snap_centre_plane.h"

#include <gtest/gtest.h>

namespace hm {
namespace {

TEST(SnapToCentrePlane, MovesOnlyOpenBoundaryVerticesWithinTheTolerance) {
  // Two triangles sharing the edge 1-2; the open boundary is 0-1, 2-3, 3-0... (every edge but 1-2).
  SurfaceMesh m;
  m.positions = {{0, 1e-4, 0}, {1, 2e-3, 0}, {0, 5e-5, 1}, {1, 1, 1}};
  m.faces = {{0, 1, 2, kInvalid}, {1, 3, 2, kInvalid}};
  EXPECT_EQ(snap_to_centre_plane(m, 1e-3), 2u);
  EXPECT_EQ(m.positions[0].y, 0.0);
  EXPECT_EQ(m.positions[1].y, 2e-3);  // beyond the tolerance
  EXPECT_EQ(m.positions[2].y, 0.0);
  EXPECT_EQ(m.positions[3].y, 1.0);
  EXPECT_EQ(snap_to_centre_plane(m, 1e-3), 0u);  // nothing left to move
  // An interior vertex near the plane stays: a fan closed around vertex 4.
  SurfaceMesh fan;
  fan.positions = {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, {0.5, 1e-5, 0.5}};
  fan.faces = {{0, 1, 4, kInvalid}, {1, 2, 4, kInvalid}, {2, 3, 4, kInvalid}, {3, 0, 4, kInvalid}};
  EXPECT_EQ(snap_to_centre_plane(fan, 1e-3), 0u);
  EXPECT_EQ(fan.positions[4].y, 1e-5);
}

// Property seed 1987's stem: a sliver between the last station and the stem has a side on the
// plane (behind a face lying in the plane, which drop_centre_plane_faces removes) and a corner
// 2 cm off it, so its mirror image's centre would be within a twentieth of its size: both go
// onto the plane, and out. Farther off the plane (a real panel) it stays.
TEST(SnapToCentrePlane, ASliverThatWouldLieBackToBackWithItsMirrorGoesOntoThePlane) {
  for (const double off : {0.02, 0.2}) {
    // Faces round vertex 2 (an inner vertex: the first rule leaves it): the sliver 2-0-1, the
    // face 1-0-4 in the plane behind it, and 1-3-2, 0-2-5, 2-3-5 closing the fan.
    SurfaceMesh m;
    m.positions = {{0, 0, 0},    {2, 0, -2},     {0.1, off, -0.25},
                   {1, 1, -1.5}, {1.5, 0, -0.5}, {0.5, 1, 0.5}};
    m.faces = {{2, 0, 1, kInvalid},
               {1, 0, 4, kInvalid},
               {1, 3, 2, kInvalid},
               {0, 2, 5, kInvalid},
               {2, 3, 5, kInvalid}};
    const std::size_t moved = snap_to_centre_plane(m, 0.05);
    const std::size_t dropped = drop_centre_plane_faces(m);
    if (off < 0.05) {
      EXPECT_EQ(moved, 1u);
      EXPECT_EQ(m.positions[2].y, 0.0);
      EXPECT_EQ(dropped, 2u);
      EXPECT_EQ(m.face_count(), 3u);
    } else {
      EXPECT_EQ(moved, 0u);
      EXPECT_EQ(m.positions[2].y, off);
      EXPECT_EQ(dropped, 1u);  // the face in the plane alone
    }
  }
}

}  // namespace
}  // namespace hm

namespace hm {
namespace {

TEST(DropCentrePlaneFaces, RemovesOnlyFacesWhollyOnThePlaneAndKeepsProvenanceInStep) {
  SurfaceMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0.5, 1}, {2, 0, 0}};
  m.faces = {{0, 1, 2, kInvalid}, {1, 3, 2, kInvalid}, {1, 4, 3, kInvalid}};
  m.face_patch = {7, 8, 9};
  m.face_block = {0, 1, 2};
  EXPECT_EQ(drop_centre_plane_faces(m), 1u);
  ASSERT_EQ(m.face_count(), 2u);
  EXPECT_EQ(m.faces[0], (Face{1, 3, 2, kInvalid}));
  EXPECT_EQ(m.face_patch, (std::vector<PatchId>{8, 9}));
  EXPECT_EQ(m.face_block, (std::vector<Index>{1, 2}));
  // A face a little off the plane stays.
  m.positions[3].y = 1e-12;
  m.positions.push_back({0, 0, 2});
  m.faces.push_back({2, 3, 5, kInvalid});
  m.face_patch.push_back(1);
  m.face_block.push_back(3);
  EXPECT_EQ(drop_centre_plane_faces(m), 0u);
}

}  // namespace
}  // namespace hm
