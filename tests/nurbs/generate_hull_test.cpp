// The parametric hull generator: exact Wigley geometry and hydrostatics, exact patch counts,
// patches that share their borders exactly, knuckles on borders, outward normals, errors.
#include "nurbs/generate_hull.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/error.h"
#include "nurbs/gauss_legendre.h"
#include "nurbs/hull_checks.h"

namespace hm {
namespace {

using test::kKinds;
using test::spec_of;

double wigley_y(const HullSpec& s, double x, double z) {
  const double xi = 2.0 * (x - 0.5 * s.length) / s.length;
  const double zeta = (z - s.draft) / s.draft;
  return 0.5 * s.beam * (1 - xi * xi) * (1 - zeta * zeta);
}

// Integral over the patches of y n_y dA below z = waterline (n the outward normal, so a
// reversed patch counts with -su x sv): the enclosed volume by the divergence theorem. Gauss
// points above the waterline are dropped (exact when no patch crosses it).
double volume_by_patches(const std::vector<Patch>& patches, double waterline, int order) {
  const GaussRule g = gauss_legendre_01(order);
  double v = 0;
  for (const Patch& p : patches) {
    const NurbsSurface& s = p.surface;
    const std::vector<double> bu = span_breaks_u(s), bv = span_breaks_v(s);
    for (std::size_t i = 0; i + 1 < bu.size(); ++i) {
      for (std::size_t j = 0; j + 1 < bv.size(); ++j) {
        const double hu = bu[i + 1] - bu[i], hv = bv[j + 1] - bv[j];
        for (int a = 0; a < order; ++a) {
          for (int b = 0; b < order; ++b) {
            const SurfaceDerivs d =
                evaluate_derivs(s, bu[i] + hu * g.nodes[a], bv[j] + hv * g.nodes[b], 1);
            if (d.p.z > waterline) continue;
            const double ny = cross(d.su, d.sv).y * (p.reversed ? -1.0 : 1.0);
            v += hu * hv * g.weights[a] * g.weights[b] * d.p.y * ny;
          }
        }
      }
    }
  }
  return v;
}

struct Wetted {
  double volume = 0, area = 0;
};

// Volume (integral of y n_y) and area of the patches below the waterline, for patches whose z
// does not increase with v (as generated): per Gauss node in u, the waterline crossing in v by
// bisection, then Gauss over the knot spans below it. Every span is cut into 4 x 4 cells.
Wetted wetted_by_patches(const std::vector<Patch>& patches, double waterline) {
  const GaussRule g = gauss_legendre_01(6);
  Wetted w;
  const auto cells = [](std::vector<double> t, double lo) {
    std::vector<double> out{lo};
    for (std::size_t k = 0; k + 1 < t.size(); ++k) {
      for (int m = 1; m <= 4; ++m) {
        const double x = t[k] + (t[k + 1] - t[k]) * m / 4;
        if (x > lo) out.push_back(x);
      }
    }
    return out;
  };
  for (const Patch& p : patches) {
    const NurbsSurface& s = p.surface;
    const std::vector<double> bu = cells(span_breaks_u(s), s.u0);
    for (std::size_t i = 0; i + 1 < bu.size(); ++i) {
      for (std::size_t a = 0; a < g.nodes.size(); ++a) {
        const double hu = bu[i + 1] - bu[i], u = bu[i] + hu * g.nodes[a];
        if (evaluate(s, u, s.v1).z >= waterline) continue;
        double start = s.v0;
        if (evaluate(s, u, s.v0).z > waterline) {
          double lo = s.v0, hi = s.v1;
          for (int it = 0; it < 60; ++it) {
            const double mid = 0.5 * (lo + hi);
            (evaluate(s, u, mid).z > waterline ? lo : hi) = mid;
          }
          start = 0.5 * (lo + hi);
        }
        const std::vector<double> bv = cells(span_breaks_v(s), start);
        for (std::size_t j = 0; j + 1 < bv.size(); ++j) {
          for (std::size_t b = 0; b < g.nodes.size(); ++b) {
            const double hv = bv[j + 1] - bv[j];
            const SurfaceDerivs d = evaluate_derivs(s, u, bv[j] + hv * g.nodes[b], 1);
            const Vec3d n = cross(d.su, d.sv) * (p.reversed ? -1.0 : 1.0);
            const double weight = hu * hv * g.weights[a] * g.weights[b];
            w.volume += weight * d.p.y * n.y;
            w.area += weight * norm(n);
          }
        }
      }
    }
  }
  return w;
}

TEST(GenerateHull, WigleyPointsSatisfyTheFormula) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int n : {1, 48}) {
    for (bool full : {false, true}) {
      const HullSpec spec = spec_of(HullKind::kWigley, full ? n + 1 : n, full);
      const GeneratedHull hull = generate_hull(spec);
      for (const Patch& p : hull.patches) {
        const NurbsSurface& s = p.surface;
        EXPECT_EQ(s.degree_u, 2);
        EXPECT_EQ(s.degree_v, 2);
        for (int k = 0; k < 20; ++k) {
          const Vec3d q =
              evaluate(s, s.u0 + unit(rng) * (s.u1 - s.u0), s.v0 + unit(rng) * (s.v1 - s.v0));
          EXPECT_NEAR(std::abs(q.y), wigley_y(spec, q.x, q.z), 1e-12) << p.name;
          EXPECT_GE(q.z, -1e-12);
          EXPECT_LE(q.z, spec.depth + 1e-12);
        }
      }
    }
  }
}

