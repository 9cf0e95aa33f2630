// IGES reader: each surface and curve type converted to NURBS, checked against its exact
// geometry by evaluating points; transforms and trim loops.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "iges/read_iges.h"
#include "iges_test_entities.h"
#include "iges_text_builder.h"
#include "nurbs/nurbs_curve.h"
#include "nurbs/nurbs_surface.h"

namespace hm {
namespace {

using test::DirFields;
using test::IgesTextBuilder;
using test::num;
constexpr double kPi = std::numbers::pi;

std::vector<std::string> arc_100(double zt, double cx, double cy, double sx, double sy, double ex,
                                 double ey) {
  return {num(zt), num(cx), num(cy), num(sx), num(sy), num(ex), num(ey)};
}

double radius_xy(const Vec3d& p) { return std::hypot(p.x, p.y); }

// Evaluates over an n x n grid of the domain.
template <class F>
void for_grid(const NurbsSurface& s, int n, F f) {
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double u = s.u0 + (s.u1 - s.u0) * i / n, v = s.v0 + (s.v1 - s.v0) * j / n;
      f(u, v, evaluate(s, u, v));
    }
  }
}

TEST(IgesGeometry, RuledSurfaceBetweenLineAndQuadraticIsExact) {
  for (int dirflg : {0, 1}) {
    IgesTextBuilder b;
    const int l = b.add(110, test::line_110({0, 0, 0}, {2, 0, 0}));
    const int q = b.add(126, {"2",  "2",  "0",  "0",  "1",  "0",  "0.", "0.", "0.", "1.",
                              "1.", "1.", "1.", "1.", "1.", "0.", "1.", "1.", "1.", "1.",
                              "2.", "2.", "1.", "1.", "0.", "1.", "0.", "0.", "1."});
    b.add(118, {num(l), num(q), num(dirflg), "0"}, DirFields{1});
    const ImportResult r = read_iges(b.build(), "ruled.igs");
    ASSERT_EQ(r.patches.size(), 1u);
    const NurbsSurface& s = r.patches[0].surface;
    EXPECT_EQ(r.patches[0].source_type, 118);
    for_grid(s, 8, [&](double u, double v, const Vec3d& p) {
      const double w = dirflg ? 1 - u : u;  // rail 2 runs backwards when DIRFLG = 1
      const Vec3d c1{2 * u, 0, 0}, c2{2 * w, 1, 1 + 2 * w - 2 * w * w};
      const Vec3d expect = (1 - v) * c1 + v * c2;
      EXPECT_NEAR(norm(p - expect), 0, 1e-12) << u << " " << v;
    });
  }
}

TEST(IgesGeometry, RuledSurfaceBetweenArcsIsAnExactCone) {
  IgesTextBuilder b;
  const int a1 = b.add(100, arc_100(0, 0, 0, 1, 0, 0, 1));
  const int a2 = b.add(100, arc_100(1, 0, 0, 2, 0, 0, 2));
  b.add(118, {num(a1), num(a2), "0", "1"}, DirFields{1});
  const ImportResult r = read_iges(b.build(), "cone.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  for_grid(r.patches[0].surface, 10, [&](double, double, const Vec3d& p) {
    EXPECT_NEAR(radius_xy(p), 1 + p.z, 1e-12);
    EXPECT_GE(p.x, -1e-12);
    EXPECT_GE(p.y, -1e-12);
  });
}

