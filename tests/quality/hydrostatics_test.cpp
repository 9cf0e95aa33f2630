#include "quality/hydrostatics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "mesh_builders.h"
#include "nurbs/generate_hull.h"
#include "nurbs/nurbs_surface.h"

namespace hm {
namespace {

constexpr double kPi = std::numbers::pi;

double rel(double got, double want) { return std::abs(got - want) / std::abs(want); }

// Keeps the faces of m whose normal does not point along -y (drops the centre-plane side).
SurfaceMesh drop_centre_plane(SurfaceMesh m) {
  std::vector<Face> kept;
  for (const Face& f : m.faces)
    if (face_normal(m.positions, f).y > -0.5) kept.push_back(f);
  m.faces = kept;
  m.face_patch.assign(kept.size(), 0);
  return m;
}

// The mirror image in y = 0, with corners reversed so the normals still point outward.
SurfaceMesh mirrored(const SurfaceMesh& m) {
  SurfaceMesh out = m;
  for (Vec3d& p : out.positions) p.y = -p.y;
  for (Face& f : out.faces) std::swap(f[1], f[is_triangle(f) ? 2 : 3]);
  return out;
}

TEST(Hydrostatics, BoxIsExact) {
  // L = 2, B = 2, depth 1, floating at draft 0.5; the cut runs through the side panels.
  const SurfaceMesh box = test::box_mesh({0, -1, 0}, {2, 1, 1}, 3);
  const Hydrostatics h = hydrostatics_mesh(box, {0.5, false});
  EXPECT_NEAR(h.volume, 2.0, 1e-13);
  EXPECT_NEAR(h.wetted_area, 4.0 + 4 * 1.0, 1e-13);
  EXPECT_NEAR(h.waterplane_area, 4.0, 1e-13);
  EXPECT_NEAR(h.buoyancy_centre.x, 1.0, 1e-13);
  EXPECT_NEAR(h.buoyancy_centre.y, 0.0, 1e-13);
  EXPECT_NEAR(h.buoyancy_centre.z, 0.25, 1e-13);
  EXPECT_NEAR(h.flotation_centre.x, 1.0, 1e-13);
  EXPECT_NEAR(h.i_transverse, 2.0 * 8 / 12, 1e-13);    // L B^3 / 12
  EXPECT_NEAR(h.i_longitudinal, 2.0 * 8 / 12, 1e-13);  // B L^3 / 12
  EXPECT_NEAR(h.bm_transverse, (4.0 / 3) / 2, 1e-13);
  EXPECT_EQ(h.waterline.size(), 1u);
  EXPECT_EQ(h.open_waterline_chains, 0u);
  // Fully submerged: the closed polyhedron's volume, centre at the middle, no waterplane.
  const Hydrostatics deep = hydrostatics_mesh(box, {3.0, false});
  EXPECT_NEAR(deep.volume, 4.0, 1e-13);
  EXPECT_NEAR(deep.buoyancy_centre.z, 0.5, 1e-13);
  EXPECT_NEAR(deep.waterplane_area, 0.0, 1e-13);
}

TEST(Hydrostatics, HalfBoxWithTheHalfFlagGivesTheSameTotals) {
  const SurfaceMesh full = test::box_mesh({0, -1, 0}, {2, 1, 1}, 4);
  const SurfaceMesh half = drop_centre_plane(test::box_mesh({0, 0, 0}, {2, 1, 1}, 4));
  const Hydrostatics hf = hydrostatics_mesh(full, {0.5, false});
  const Hydrostatics hh = hydrostatics_mesh(half, {0.5, true});
  EXPECT_NEAR(hh.volume, hf.volume, 1e-13);
  EXPECT_NEAR(hh.wetted_area, hf.wetted_area, 1e-13);
  EXPECT_NEAR(hh.waterplane_area, hf.waterplane_area, 1e-13);
  EXPECT_NEAR(hh.i_transverse, hf.i_transverse, 1e-13);
  EXPECT_NEAR(hh.i_longitudinal, hf.i_longitudinal, 1e-13);
  EXPECT_EQ(hh.buoyancy_centre.y, 0.0);
  EXPECT_EQ(hh.open_waterline_chains, 1u);  // closed on y = 0
}

// A half box whose transom (the face x = 0) is missing, as an open-transom file's is: the
// waterline breaks off at the transom, away from the centre plane, and the waterplane figures
// come from the panels' fluxes, which are exact for the box. The waterline polygon, closed
// straight back to its start, would have cut the waterplane in half.
TEST(Hydrostatics, OpenTransomTakesTheWaterplaneFromTheFluxes) {
  SurfaceMesh half = drop_centre_plane(test::box_mesh({0, 0, 0}, {2, 1, 1}, 4));
  std::vector<Face> kept;
  for (const Face& f : half.faces)
    if (face_normal(half.positions, f).x > -0.5) kept.push_back(f);
  half.faces = kept;
  half.face_patch.assign(kept.size(), 0);
  const Hydrostatics h = hydrostatics_mesh(half, {0.5, true});
  EXPECT_TRUE(h.waterplane_from_fluxes);
  EXPECT_NEAR(h.waterplane_area, 4.0, 1e-13);
  EXPECT_NEAR(h.flotation_centre.x, 1.0, 1e-13);
  EXPECT_NEAR(h.i_transverse, 2.0 * 8 / 12, 1e-13);
  EXPECT_NEAR(h.i_longitudinal, 2.0 * 8 / 12, 1e-13);
  // The closed half box keeps its polygon.
  const SurfaceMesh closed = drop_centre_plane(test::box_mesh({0, 0, 0}, {2, 1, 1}, 4));
  EXPECT_FALSE(hydrostatics_mesh(closed, {0.5, true}).waterplane_from_fluxes);
}

TEST(Hydrostatics, SphereVolumeConvergesAtSecondOrder) {
  // Expected order 2: the inscribed polyhedron's error is O(h^2) in the panel size.
  auto err = [](int n) {
    const SurfaceMesh s = test::sphere_mesh(1.0, {0, 0, 0}, 2 * n, n);
    const Hydrostatics h = hydrostatics_mesh(s, {0.0, false});  // half submerged
    EXPECT_NEAR(h.buoyancy_centre.x, 0.0, 1e-12);
    EXPECT_NEAR(h.buoyancy_centre.y, 0.0, 1e-12);
    return std::array{rel(h.volume, 2 * kPi / 3), rel(h.waterplane_area, kPi),
                      rel(h.buoyancy_centre.z, -3.0 / 8)};
  };
  const auto e1 = err(16), e2 = err(32);
  for (int k = 0; k < 3; ++k) {
    const double order = std::log2(e1[k] / e2[k]);
    EXPECT_NEAR(order, 2.0, 0.15) << "quantity " << k;
  }
  EXPECT_LT(e2[0], 5e-3);
}

// The generated Wigley hull (port half): y = B/2 (1 - (2x/L - 1)^2)(1 - (z/T - 1)^2), keel at
// z = 0, waterline z = T. Closed forms (whole hull), from the waterline y_w(x) = B/2 (1 - xi^2)
// with xi = 2x/L - 1 and the sections:
//   V = 4/9 L B T;  VCB = 5/8 T (int (1 + zeta)(1 - zeta^2) d zeta over [-1, 0] = 5/12,
//   divided by int (1 - zeta^2) = 2/3);  LCB = LCF = L/2;
//   A_wp = 2 int y_w dx = 2/3 L B;
//   I_T = 2 int y_w^3 / 3 dx = (2/3)(B/2)^3 (L/2) int (1 - xi^2)^3 dxi = (2/3)(B/2)^3 L (16/35);
//   I_L = 2 int (x - L/2)^2 y_w dx = B (L/2)^3 int xi^2 (1 - xi^2) dxi = B L^3 / 30.
struct WigleyExact {
  double l, b, t;
  double volume() const { return 4.0 / 9 * l * b * t; }
  double vcb() const { return 5.0 / 8 * t; }
  double awp() const { return 2.0 / 3 * l * b; }
  double i_t() const { return 2.0 / 3 * std::pow(b / 2, 3) * l * 16 / 35; }
  double i_l() const { return b * l * l * l / 30; }
  // Wetted area by composite Gauss on the formula (independent of the NURBS): both sides.
  double wetted_area() const {
    const double g[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                         0.9061798459386640};
    const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                         0.4786286704993665, 0.2369268850561891};
    const int n = 64;
    double sum = 0;
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 5; ++a) {
        const double x = l * (i + 0.5 + 0.5 * g[a]) / n;
        for (int j = 0; j < n; ++j)
          for (int c = 0; c < 5; ++c) {
            const double z = t * (j + 0.5 + 0.5 * g[c]) / n;
            const double xi = 2 * x / l - 1, ze = z / t - 1;
            const double yx = b / 2 * (-2 * xi * 2 / l) * (1 - ze * ze);
            const double yz = b / 2 * (1 - xi * xi) * (-2 * ze / t);
            sum += w[a] * w[c] * std::sqrt(1 + yx * yx + yz * yz);
          }
      }
    return 2 * sum * (l / n / 2) * (t / n / 2);
  }
};