TEST(GenerateHull, WigleyVolumeByQuadratureOfPatchesIsClosedForm) {
  HullSpec spec = spec_of(HullKind::kWigley, 7);
  spec.depth = spec.draft;  // the classic Wigley hull: its depth is the draft
  const double exact = 4.0 / 9.0 * spec.length * spec.beam * spec.draft;
  const GeneratedHull half = generate_hull(spec);
  EXPECT_NEAR(2.0 * volume_by_patches(half.patches, spec.draft, 4), exact, 1e-10 * exact);
  EXPECT_DOUBLE_EQ(half.facts.displacement_volume, exact);

  spec.full_hull = true;
  spec.patches = 48;
  const GeneratedHull full = generate_hull(spec);
  EXPECT_NEAR(volume_by_patches(full.patches, spec.draft, 4), exact, 1e-10 * exact);
  // The patches are the wetted surface exactly, so their area is the wetted area.
  EXPECT_NEAR(full.facts.surface_area, full.facts.wetted_area, 1e-8 * full.facts.wetted_area);
  EXPECT_NEAR(half.facts.surface_area, 0.5 * full.facts.wetted_area, 1e-8 * full.facts.wetted_area);
}

TEST(GenerateHull, WigleyWettedAreaMatchesIndependentQuadrature) {
  // Composite midpoint rule on the formula, coarse but independent of the generator's Gauss.
  const HullSpec spec = spec_of(HullKind::kWigley, 1);
  const int n = 800;
  double area = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double x = spec.length * (i + 0.5) / n, z = spec.draft * (j + 0.5) / n;
      const double h = 1e-6;
      const double yx = (wigley_y(spec, x + h, z) - wigley_y(spec, x - h, z)) / (2 * h);
      const double yz = (wigley_y(spec, x, z + h) - wigley_y(spec, x, z - h)) / (2 * h);
      area += std::sqrt(1 + yx * yx + yz * yz);
    }
  }
  area *= 2.0 * spec.length * spec.draft / (n * n);
  EXPECT_NEAR(generate_hull(spec).facts.wetted_area, area, 1e-6 * area);
}

// Each sample point on a patch side lies on another patch's side (or on a free edge), and the
// count is exact.
void expect_borders_shared(const HullSpec& spec) {
  const GeneratedHull hull = generate_hull(spec);
  ASSERT_EQ(hull.patches.size(), static_cast<std::size_t>(spec.patches));
  const test::EdgeIndex index(hull.patches);
  const double tol = 1e-9 * spec.length;
  int checked = 0;
  for (std::size_t k = 0; k < hull.patches.size(); ++k) {
    const NurbsSurface& s = hull.patches[k].surface;
    EXPECT_NO_THROW(validate_surface(s));
    EXPECT_EQ(hull.patches[k].wrapping, Wrapping::kGenerated);
    EXPECT_EQ(hull.patches[k].de, 0);
    EXPECT_FALSE(hull.patches[k].name.empty());
    for (int side = 0; side < 4; ++side) {
      if (test::edge_length(s, side) < tol) continue;  // collapsed to a point
      // Two points per side, one for the large counts (time).
      const std::vector<double> ts =
          spec.patches >= 1000 ? std::vector<double>{0.5} : std::vector<double>{1.0 / 3, 2.0 / 3};
      for (double t : ts) {
        const Vec3d q = test::edge_point(s, side, t);
        if (test::on_free_edge(q, spec, tol)) continue;
        ++checked;
        EXPECT_LT(index.distance(q, k, tol), tol)
            << to_string(spec.kind) << " " << spec.patches << " patch " << hull.patches[k].name
            << " side " << side << " t " << t;
      }
    }
  }
  if (spec.patches > 1) {
    EXPECT_GT(checked, 0);
  }
}

TEST(GenerateHull, EveryKindGivesExactCountsWithSharedBorders) {
  for (HullKind kind : kKinds) {
    for (int n : {1, 7, 48, 1000}) expect_borders_shared(spec_of(kind, n));
    for (int n : {2, 7, 48, 1000}) expect_borders_shared(spec_of(kind, n, true));
  }
}

