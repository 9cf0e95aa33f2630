// The lid closes a wetted hull at its waterline: the same waterline vertices, normals up, a
// triangulation of exactly the waterplane inside the waterline, with well-shaped triangles.
#include "mesh/make_lid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "core/error.h"

namespace hm {
namespace {

constexpr double kPi = std::numbers::pi;

// The lower half of the ellipsoid x^2/a^2 + y^2/b^2 + z^2/c^2 = 1 (a wetted "hull" cut at z = 0),
// as quads on a longitude-latitude grid, normals outwards. With half set, only y >= 0.
SurfaceMesh bowl(double a, double b, double c, int n_around, int n_down, bool half) {
  SurfaceMesh m;
  const int cols = half ? n_around / 2 + 1 : n_around;
  // Ring j = 0 is the waterline (z = 0); the bottom pole closes the last ring.
  for (int j = 0; j < n_down; ++j) {
    const double phi = 0.5 * kPi * j / n_down;  // 0 at the waterline
    for (int i = 0; i < cols; ++i) {
      const double th = 2 * kPi * i / n_around;
      m.positions.push_back(
          {a * std::cos(phi) * std::cos(th), b * std::cos(phi) * std::sin(th), -c * std::sin(phi)});
    }
  }
  const Index pole = static_cast<Index>(m.positions.size());
  m.positions.push_back({0, 0, -c});
  for (auto& p : m.positions) {
    if (std::abs(p.z) < 1e-15) p.z = 0;
    if (half && std::abs(p.y) < 1e-12) p.y = 0;
  }
  const int spans = half ? cols - 1 : cols;
  auto at = [&](int i, int j) { return static_cast<Index>(j * cols + (i % cols)); };
  for (int j = 0; j + 1 < n_down; ++j) {
    for (int i = 0; i < spans; ++i) {
      // Seen from outside, (i, j) -> (i, j + 1) -> (i + 1, j + 1) -> (i + 1, j) turns
      // counter-clockwise: normal outwards.
      m.faces.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
    }
  }
  for (int i = 0; i < spans; ++i)
    m.faces.push_back({at(i, n_down - 1), pole, at(i + 1, n_down - 1), kInvalid});
  m.face_patch.assign(m.faces.size(), 0);
  return m;
}

Vec3d newell(const SurfaceMesh& m, const Face& f) { return face_normal(m.positions, f); }

// Free edges of a mesh (used by one face), as (lo, hi) vertex pairs.
std::vector<std::pair<Index, Index>> free_edges(const SurfaceMesh& m) {
  std::map<std::pair<Index, Index>, int> count;
  for (const Face& f : m.faces) {
    const int n = corner_count(f);
    for (int k = 0; k < n; ++k) {
      const Index a = f[k], b = f[(k + 1) % n];
      ++count[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<std::pair<Index, Index>> out;
  for (const auto& [e, c] : count) {
    if (c == 1) out.push_back(e);
  }
  return out;
}

double min_angle_deg(const SurfaceMesh& m, const Face& f) {
  double worst = 180;
  for (int k = 0; k < 3; ++k) {
    const Vec3d p = m.positions[f[k]];
    const Vec3d u = m.positions[f[(k + 1) % 3]] - p, v = m.positions[f[(k + 2) % 3]] - p;
    worst = std::min(worst, std::acos(dot(u, v) / (norm(u) * norm(v))) * 180 / kPi);
  }
  return worst;
}

TEST(MakeLid, ClosesAFullHullWithUpwardWellShapedTriangles) {
  const SurfaceMesh hull = bowl(10, 2, 1.5, 96, 8, false);
  const Lid lid = make_lid(hull);
  EXPECT_EQ(lid.report.loops, 1u);
  EXPECT_EQ(lid.report.waterline_vertices, 96u);
  EXPECT_FALSE(lid.report.half);
  EXPECT_GT(lid.report.interior_vertices, 20u);
  // The lid covers exactly the waterline polygon (96 corners of the ellipse).
  const double polygon = 0.5 * 96 * 10 * 2 * std::sin(2 * kPi / 96);
  EXPECT_NEAR(lid.report.area, polygon, 1e-9 * polygon);
  double area = 0, worst = 180;
  for (const Face& f : lid.mesh.faces) {
    ASSERT_TRUE(is_triangle(f));
    EXPECT_GT(newell(lid.mesh, f).z, 0.999);
    area += face_area(lid.mesh.positions, f);
    worst = std::min(worst, min_angle_deg(lid.mesh, f));
  }
  EXPECT_NEAR(area, polygon, 1e-9 * polygon);
  EXPECT_GT(worst, 15.0);  // 17 deg here, at the fine bow and stern ends
  for (const Vec3d& p : lid.mesh.positions) EXPECT_EQ(p.z, 0.0);
  // Hull and lid together: closed, every edge used twice.
  const SurfaceMesh closed = append_lid(hull, lid);
  EXPECT_TRUE(free_edges(closed).empty());
  EXPECT_EQ(closed.faces.size(), hull.faces.size() + lid.mesh.faces.size());
  // The lid's only free edges are the waterline's.
  EXPECT_EQ(free_edges(lid.mesh).size(), 96u);
}

TEST(MakeLid, HalfHullIsClosedAlongTheCentrePlane) {
  const SurfaceMesh hull = bowl(10, 2, 1.5, 96, 8, true);
  const Lid lid = make_lid(hull);
  EXPECT_TRUE(lid.report.half);
  EXPECT_EQ(lid.report.waterline_vertices, 49u);
  // The centre segment is 20 m long, spaced at the lid's target edge.
  const double spacing = 20.0 / (lid.report.centre_vertices + 1);
  EXPECT_NEAR(spacing, lid.report.edge_length, 0.05 * lid.report.edge_length);
  const double polygon = 0.5 * 48 * 10 * 2 * std::sin(2 * kPi / 96);
  EXPECT_NEAR(lid.report.area, polygon, 1e-9 * polygon);
  for (const Face& f : lid.mesh.faces) EXPECT_GT(newell(lid.mesh, f).z, 0.999);
  for (const Vec3d& p : lid.mesh.positions) EXPECT_GE(p.y, 0.0);
  // Appended, the only free edges left are on the centre plane.
  const SurfaceMesh closed = append_lid(hull, lid);
  const auto open = free_edges(closed);
  EXPECT_FALSE(open.empty());
  for (const auto& [a, b] : open) {
    EXPECT_EQ(closed.positions[a].y, 0.0);
    EXPECT_EQ(closed.positions[b].y, 0.0);
  }
}

TEST(MakeLid, SameLidEveryTime) {
  const SurfaceMesh hull = bowl(7, 1.3, 1, 64, 6, false);
  const Lid a = make_lid(hull), b = make_lid(hull);
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
  ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
  for (std::size_t k = 0; k < a.mesh.positions.size(); ++k)
    EXPECT_TRUE(a.mesh.positions[k] == b.mesh.positions[k]);
}

TEST(MakeLid, HullsWithoutAClosedWaterlineAreRefused) {
  // Nothing on z = 0: the bowl lifted.
  SurfaceMesh dry = bowl(10, 2, 1.5, 32, 4, false);
  for (Vec3d& p : dry.positions) p.z -= 0.5;
  EXPECT_THROW(make_lid(dry), GeometryError);
  // A hole at the waterline: drop the first column of panels of a full hull.
  SurfaceMesh holed = bowl(10, 2, 1.5, 32, 4, false);
  std::vector<Face> kept;
  for (std::size_t k = 0; k < holed.faces.size(); ++k) {
    if (k % 32 != 5) kept.push_back(holed.faces[k]);
  }
  holed.faces = kept;
  holed.face_patch.assign(kept.size(), 0);
  try {
    make_lid(holed);
    FAIL() << "a waterline broken by a hole made a lid";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("waterline"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hm