GeneratedHull wigley() {
  HullSpec spec;
  spec.kind = HullKind::kWigley;
  return generate_hull(spec);  // L 100, B 10, T 6.25, depth 8, port half, one patch
}

TEST(Hydrostatics, WigleyNurbsMatchesTheClosedForm) {
  const GeneratedHull hull = wigley();
  const WigleyExact ex{100, 10, 6.25};
  const Hydrostatics h = hydrostatics_nurbs(hull.patches, {6.25, true});
  EXPECT_LT(rel(h.volume, ex.volume()), 1e-8) << h.volume;
  EXPECT_LT(rel(h.waterplane_area, ex.awp()), 1e-8) << h.waterplane_area;
  EXPECT_LT(rel(h.buoyancy_centre.x, 50), 1e-8);
  EXPECT_LT(rel(h.buoyancy_centre.z, ex.vcb()), 1e-8) << h.buoyancy_centre.z;
  EXPECT_LT(rel(h.flotation_centre.x, 50), 1e-8);
  EXPECT_LT(rel(h.i_transverse, ex.i_t()), 1e-8) << h.i_transverse;
  EXPECT_LT(rel(h.i_longitudinal, ex.i_l()), 1e-8) << h.i_longitudinal;
  EXPECT_LT(rel(h.wetted_area, ex.wetted_area()), 1e-8) << h.wetted_area;
  EXPECT_LT(rel(h.bm_transverse, ex.i_t() / ex.volume()), 1e-8);
  EXPECT_EQ(h.buoyancy_centre.y, 0.0);
}