TEST(GenerateHull, SmallCountsBelowThePartCount) {
  for (HullKind kind : kKinds) {
    for (int n : {1, 2, 3, 4, 5}) expect_borders_shared(spec_of(kind, n));
    for (int n : {3, 5}) expect_borders_shared(spec_of(kind, n, true));
  }
}

TEST(GenerateHull, OtherProportionsKeepSharedBordersAndFacts) {
  for (HullKind kind : kKinds) {
    HullSpec spec = spec_of(kind, 48, true);
    spec.length = 30;
    spec.beam = 9;
    spec.depth = 4;
    spec.draft = 2.5;
    expect_borders_shared(spec);
    const GeneratedHull hull = generate_hull(spec);
    const Wetted w = wetted_by_patches(hull.patches, spec.draft);
    EXPECT_NEAR(w.volume, hull.facts.displacement_volume, 1e-4 * w.volume) << to_string(kind);
  }
}

TEST(GenerateHull, NormalsPointOutOfTheHull) {
  for (HullKind kind : kKinds) {
    for (bool full : {false, true}) {
      const HullSpec spec = spec_of(kind, 48, full);
      const Vec3d inside{0.5 * spec.length, 0.0, 0.5 * spec.draft};
      for (const Patch& p : generate_hull(spec).patches) {
        const NurbsSurface& s = p.surface;
        const double u = 0.5 * (s.u0 + s.u1), v = 0.5 * (s.v0 + s.v1);
        const Vec3d n = normal(s, u, v) * (p.reversed ? -1.0 : 1.0);
        EXPECT_GT(dot(n, evaluate(s, u, v) - inside), 0) << to_string(kind) << " " << p.name;
      }
    }
  }
}

TEST(GenerateHull, SurfaceAreaDoesNotDependOnTheSplit) {
  for (HullKind kind : kKinds) {
    const double one = generate_hull(spec_of(kind, 1)).facts.surface_area;
    EXPECT_GT(one, 0);
    for (int n : {7, 48, 1000}) {
      EXPECT_NEAR(generate_hull(spec_of(kind, n)).facts.surface_area, one, 1e-9 * one)
          << to_string(kind) << " " << n;
    }
    const double full = generate_hull(spec_of(kind, 48, true)).facts.surface_area;
    EXPECT_NEAR(full, 2 * one, 2e-9 * one) << to_string(kind);
  }
}

TEST(GenerateHull, FactsAgreeWithQuadratureOfThePatches) {
  for (HullKind kind : kKinds) {
    const HullSpec spec = spec_of(kind, 48, true);
    const GeneratedHull hull = generate_hull(spec);
    const Wetted w = wetted_by_patches(hull.patches, spec.draft);
    // The round-bilge patches interpolate the defining shape between its sections; the Wigley
    // and chine patches are it.
    const double tol = kind == HullKind::kRoundBilge ? 1e-4 : 1e-8;
    EXPECT_NEAR(w.volume, hull.facts.displacement_volume, tol * w.volume) << to_string(kind);
    EXPECT_NEAR(w.area, hull.facts.wetted_area, tol * w.area) << to_string(kind);
    EXPECT_LT(hull.facts.wetted_area, hull.facts.surface_area);
    const double block = spec.length * spec.beam * spec.draft;
    EXPECT_GT(hull.facts.displacement_volume, 0.3 * block);
    EXPECT_LT(hull.facts.displacement_volume, 0.9 * block);
  }
}

TEST(GenerateHull, KnucklesLieOnPatchBordersAndOnTheSurface) {
  for (HullKind kind : {HullKind::kRoundBilge, HullKind::kChine}) {
    for (int n : {7, 48}) {
      const HullSpec spec = spec_of(kind, n, n == 48);
      const GeneratedHull hull = generate_hull(spec);
      ASSERT_FALSE(hull.facts.knuckles.empty());
      const test::EdgeIndex index(hull.patches);
      const double tol = 1e-9 * spec.length;
      for (const auto& line : hull.facts.knuckles) {
        ASSERT_GE(line.size(), 50u);
        for (std::size_t k = 0; k < line.size(); k += 7) {
          EXPECT_LT(index.distance(line[k], hull.patches.size(), tol), tol)
              << to_string(kind) << " " << n << " point " << k;
        }
      }
    }
  }
  EXPECT_TRUE(generate_hull(spec_of(HullKind::kWigley, 7)).facts.knuckles.empty());
}

