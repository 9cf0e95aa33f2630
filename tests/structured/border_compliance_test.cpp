// Boundary compliance of the structured mesher: every panel node on the mesh's open border or on a
// knuckle, where that border is an edge of a patch's parameter domain (a keel line, a transom's
// edge, a chine between two patches), lies on that NURBS edge curve, not on a chord of the fine
// mesh beside it. Measured against the exact curves, independently of the fine mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include "iges/read_iges.h"
#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "nurbs/nurbs_surface.h"
#include "query/hull_query.h"
#include "structured/structured.h"
#include "support/test_support.h"
#include "tessellate/tessellate.h"
#include "unstructured/cut_at_plane.h"
#include "unstructured/features.h"
#include "unstructured/merge.h"
#include "wetted_surface.h"

namespace hm {
namespace {

// Distance (m) from q to the nearest of the four edge curves of s's parameter domain: a sampled
// start, then golden-section search on the arc parameter.
double distance_to_domain_edges(const NurbsSurface& s, const Vec3d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (int e = 0; e < 4; ++e) {
    auto at = [&](double t) {
      switch (e) {
        case 0:
          return evaluate(s, s.u0 + t * (s.u1 - s.u0), s.v0);
        case 1:
          return evaluate(s, s.u0 + t * (s.u1 - s.u0), s.v1);
        case 2:
          return evaluate(s, s.u0, s.v0 + t * (s.v1 - s.v0));
        default:
          return evaluate(s, s.u1, s.v0 + t * (s.v1 - s.v0));
      }
    };
    auto d = [&](double t) { return norm(at(t) - q); };
    constexpr int kSamples = 400;
    int k = 0;
    double dk = d(0);
    for (int i = 1; i <= kSamples; ++i) {
      const double di = d(double(i) / kSamples);
      if (di < dk) {
        dk = di;
        k = i;
      }
    }
    double a = std::max(0, k - 1) / double(kSamples),
           b = std::min(kSamples, k + 1) / double(kSamples);
    const double g = (std::sqrt(5.0) - 1) / 2;
    double c = b - g * (b - a), dd = a + g * (b - a);
    double fc = d(c), fd = d(dd);
    for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
      if (fc < fd) {
        b = dd;
        dd = c;
        fd = fc;
        c = b - g * (b - a);
        fc = d(c);
      } else {
        a = c;
        c = dd;
        fc = fd;
        dd = a + g * (b - a);
        fd = d(dd);
      }
    }
    best = std::min({best, dk, fc, fd});
  }
  return best;
}

using Prepared = test::WettedSurface;

// As `hullmesh structured` prepares a hull: about 20 fine triangles per panel, merged, cut at the
// waterline z (NaN: not cut), features and query.
std::unique_ptr<Prepared> prepare(std::vector<Patch> patches, double waterline_z,
                                  std::size_t panels) {
  const double edge = edge_length_for_triangles(patches, 20 * panels);
  return test::prepare_surface(std::move(patches), waterline_z, edge);
}

struct Compliance {
  std::size_t nodes = 0;  // border and knuckle nodes near a patch's edge curve
  double worst = 0;       // their largest distance from it, m
};

// Nodes on the panel mesh's free edges (but for edges along the waterline z = waterline_z, a cut
// line on no patch edge) and on its knuckle edges, whose nearest patch edge curve is within `near`
// (m): their largest distance from that curve.
Compliance measure(const Prepared& w, const StructuredMesh& m, double waterline_z, double near) {
  const SurfaceMesh& mesh = m.mesh;
  std::vector<char> pick(mesh.vertex_count(), 0);
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  const double on_plane = 1e-9 * w.query->length_scale();
  auto at_waterline = [&](Index v) {
    return std::abs(mesh.positions[v].z - waterline_z) <= on_plane;
  };
  for (const BoundaryLoop& loop : adj.boundary_loops) {
    const std::size_t n = loop.vertices.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Index a = loop.vertices[i], b = loop.vertices[(i + 1) % n];
      if (at_waterline(a) && at_waterline(b)) continue;
      pick[a] = pick[b] = 1;
    }
  }
  for (const auto& e : m.knuckle_edges) pick[e[0]] = pick[e[1]] = 1;
  Compliance c;
  for (Index v = 0; v < mesh.vertex_count(); ++v) {
    if (!pick[v]) continue;
    double d = std::numeric_limits<double>::infinity();
    for (const Patch& p : w.patches)
      d = std::min(d, distance_to_domain_edges(p.surface, mesh.positions[v]));
    if (d > near) continue;
    ++c.nodes;
    c.worst = std::max(c.worst, d);
  }
  return c;
}

TEST(BorderCompliance, ChineHullBorderAndKnuckleNodesLieOnTheEdgeCurves) {
  HullSpec spec;
  spec.kind = HullKind::kChine;
  spec.patches = 24;
  const auto w = prepare(generate_hull(spec).patches, spec.draft, 1200);
  StructuredOptions o;
  o.target_panels = 1200;
  const StructuredMesh m =
      mesh_structured(w->patches, w->cut.mesh, w->adj, *w->query, w->features, o);
  const double L = w->query->length_scale();
  const Compliance c = measure(*w, m, spec.draft, 1e-4 * L);
  EXPECT_GT(c.nodes, 100u);
  EXPECT_LT(c.worst, 1e-9 * L) << c.nodes << " nodes";
}

// The whole file, up to the deck: its transom's edge (a domain edge of the main hull patch, x =
// 3.05 m, above z = 0) is an open border, as are the keel and stem on y = 0 and the deck edge.
TEST(BorderCompliance, Dtmb5415TransomAndKeelNodesLieOnTheEdgeCurves) {
  HM_REQUIRE_SHARED_HULL(path, "dtmb5415.iges");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto w = prepare(read_iges_file(path.string()).patches, nan, 2000);
  StructuredOptions o;
  o.target_panels = 2000;
  const StructuredMesh m =
      mesh_structured(w->patches, w->cut.mesh, w->adj, *w->query, w->features, o);
  const double L = w->query->length_scale();
  const Compliance c = measure(*w, m, nan, 1e-4 * L);
  EXPECT_GT(c.nodes, 50u);
  EXPECT_LT(c.worst, 1e-9 * L) << c.nodes << " nodes";
}

}  // namespace
}  // namespace hm
