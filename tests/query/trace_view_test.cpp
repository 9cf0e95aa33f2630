#include "query/trace_view.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "support/test_support.h"

namespace hm {
namespace {

// A quad (face 0) over x in [0, 1] and a triangle (face 1) over x in [1, 2], y in [0, 1], in the
// plane z = 0.25.
SurfaceMesh quad_and_triangle() {
  SurfaceMesh m;
  m.positions = {{0, 0, 0.25}, {1, 0, 0.25}, {1, 1, 0.25}, {0, 1, 0.25}, {2, 0, 0.25}};
  m.faces = {{0, 1, 2, 3}, {1, 4, 2, kInvalid}};
  m.face_patch = {0, 0};
  return m;
}

// Two unit squares facing each other: face 0 in the plane y = 0, face 1 in y = 1.
SurfaceMesh two_walls() {
  SurfaceMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1},
                 {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}};
  m.faces = {{0, 1, 2, 3}, {4, 5, 6, 7}};
  m.face_patch = {0, 0};
  return m;
}

// The centre of pixel (i, j)'s ray start, from the camera's panes.
Vec3d pixel_origin(const ViewCamera& cam, std::uint32_t i, std::uint32_t j) {
  for (const OrthoPane& p : cam.panes) {
    if (i >= p.first_column && i < p.first_column + p.columns)
      return p.origin + double(i - p.first_column) * p.step_right + double(j) * p.step_down;
  }
  ADD_FAILURE() << "no pane for column " << i;
  return {};
}

TEST(TraceView, PlanViewFindsTheFaceUnderEachPixelAndItsExactPoint) {
  const SurfaceMesh m = quad_and_triangle();
  const ViewCamera cam = fit_view_camera(m, ViewKind::kPlan, 200);
  ASSERT_EQ(cam.width, 200u);
  // 2 x 1 metres plus 3% of 2 m on each side: 2.12 m over 200 pixels.
  EXPECT_NEAR(cam.pixel_size, 2.12 / 200, 1e-12);
  EXPECT_EQ(cam.height, static_cast<std::uint32_t>(std::ceil(1.12 / cam.pixel_size - 1e-9)));
  const ViewHits h = trace_view(m, cam);
  ASSERT_EQ(h.face.size(), std::size_t{cam.width} * cam.height);
  std::size_t hits[2] = {0, 0};
  for (std::uint32_t j = 0; j < cam.height; ++j) {
    for (std::uint32_t i = 0; i < cam.width; ++i) {
      const std::size_t s = std::size_t{j} * cam.width + i;
      const Vec3d o = pixel_origin(cam, i, j);
      // The triangle is the corner (1, 0) (2, 0) (1, 1).
      const bool in_quad = o.x > 0 && o.x < 1 && o.y > 0 && o.y < 1;
      const bool in_tri = o.x > 1 && o.y > 0 && o.x + o.y < 2;
      const bool near_border = std::abs(o.x - 1) < 1e-6 || std::abs(o.x + o.y - 2) < 1e-6;
      if (near_border) continue;
      if (in_quad) {
        ASSERT_EQ(h.face[s], 0u) << i << " " << j;
      } else if (in_tri) {
        ASSERT_EQ(h.face[s], 1u) << i << " " << j;
      } else if (o.x < -1e-6 || o.x > 2 + 1e-6 || o.y < -1e-6 || o.y > 1 + 1e-6) {
        ASSERT_EQ(h.face[s], kInvalid) << i << " " << j;
      }
      if (h.face[s] != kInvalid) {
        ++hits[h.face[s]];
        // The hit lies on the plane and on the ray (rays run along +z from below).
        EXPECT_NEAR(h.point[s].z, 0.25, 1e-12);
        EXPECT_NEAR(h.point[s].x, o.x, 1e-12);
        EXPECT_NEAR(h.point[s].y, o.y, 1e-12);
      }
    }
  }
  // Pixel counts follow the areas (1 and 0.5 m^2), within a pixel row of the borders.
  const double per_m2 = 1 / (cam.pixel_size * cam.pixel_size);
  EXPECT_NEAR(hits[0], per_m2, 4 / cam.pixel_size);
  EXPECT_NEAR(hits[1], 0.5 * per_m2, 4 / cam.pixel_size);
  for (const Vec3d& d : h.column_dir) EXPECT_EQ(d, (Vec3d{0, 0, 1}));
}

TEST(TraceView, ProfileSeesTheNearerOfTwoWalls) {
  const SurfaceMesh m = two_walls();
  const ViewCamera cam = fit_view_camera(m, ViewKind::kProfile, 64);
  const ViewHits h = trace_view(m, cam);
  std::size_t hit = 0;
  for (std::size_t s = 0; s < h.face.size(); ++s) {
    if (h.face[s] == kInvalid) continue;
    ++hit;
    EXPECT_EQ(h.face[s], 0u);  // rays run along +y, so the wall at y = 0 is in front
    EXPECT_NEAR(h.point[s].y, 0.0, 1e-12);
  }
  const double expected = 1 / (cam.pixel_size * cam.pixel_size);
  EXPECT_NEAR(hit, expected, 4 / cam.pixel_size);
  // x grows to the right, z up: the top-left pixel of the wall is near (0, 1).
  const ViewCamera again = fit_view_camera(m, ViewKind::kProfile, 64);
  const Vec3d tl = pixel_origin(again, 0, 0), br = pixel_origin(again, 63, again.height - 1);
  EXPECT_LT(tl.x, br.x);
  EXPECT_GT(tl.z, br.z);
}