// Interior knot values of full multiplicity (knuckle lines inside one patch).
std::vector<double> knuckle_knots(const std::vector<double>& knots, int degree) {
  std::vector<double> out;
  for (std::size_t k = degree + 1; k + degree + 1 < knots.size();) {
    std::size_t m = 1;
    while (k + m < knots.size() && knots[k + m] == knots[k]) ++m;
    if (static_cast<int>(m) >= degree && knots[k] > knots.front() && knots[k] < knots.back()) {
      out.push_back(knots[k]);
    }
    k += m;
  }
  return out;
}

TEST(GenerateHull, OnePatchHoldsTheKnucklesAsRepeatedKnots) {
  for (HullKind kind : {HullKind::kRoundBilge, HullKind::kChine}) {
    const GeneratedHull hull = generate_hull(spec_of(kind, 1));
    ASSERT_EQ(hull.patches.size(), 1u);
    const NurbsSurface& s = hull.patches[0].surface;
    const std::vector<double> ku = knuckle_knots(s.knots_u, s.degree_u);
    const std::vector<double> kv = knuckle_knots(s.knots_v, s.degree_v);
    EXPECT_EQ(ku.size(), 1u) << to_string(kind);  // the transom edge
    EXPECT_EQ(kv.size(), kind == HullKind::kChine ? 1u : 0u) << to_string(kind);  // the chine
    // Every knuckle point lies on one of those knot lines of the patch.
    for (const auto& line : hull.facts.knuckles) {
      for (std::size_t k = 0; k < line.size(); k += 5) {
        double d = 1e300;
        for (double u : ku) d = std::min(d, test::line_distance(s, true, u, line[k]));
        for (double v : kv) d = std::min(d, test::line_distance(s, false, v, line[k]));
        EXPECT_LT(d, 1e-9 * 100) << to_string(kind) << " point " << k;
      }
    }
  }
}

TEST(GenerateHull, IsDeterministic) {
  for (HullKind kind : kKinds) {
    const GeneratedHull a = generate_hull(spec_of(kind, 48, true));
    const GeneratedHull b = generate_hull(spec_of(kind, 48, true));
    ASSERT_EQ(a.patches.size(), b.patches.size());
    for (std::size_t k = 0; k < a.patches.size(); ++k) {
      const auto& pa = a.patches[k].surface.points;
      const auto& pb = b.patches[k].surface.points;
      ASSERT_EQ(pa.size(), pb.size());
      EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(Vec3d)), 0);
      EXPECT_EQ(a.patches[k].name, b.patches[k].name);
    }
    EXPECT_EQ(a.facts.displacement_volume, b.facts.displacement_volume);
  }
}

// The speed of this is bench_nurbs' BM_GenerateHull; here only that 1000 patches come out.
TEST(GenerateHull, ThousandPatchesOfEveryKind) {
  for (HullKind kind : kKinds) {
    const GeneratedHull hull = generate_hull(spec_of(kind, 1000, true));
    EXPECT_EQ(hull.patches.size(), 1000u) << to_string(kind);
  }
}

TEST(GenerateHull, RejectsBadSettings) {
  EXPECT_THROW(generate_hull(spec_of(HullKind::kWigley, 0)), UsageError);
  EXPECT_THROW(generate_hull(spec_of(HullKind::kChine, 1001)), UsageError);
  EXPECT_THROW(generate_hull(spec_of(HullKind::kChine, 1, true)), UsageError);
  HullSpec s = spec_of(HullKind::kRoundBilge, 4);
  s.beam = -1;
  EXPECT_THROW(generate_hull(s), UsageError);
  s = spec_of(HullKind::kRoundBilge, 4);
  s.draft = s.depth + 1;
  EXPECT_THROW(generate_hull(s), UsageError);
  s = spec_of(HullKind::kWigley, 4);
  s.depth = 2.5 * s.draft;
  EXPECT_THROW(generate_hull(s), UsageError);
  s = spec_of(HullKind::kWigley, 4);
  s.defects.overlap = 0.9;
  EXPECT_THROW(generate_hull(s), UsageError);
  s.defects.overlap = 0;
  s.defects.gap = -1;
  EXPECT_THROW(generate_hull(s), UsageError);
  s = spec_of(HullKind::kChine, 4);
  s.beam = 10 * s.depth;
  EXPECT_THROW(generate_hull(s), UsageError);
  s.kind = HullKind::kRoundBilge;
  EXPECT_THROW(generate_hull(s), UsageError);
}

TEST(GenerateHull, KindNamesRoundTrip) {
  for (HullKind kind : kKinds) {
    HullKind parsed = HullKind::kWigley;
    ASSERT_TRUE(parse_hull_kind(to_string(kind), parsed));
    EXPECT_EQ(parsed, kind);
  }
  HullKind k;
  EXPECT_FALSE(parse_hull_kind("catamaran", k));
}

}  // namespace
}  // namespace hm
