// Whole generated hulls of every kind and patch count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "hull_checks.h"
#include "nurbs/generate_hull.h"
#include "support/test_support.h"
#include "tessellate/tessellate.h"

namespace hm {
namespace {

class GeneratedHullTest : public ::testing::TestWithParam<std::tuple<HullKind, int>> {};

TEST_P(GeneratedHullTest, MeetsToleranceAndTopology) {
  HullSpec spec;
  spec.kind = std::get<0>(GetParam());
  spec.patches = std::get<1>(GetParam());
  const GeneratedHull hull = generate_hull(spec);
  const Tessellation t = tessellate(hull.patches, {}, silent_progress());
  test::expect_good_tessellation(hull.patches, t, to_string(spec.kind));
  // The flat triangles underestimate the area by at most the chord error over the surface.
  double area = 0;
  for (std::size_t f = 0; f < t.mesh.face_count(); ++f) area += test::triangle_area(t.mesh, f);
  EXPECT_NEAR(area, hull.facts.surface_area, 1e-3 * hull.facts.surface_area);
}

INSTANTIATE_TEST_SUITE_P(Kinds, GeneratedHullTest,
                         ::testing::Combine(::testing::Values(HullKind::kWigley, HullKind::kChine,
                                                              HullKind::kRoundBilge),
                                            ::testing::Values(1, 10, 100, 1000)));

// Knot values of one direction where the surface is only C0 (multiplicity >= degree), strictly
// inside the domain: the knuckles of a one-patch hull.
std::vector<double> crease_knots(const std::vector<double>& knots, int degree, double lo,
                                 double hi) {
  std::vector<double> out;
  for (std::size_t k = 0; k < knots.size(); ++k) {
    const double t = knots[k];
    if (t <= lo || t >= hi || (k > 0 && knots[k - 1] == t)) continue;
    if (std::count(knots.begin(), knots.end(), t) >= degree) out.push_back(t);
  }
  return out;
}

// A knot line u = value (fixed_u) or v = value, running over [lo, hi] of the other parameter.
struct KnotLine {
  bool fixed_u;
  double value;
  double lo, hi;
  double along(const Vec2d& w) const { return fixed_u ? w.y : w.x; }
  double across(const Vec2d& w) const { return fixed_u ? w.x : w.y; }
  // Whether mesh vertex v lies on the line: it carries the knot parameter exactly, or (a vertex
  // merged into a point where the surface collapses, whose (u, v) names another preimage) its
  // position is that of the line at its other parameter, within tol (m).
  bool holds(const NurbsSurface& s, const SurfaceMesh& m, Index v, double tol) const {
    const Vec2d& w = m.vertex_uv[v];
    if (across(w) == value) return true;
    const Vec3d p = fixed_u ? evaluate(s, value, w.y) : evaluate(s, w.x, value);
    return norm(p - m.positions[v]) <= tol;
  }
};

double segment_distance(const Vec3d& q, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double l2 = squared_norm(ab);
  const double t = l2 > 0 ? std::clamp(dot(q - a, ab) / l2, 0.0, 1.0) : 0.0;
  return norm(q - (a + t * ab));
}

Vec3d face_normal(const SurfaceMesh& m, std::size_t f) {
  const Face& v = m.faces[f];
  return cross(m.positions[v[1]] - m.positions[v[0]], m.positions[v[2]] - m.positions[v[0]]);
}

double angle_deg(const Vec3d& a, const Vec3d& b) {
  return std::acos(std::clamp(dot(a, b) / (norm(a) * norm(b)), -1.0, 1.0)) * 180 / std::numbers::pi;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Default options (adaptive refinement on) on one-patch hulls, whose knuckles (chine, transom)
// are knots of full multiplicity inside the patch: every knot line stays an unbroken chain of
// mesh edges whose vertices keep the knot parameter exactly (a vertex created on such an edge
// must not be projected across the knot), no triangle straddles a knot line in (u, v), nothing
// folds, and the chord error stays within tolerance, for any thread count.
class OnePatchHullKnuckleTest : public ::testing::TestWithParam<HullKind> {};

TEST_P(OnePatchHullKnuckleTest, RefinedKnucklesStayOnTheirKnots) {
  HullSpec spec;
  spec.kind = GetParam();
  spec.patches = 1;
  const GeneratedHull hull = generate_hull(spec);
  ASSERT_EQ(hull.patches.size(), 1u);
  ASSERT_FALSE(hull.facts.knuckles.empty());
  const NurbsSurface& s = hull.patches[0].surface;
  std::vector<KnotLine> lines;
  for (double t : crease_knots(s.knots_u, s.degree_u, s.u0, s.u1))
    lines.push_back({true, t, s.v0, s.v1});
  for (double t : crease_knots(s.knots_v, s.degree_v, s.v0, s.v1))
    lines.push_back({false, t, s.u0, s.u1});
  ASSERT_FALSE(lines.empty());
  const Tessellation t =
      hm::test::with_threads(1, [&] { return tessellate(hull.patches, {}, silent_progress()); });
  const Tessellation two =
      hm::test::with_threads(8, [&] { return tessellate(hull.patches, {}, silent_progress()); });
  const std::string what = to_string(spec.kind);
  EXPECT_TRUE(same_bytes(t.mesh.positions, two.mesh.positions)) << what;
  EXPECT_TRUE(same_bytes(t.mesh.vertex_uv, two.mesh.vertex_uv)) << what;
  EXPECT_TRUE(same_bytes(t.mesh.faces, two.mesh.faces)) << what;
  EXPECT_TRUE(same_bytes(t.chord_error, two.chord_error)) << what;
  const SurfaceMesh& m = t.mesh;
  const double exact = 1e-9 * spec.length;
  EXPECT_LE(t.summary.max_chord_error, t.summary.chord_tolerance) << what;

  std::map<std::pair<Index, Index>, std::vector<std::size_t>> edges;  // edge -> its faces
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const Index a = m.faces[f][i], b = m.faces[f][(i + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  auto line_of = [&](Index a, Index b) -> const KnotLine* {
    for (const KnotLine& c : lines)
      if (c.holds(s, m, a, exact) && c.holds(s, m, b, exact)) return &c;
    return nullptr;
  };

  // Each knot line is covered end to end by mesh edges on it (the parameter lengths add up).
  std::vector<std::pair<Vec3d, Vec3d>> chain;
  for (const KnotLine& c : lines) {
    double covered = 0;
    for (const auto& [e, faces] : edges) {
      if (line_of(e.first, e.second) != &c) continue;
      covered += std::abs(c.along(m.vertex_uv[e.second]) - c.along(m.vertex_uv[e.first]));
      chain.push_back({m.positions[e.first], m.positions[e.second]});
    }
    EXPECT_NEAR(covered, c.hi - c.lo, 1e-9 * (c.hi - c.lo)) << what << " knot " << c.value;
  }
  // Those chains are the true knuckles: every sample of one lies within the chord tolerance of
  // them (a chain edge is a chord of the knuckle curve).
  for (const std::vector<Vec3d>& knuckle : hull.facts.knuckles) {
    for (const Vec3d& q : knuckle) {
      double best = INFINITY;
      for (const auto& [a, b] : chain) best = std::min(best, segment_distance(q, a, b));
      EXPECT_LE(best, t.summary.chord_tolerance) << what;
    }
  }

  // Each triangle lies in one C0 piece: no corner on either side of a knot line.
  std::size_t straddling = 0;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    for (const KnotLine& c : lines) {
      bool below = false, above = false;
      for (Index v : {m.faces[f][0], m.faces[f][1], m.faces[f][2]}) {
        if (c.holds(s, m, v, exact)) continue;
        below = below || c.across(m.vertex_uv[v]) < c.value;
        above = above || c.across(m.vertex_uv[v]) > c.value;
      }
      straddling += below && above;
    }
  }
  EXPECT_EQ(straddling, 0u) << what;

  // No fold: neighbouring faces within 120 degrees, and no sharp edge (a zigzag of the knuckle)
  // off the knot lines; across a knot line the mesh follows the dihedral angle of the NURBS.
  for (const auto& [e, faces] : edges) {
    if (faces.size() != 2) continue;
    const double a = angle_deg(face_normal(m, faces[0]), face_normal(m, faces[1]));
    const KnotLine* c = line_of(e.first, e.second);
    if (!c) {
      EXPECT_LT(a, 30.0) << what << " edge " << e.first << " " << e.second;
      continue;
    }
    const double mid = 0.5 * (c->along(m.vertex_uv[e.first]) + c->along(m.vertex_uv[e.second]));
    const double d = 1e-7 * (c->hi - c->lo);
    const Vec3d n0 = c->fixed_u ? normal(s, c->value - d, mid) : normal(s, mid, c->value - d);
    const Vec3d n1 = c->fixed_u ? normal(s, c->value + d, mid) : normal(s, mid, c->value + d);
    EXPECT_NEAR(a, angle_deg(n0, n1), 10.0) << what << " edge " << e.first << " " << e.second;
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, OnePatchHullKnuckleTest,
                         ::testing::Values(HullKind::kChine, HullKind::kRoundBilge));
}  // namespace
}  // namespace hm