TEST(Hydrostatics, WigleyNurbsAtAnotherDraftAgreesWithTheMesh) {
  // Cut at z = 4 (inside the patch, not at a parameter line of a knot): NURBS vs a fine mesh.
  const GeneratedHull hull = wigley();
  const Hydrostatics hn = hydrostatics_nurbs(hull.patches, {4.0, true});
  const NurbsSurface& s = hull.patches[0].surface;
  const SurfaceMesh m = test::grid_mesh(160, 64, [&](double u, double v) {
    return evaluate(s, s.u0 + u * (s.u1 - s.u0), s.v0 + v * (s.v1 - s.v0));
  });
  const Hydrostatics hm = hydrostatics_mesh(m, {4.0, true});
  EXPECT_LT(rel(hm.volume, hn.volume), 2e-4);
  EXPECT_LT(rel(hm.waterplane_area, hn.waterplane_area), 2e-4);
  EXPECT_LT(rel(hm.wetted_area, hn.wetted_area), 2e-4);
  EXPECT_LT(rel(hm.i_transverse, hn.i_transverse), 1e-3);
}

// A mesh of the wetted Wigley half hull: n panels along x, m down to the keel, from the NURBS.
SurfaceMesh wigley_mesh(const NurbsSurface& s, int n, int m, double v_waterline) {
  return test::grid_mesh(n, m, [&](double u, double v) {
    return evaluate(s, s.u0 + u * (s.u1 - s.u0), v_waterline + v * (s.v1 - v_waterline));
  });
}

TEST(Hydrostatics, WigleyMeshConvergesAtSecondOrder) {
  // Expected order of convergence: 2 (flat panels through points of a smooth surface).
  const GeneratedHull hull = wigley();
  const NurbsSurface& s = hull.patches[0].surface;
  const WigleyExact ex{100, 10, 6.25};
  const double v_wl = 1 - 6.25 / 8.0;  // z = 8 (1 - v): the waterline row
  auto errors = [&](int n, int m) {
    const Hydrostatics h = hydrostatics_mesh(wigley_mesh(s, n, m, v_wl), {6.25, true});
    return std::array{rel(h.volume, ex.volume()), rel(h.waterplane_area, ex.awp()),
                      rel(h.i_transverse, ex.i_t())};
  };
  const auto e1 = errors(20, 8), e2 = errors(40, 16);
  std::printf(
      "Wigley mesh relative errors (V, Awp, I_T): 20x8 %.3e %.3e %.3e, 40x16 %.3e %.3e %.3e\n",
      e1[0], e1[1], e1[2], e2[0], e2[1], e2[2]);
  for (int k = 0; k < 3; ++k) {
    const double order = std::log2(e1[k] / e2[k]);
    EXPECT_NEAR(order, 2.0, 0.2) << "quantity " << k << ": " << e1[k] << " -> " << e2[k];
  }
  EXPECT_LT(e2[0], 5e-3);
}