TEST(TraceView, BodyPlanShowsTheAftBodyLeftAndTheForeBodyRightMirrored) {
  // Transverse plates: face 0 at x = -1 (aft), face 1 at x = +1 (fore), y in [0, 1], z in [0, 1];
  // face 2 a keel strip joining them in the plane y = 0 (seen edge-on).
  SurfaceMesh m;
  m.positions = {{-1, 0, 0}, {-1, 1, 0}, {-1, 1, 1}, {-1, 0, 1},
                 {1, 0, 0},  {1, 1, 0},  {1, 1, 1},  {1, 0, 1}};
  m.faces = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 4, 7, 3}};
  m.face_patch = {0, 0, 0};
  const ViewCamera cam = fit_view_camera(m, ViewKind::kBodyPlan, 100);
  ASSERT_EQ(cam.panes.size(), 2u);
  EXPECT_DOUBLE_EQ(cam.centre_line_x, 50.0);
  const ViewHits h = trace_view(m, cam);
  const std::uint32_t mid_row = cam.height / 2;
  for (std::uint32_t i = 0; i < cam.width; ++i) {
    const std::size_t s = std::size_t{mid_row} * cam.width + i;
    // Distance of the column's centre from the centre line, in metres; the plates reach 1 m.
    const double off = std::abs(i + 0.5 - 50) * cam.pixel_size;
    if (off > 1 + 1e-9 || off < 1e-9) continue;
    if (i < 50) {
      ASSERT_EQ(h.face[s], 0u) << i;
      EXPECT_NEAR(h.point[s].x, -1.0, 1e-12);
      EXPECT_NEAR(h.point[s].y, off, 1e-12);  // mirrored: farther left is farther out
      EXPECT_EQ(h.column_dir[i], (Vec3d{1, 0, 0}));
    } else {
      ASSERT_EQ(h.face[s], 1u) << i;
      EXPECT_NEAR(h.point[s].x, 1.0, 1e-12);
      EXPECT_NEAR(h.point[s].y, off, 1e-12);
      EXPECT_EQ(h.column_dir[i], (Vec3d{-1, 0, 0}));
    }
  }
}

TEST(TraceView, SameHitsWithOneAndTwoThreads) {
  SurfaceMesh m;
  // A bumpy 30 x 20 grid of quads: many rays, rows split between threads.
  const int nx = 30, ny = 20;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      m.positions.push_back({double(i), double(j), std::sin(0.3 * i) * std::cos(0.4 * j)});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Index a = Index(j * (nx + 1) + i);
      m.faces.push_back({a, a + 1, a + nx + 2, a + nx + 1});
      m.face_patch.push_back(0);
    }
  const ViewCamera cam = fit_view_camera(m, ViewKind::kIso, 400);
  const ViewHits one = hm::test::with_threads(1, [&] { return trace_view(m, cam); });
  const ViewHits two = hm::test::with_threads(8, [&] { return trace_view(m, cam); });
  EXPECT_EQ(one.face, two.face);
  ASSERT_EQ(one.point.size(), two.point.size());
  for (std::size_t s = 0; s < one.point.size(); ++s) ASSERT_EQ(one.point[s], two.point[s]) << s;
  std::size_t hit = 0;
  for (Index f : one.face) hit += f != kInvalid;
  EXPECT_GT(hit, one.face.size() / 10);
}

TEST(TraceView, EmptyMeshAndBadIndicesAreGeometryErrors) {
  SurfaceMesh empty;
  EXPECT_THROW(fit_view_camera(empty, ViewKind::kProfile, 100), GeometryError);
  ViewCamera cam;
  EXPECT_THROW(trace_view(empty, cam), GeometryError);
  SurfaceMesh bad = quad_and_triangle();
  bad.faces[1][2] = 99;
  EXPECT_THROW(fit_view_camera(bad, ViewKind::kPlan, 100), GeometryError);
}

TEST(TraceView, TooTallAPictureIsAUsageError) {
  // A 1 m tall, 1 mm long plate seen from the side: the height would dwarf the width.
  SurfaceMesh m;
  m.positions = {{0, 0, 0}, {0.001, 0, 0}, {0.001, 0, 100}, {0, 0, 100}};
  m.faces = {{0, 1, 2, 3}};
  m.face_patch = {0};
  EXPECT_THROW(fit_view_camera(m, ViewKind::kProfile, 16000, 0.03, 2000), UsageError);
}

}  // namespace
}  // namespace hm