TEST(IgesGeometry, SurfaceOfRevolutionIsExact) {
  IgesTextBuilder b;
  const int axis = b.add(110, test::line_110({0, 0, 0}, {0, 0, 1}));
  const int gen = b.add(126, test::polyline_126({{1, 0, 0}, {2, 0, 1}}));
  b.add(120, {num(axis), num(gen), "0.", num(kPi)});
  const ImportResult r = read_iges(b.build(), "rev.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const NurbsSurface& s = r.patches[0].surface;
  EXPECT_EQ(r.patches[0].source_type, 120);
  EXPECT_DOUBLE_EQ(s.v0, 0.0);
  EXPECT_DOUBLE_EQ(s.v1, kPi);
  for_grid(s, 12, [&](double, double, const Vec3d& p) {
    EXPECT_NEAR(radius_xy(p), 1 + p.z, 1e-12);
    EXPECT_GE(p.y, -1e-12);
  });
  // At the knots the parameter is the angle.
  const Vec3d mid = evaluate(s, 0.5, kPi / 2);
  EXPECT_NEAR(norm(mid - Vec3d{0, 1.5, 0.5}), 0, 1e-12);
}

TEST(IgesGeometry, TabulatedCylinderIsExact) {
  IgesTextBuilder b;
  const int arc = b.add(100, arc_100(0, 0, 0, 1, 0, 0, 1));
  b.add(122, {num(arc), "1.", "0.", "3."});
  const ImportResult r = read_iges(b.build(), "tab.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const NurbsSurface& s = r.patches[0].surface;
  for_grid(s, 10, [&](double, double v, const Vec3d& p) {
    EXPECT_NEAR(radius_xy(p), 1, 1e-12);
    EXPECT_NEAR(p.z, 3 * v, 1e-12);
  });
  EXPECT_NEAR(norm(evaluate(s, s.u1, 1) - Vec3d{0, 1, 3}), 0, 1e-12);
}

TEST(IgesGeometry, BoundedPlaneKeepsItsCircleAsTheLoop) {
  IgesTextBuilder b;
  const int circle = b.add(100, arc_100(1, 0, 0, 2, 0, 2, 0));
  b.add(108, {"0.", "0.", "1.", "1.", num(circle), "0.", "0.", "1.", "1."}, DirFields{1});
  const ImportResult r = read_iges(b.build(), "plane.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const Patch& p = r.patches[0];
  EXPECT_EQ(p.source_type, 108);
  for_grid(p.surface, 4, [&](double, double, const Vec3d& q) { EXPECT_NEAR(q.z, 1, 1e-12); });
  ASSERT_EQ(p.loops.size(), 1u);
  for (const NurbsCurve& c : p.loops[0].curves_uv) {
    for (int k = 0; k <= 16; ++k) {
      const Vec3d uv = evaluate(c, c.t0 + (c.t1 - c.t0) * k / 16);
      EXPECT_NEAR(radius_xy(evaluate(p.surface, uv.x, uv.y)), 2, 1e-9);
    }
  }
}

TEST(IgesGeometry, PlaneSurfaceBoundedByATrimmedSurfacesModelCurves) {
  IgesTextBuilder b;
  const int pt = b.add(116, {"0.", "0.", "5.", "0"});
  const int n = b.add(123, {"0.", "0.", "1."});
  const int ref = b.add(123, {"1.", "0.", "0."});
  const int plane = b.add(190, {num(pt), num(n), num(ref)}, DirFields{1});
  std::vector<int> sides;
  const Vec3d c[4] = {{-1, 0, 5}, {3, 0, 5}, {3, 2, 5}, {-1, 2, 5}};
  for (int k = 0; k < 4; ++k) sides.push_back(b.add(110, test::line_110(c[k], c[(k + 1) % 4])));
  const int comp = b.add(102, {"4", num(sides[0]), num(sides[1]), num(sides[2]), num(sides[3])});
  const int cos = b.add(142, {"0", num(plane), "0", num(comp), "2"});
  b.add(144, {num(plane), "1", "0", num(cos)});
  const ImportResult r = read_iges(b.build(), "p190.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const Patch& p = r.patches[0];
  EXPECT_EQ(p.source_type, 190);
  EXPECT_EQ(p.wrapping, Wrapping::kTrimmed);
  EXPECT_TRUE(p.loops.empty()) << "the square is the plane patch's whole domain";
  EXPECT_NEAR(r.bbox.lo.x, -1, 1e-12);
  EXPECT_NEAR(r.bbox.hi.x, 3, 1e-12);
  EXPECT_NEAR(r.bbox.hi.y, 2, 1e-12);
  EXPECT_NEAR(r.bbox.lo.z, 5, 1e-12);
  EXPECT_EQ(r.skipped_by_type.size(), 0u);
}

TEST(IgesGeometry, UnboundedPlaneBoundedByA143Boundary) {
  IgesTextBuilder b;
  const int plane = b.add(108, {"0.", "0.", "2.", "4.", "0", "0.", "0.", "0.", "0."});  // z = 2
  const int circle = b.add(100, arc_100(2, 1, 1, 4, 1, 4, 1));                          // r = 3
  const int bnd = b.add(141, {"0", "1", num(plane), "1", num(circle), "1", "0"});
  b.add(143, {"0", num(plane), "1", num(bnd)});
  const ImportResult r = read_iges(b.build(), "p108.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const Patch& p = r.patches[0];
  EXPECT_EQ(p.source_type, 108);
  EXPECT_EQ(p.wrapping, Wrapping::kBounded);
  ASSERT_EQ(p.loops.size(), 1u);
  for (const NurbsCurve& c : p.loops[0].curves_uv) {
    for (int k = 0; k <= 16; ++k) {
      const Vec3d uv = evaluate(c, c.t0 + (c.t1 - c.t0) * k / 16);
      const Vec3d q = evaluate(p.surface, uv.x, uv.y);
      EXPECT_NEAR(std::hypot(q.x - 1, q.y - 1), 3, 1e-5);
      EXPECT_NEAR(q.z, 2, 1e-12);
    }
  }
}

TEST(IgesGeometry, ParametricSplineSurfaceBecomesExactBezierPieces) {
  // One patch on [0, 2] x [0, 1]: x = s, y = t, z = s t + 0.25 s^3 t^2.
  std::vector<std::string> p{"3", "1", "1", "1", "0.", "2.", "0.", "1."};
  std::vector<double> x(16, 0.0), y(16, 0.0), z(16, 0.0);
  x[1] = 1;             // B: s
  y[4] = 1;             // E: t
  z[1 + 4 * 1] = 1;     // F: s t
  z[3 + 4 * 2] = 0.25;  // N: s^3 t^2
  for (const auto* a : {&x, &y, &z}) {
    for (double c : *a) p.push_back(num(c));
  }
  for (int k = 0; k < 48 + 96; ++k) p.push_back("0.");  // the spare values of the format
  IgesTextBuilder b;
  b.add(114, p);
  const ImportResult r = read_iges(b.build(), "s114.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const NurbsSurface& s = r.patches[0].surface;
  EXPECT_DOUBLE_EQ(s.u1, 2.0);
  for_grid(s, 8, [&](double u, double v, const Vec3d& q) {
    const Vec3d expect{u, v, u * v + 0.25 * u * u * u * v * v};
    EXPECT_NEAR(norm(q - expect), 0, 1e-12);
  });
}

TEST(IgesGeometry, ParametricSplineCurveAsARuledRail) {
  IgesTextBuilder b;
  // 112: one cubic segment on [0, 1]: x = t, y = t^2, z = 0.
  const int c = b.add(112, {"3",  "1",  "2",  "1",  "0.", "1.", "0.", "1.", "0.", "0.",
                            "0.", "0.", "1.", "0.", "0.", "0.", "0.", "0.", "1.", "1.",
                            "0.", "0.", "0.", "0.", "0.", "0.", "0.", "0.", "0."});
  const int l = b.add(110, test::line_110({0, 0, 1}, {1, 0, 1}));
  b.add(118, {num(c), num(l), "0", "0"}, DirFields{1});
  const ImportResult r = read_iges(b.build(), "s112.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  for (int k = 0; k <= 10; ++k) {
    const double t = k / 10.0;
    EXPECT_NEAR(norm(evaluate(r.patches[0].surface, t, 0) - Vec3d{t, t * t, 0}), 0, 1e-12);
  }
}

TEST(IgesGeometry, TransformChainAppliesInnerThenOuter) {
  IgesTextBuilder b;
  // DE 1: surface -> DE 3 (translate +10 x) -> DE 5 (rotate 90 degrees about z).
  b.add(128, test::square(0, 0, 1).params(), DirFields{0, 3});
  b.add(124, {"1", "0", "0", "10", "0", "1", "0", "0", "0", "0", "1", "0"}, DirFields{0, 5});
  b.add(124, {"0", "-1", "0", "0", "1", "0", "0", "0", "0", "0", "1", "0"});
  const ImportResult r = read_iges(b.build(), "chain.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const NurbsSurface& s = r.patches[0].surface;
  EXPECT_NEAR(norm(s.points[1] - Vec3d{0, 11, 0}), 0, 1e-12);   // (1,0,0) -> (11,0,0) -> (0,11,0)
  EXPECT_NEAR(norm(s.points[2] - Vec3d{-1, 10, 0}), 0, 1e-12);  // (0,1,0) -> (10,1,0) -> (-1,10,0)
  EXPECT_NEAR(r.bbox.hi.y, 11, 1e-12);
  EXPECT_TRUE(r.skipped_by_type.empty()) << "the 124s are used";
}

// A 4 m square patch on [0, 1]^2 trimmed by a natural outer loop and a circular hole.
ImportResult square_with_hole(int pref, bool with_uv, bool with_model) {
  IgesTextBuilder b;
  const int surf = b.add(128, test::square(0, 0, 4).params());
  const int outer_uv =
      b.add(126, test::polyline_126({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}}));
  const int outer = b.add(142, {"1", num(surf), num(outer_uv), "0", "1"});
  const int hole_uv = with_uv ? b.add(100, arc_100(0, 0.5, 0.5, 0.6, 0.5, 0.6, 0.5)) : 0;  // r 0.1
  const int hole_xyz = with_model ? b.add(100, arc_100(0, 2, 2, 3.6, 2, 3.6, 2)) : 0;      // r 1.6
  const int hole = b.add(142, {"1", num(surf), num(hole_uv), num(hole_xyz), num(pref)});
  b.add(144, {num(surf), "1", "1", num(outer), num(hole)});
  return read_iges(b.build(), "hole.igs");
}

// Largest |radius - r| of the loop around (0.5, 0.5), over points along its curves.
double radius_error(const TrimLoop& loop, double r) {
  double e = 0;
  for (const NurbsCurve& c : loop.curves_uv) {
    for (int k = 0; k <= 64; ++k) {
      const Vec3d uv = evaluate(c, c.t0 + (c.t1 - c.t0) * k / 64);
      e = std::max(e, std::fabs(std::hypot(uv.x - 0.5, uv.y - 0.5) - r));
    }
  }
  return e;
}

TEST(IgesTrims, TrimmedSurfaceWithAHoleProjectedFromModelSpace) {
  const ImportResult r = square_with_hole(2, false, true);
  ASSERT_EQ(r.patches.size(), 1u);
  const Patch& p = r.patches[0];
  ASSERT_EQ(p.loops.size(), 2u) << "a natural outer loop stays when there are holes";
  EXPECT_TRUE(p.loops[0].outer);
  EXPECT_FALSE(p.loops[1].outer);
  EXPECT_LT(radius_error(p.loops[1], 0.4), 1e-5);
  EXPECT_EQ(p.loops[1].curves_uv[0].degree, 1) << "projected curves are fitted polylines";
  EXPECT_EQ(r.diagnostics.count(Severity::kError), 0u);
}

TEST(IgesTrims, CurvePreferenceFlagIsHonoured) {
  // The two representations disagree on purpose (uv radius 0.1, model radius 1.6 m = 0.4).
  EXPECT_LT(radius_error(square_with_hole(1, true, true).patches[0].loops[1], 0.1), 1e-9);
  EXPECT_LT(radius_error(square_with_hole(2, true, true).patches[0].loops[1], 0.4), 1e-5);
  EXPECT_LT(radius_error(square_with_hole(0, true, false).patches[0].loops[1], 0.1), 1e-9);
}

TEST(IgesTrims, BoundedSurfaceWithModelSpaceBoundary) {
  IgesTextBuilder b;
  const int surf = b.add(128, test::square(0, 0, 4).params());
  const int circle = b.add(100, arc_100(0, 2, 2, 3.5, 2, 3.5, 2));
  const int bnd = b.add(141, {"0", "1", num(surf), "1", num(circle), "1", "0"});
  b.add(143, {"0", num(surf), "1", num(bnd)});
  const ImportResult r = read_iges(b.build(), "b143.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const Patch& p = r.patches[0];
  EXPECT_EQ(p.wrapping, Wrapping::kBounded);
  ASSERT_EQ(p.loops.size(), 1u);
  EXPECT_TRUE(p.loops[0].outer);
  EXPECT_LT(radius_error(p.loops[0], 0.375), 1e-5);
}

TEST(IgesTrims, EllipseConicWithATransformAsAnOuterLoop) {
  IgesTextBuilder b;
  const int surf = b.add(128, test::square(0, 0, 1).params());
  const int shift = b.add(124, {"1", "0", "0", "0.5", "0", "1", "0", "0.5", "0", "0", "1", "0"});
  // x^2 / 0.4^2 + y^2 / 0.2^2 = 1, full ellipse, moved to (0.5, 0.5).
  const int ell = b.add(104, {"6.25", "0", "25", "0", "0", "-1", "0", "0.4", "0", "0.4", "0"},
                        DirFields{1, shift});
  const int outer = b.add(142, {"1", num(surf), num(ell), "0", "1"});
  b.add(144, {num(surf), "1", "0", num(outer)});
  const ImportResult r = read_iges(b.build(), "ellipse.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  ASSERT_EQ(r.patches[0].loops.size(), 1u);
  for (const NurbsCurve& c : r.patches[0].loops[0].curves_uv) {
    for (int k = 0; k <= 32; ++k) {
      const Vec3d uv = evaluate(c, c.t0 + (c.t1 - c.t0) * k / 32);
      const double x = (uv.x - 0.5) / 0.4, y = (uv.y - 0.5) / 0.2;
      EXPECT_NEAR(x * x + y * y, 1, 1e-12);
    }
  }
}

TEST(IgesTrims, CopiousDataLoopAndBRepEdgesWithoutParameterCurves) {
  IgesTextBuilder b;
  const int surf = b.add(128, test::square(0, 0, 2).params());
  // Face loop from model-space edges only: a triangle (0,0)-(2,0)-(2,2) -> projected.
  const int e1 = b.add(110, test::line_110({0, 0, 0}, {2, 0, 0}));
  const int e2 =
      b.add(106, {"2", "3", "2.", "0.", "0.", "2.", "1.", "0.", "2.", "2.", "0."}, DirFields{12});
  const int e3 = b.add(110, test::line_110({0, 0, 0}, {2, 2, 0}));  // used reversed (OF = 0)
  const int verts =
      b.add(502, {"3", "0.", "0.", "0.", "2.", "0.", "0.", "2.", "2.", "0."}, DirFields{1});
  const int edges = b.add(504,
                          {"3", num(e1), num(verts), "1", num(verts), "2", num(e2), num(verts), "2",
                           num(verts), "3", num(e3), num(verts), "1", num(verts), "3"},
                          DirFields{1});
  const int loop = b.add(508,
                         {"3", "0", num(edges), "1", "1", "0", "0", num(edges), "2", "1", "0", "0",
                          num(edges), "3", "0", "0"},
                         DirFields{1});
  b.add(510, {num(surf), "1", "1", num(loop)}, DirFields{1});
  const ImportResult r = read_iges(b.build(), "edges.igs");
  ASSERT_EQ(r.patches.size(), 1u);
  const Patch& p = r.patches[0];
  ASSERT_EQ(p.loops.size(), 1u);
  ASSERT_EQ(p.loops[0].curves_uv.size(), 3u);
  const NurbsCurve& last = p.loops[0].curves_uv[2];
  EXPECT_NEAR(norm(last.points.front() - Vec3d{1, 1, 0}), 0, 1e-6)
      << "reversed edge starts at (2,2)";
  EXPECT_NEAR(norm(last.points.back() - Vec3d{0, 0, 0}), 0, 1e-6);
  EXPECT_TRUE(r.skipped_by_type.empty());
}

}  // namespace
}  // namespace hm