TEST(Hydrostatics, WigleyHalfAndMirroredFullMeshGiveTheSameTotals) {
  const GeneratedHull hull = wigley();
  const SurfaceMesh half = wigley_mesh(hull.patches[0].surface, 24, 10, 1 - 6.25 / 8.0);
  SurfaceMesh full = half;
  test::append(full, mirrored(half));
  test::merge_vertices(full);
  const Hydrostatics hh = hydrostatics_mesh(half, {6.25, true});
  const Hydrostatics hf = hydrostatics_mesh(full, {6.25, false});
  EXPECT_LT(rel(hh.volume, hf.volume), 1e-12);
  EXPECT_LT(rel(hh.wetted_area, hf.wetted_area), 1e-12);
  EXPECT_LT(rel(hh.waterplane_area, hf.waterplane_area), 1e-12);
  EXPECT_LT(rel(hh.i_transverse, hf.i_transverse), 1e-12);
  EXPECT_LT(rel(hh.i_longitudinal, hf.i_longitudinal), 1e-12);
  EXPECT_LT(rel(hh.buoyancy_centre.z, hf.buoyancy_centre.z), 1e-12);
  EXPECT_NEAR(hf.buoyancy_centre.y, 0.0, 1e-12);
  EXPECT_EQ(hf.open_waterline_chains, 0u);
  EXPECT_EQ(hh.open_waterline_chains, 1u);
}

TEST(Hydrostatics, ClippingAMeshThatRisesAboveTheWaterline) {
  // The whole generated patch (up to z = 8), clipped at z = 6.25, against the wetted-only mesh
  // of the same rows below the waterline: the same polyhedron where they overlap.
  const GeneratedHull hull = wigley();
  const NurbsSurface& s = hull.patches[0].surface;
  const WigleyExact ex{100, 10, 6.25};
  const Hydrostatics h =
      hydrostatics_mesh(wigley_mesh(s, 80, 64, 0.0), {6.25, true});  // cut inside a row
  EXPECT_LT(rel(h.volume, ex.volume()), 1e-3);
  EXPECT_LT(rel(h.waterplane_area, ex.awp()), 1e-3);
  EXPECT_EQ(h.lid_faces, 0u);
}

TEST(Hydrostatics, PlacementRotatesAboutThePivotOnTheWaterplane) {
  const Placement p = floating_placement(5.0, 1.0, 0.0, 0.0, 50.0);
  EXPECT_EQ(p.waterline_z, 5.0);
  const Vec3d pivot = p.transform({50, 0, 5});
  EXPECT_NEAR(norm(pivot - Vec3d{50, 0, 5}), 0.0, 1e-12);
  // Bow down for positive trim: the keel point at the bow (x = 100) sinks by 50 sin(1 deg).
  const Vec3d bow = p.transform({100, 0, 0});
  EXPECT_NEAR(bow.z, 5 - 50 * std::sin(kPi / 180) - 5 * std::cos(kPi / 180), 1e-12);
  // Heel: positive lifts the port side.
  const Placement q = floating_placement(5.0, 0.0, 10.0);
  EXPECT_GT(q.transform({0, 3, 5}).z, 5.0);
  // A sphere's volume does not depend on heel.
  const SurfaceMesh ball = test::sphere_mesh(1.0, {0, 0, 0}, 64, 32);
  const Placement r = floating_placement(1.0, 0.0, 0.0, -1.0);
  const Hydrostatics upright = hydrostatics_mesh(transformed(ball, r.transform), {r.waterline_z});
  EXPECT_NEAR(upright.volume, hydrostatics_mesh(ball, {0.0}).volume, 1e-12);
}

}  // namespace
}  // namespace hm
