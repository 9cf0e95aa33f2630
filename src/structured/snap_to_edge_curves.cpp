// Boundary compliance on the exact curves. A panel node on the mesh's open border or on a knuckle
// was placed on the fine surface's boundary or knuckle polyline: on a chord of it, off the NURBS
// curve by up to the chord tolerance. Where that polyline runs along an edge of a patch's
// parameter domain (a keel or centre-plane line, a transom's edge, a chine between two patches,
// a knuckle at a repeated knot that a patch border follows), the node moves onto that edge curve:
// a row node at the curve's crossing with its station plane, a node on the waterline at the
// curve's crossing with the waterplane, any other node at the curve's point nearest it.
//
// collect (the border and knuckle nodes, the fine feature segments on an edge curve) -> match
// (each node's nearest such segment) -> solve (Newton on the curve parameter, per node, in
// parallel; each node writes only its own slots) -> apply.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "core/parallel.h"
#include "nurbs/nurbs_surface.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// A domain edge of one patch: u fixed (u_fixed) at `fixed`, or v fixed.
struct EdgeCurve {
  PatchId patch = kInvalid;
  bool u_fixed = true;
  double fixed = 0;
};

// One fine feature segment that lies on a domain edge: its ends' positions and their parameters
// along the edge curve.
struct CurveSegment {
  Vec3d a, b;
  EdgeCurve curve;
  double ta = 0, tb = 0;
  double x_lo = 0, x_hi = 0;
};

// The domain edges (u0, u1, v0, v1) that (u, v) lies on, as bits 1, 2, 4, 8. Within 1e-6 of the
// domain: a trim loop drawn along a domain edge runs a little inside it (DTMB 5415's keel, 1e-9
// of the domain in), and that edge is the border the designer meant.
unsigned edges_of(const NurbsSurface& s, const Vec2d& uv) {
  const double eu = 1e-6 * (s.u1 - s.u0), ev = 1e-6 * (s.v1 - s.v0);
  unsigned bits = 0;
  if (std::abs(uv.x - s.u0) <= eu) bits |= 1;
  if (std::abs(uv.x - s.u1) <= eu) bits |= 2;
  if (std::abs(uv.y - s.v0) <= ev) bits |= 4;
  if (std::abs(uv.y - s.v1) <= ev) bits |= 8;
  return bits;
}

// Position and derivative along the edge curve at parameter t.
void curve_at(const NurbsSurface& s, const EdgeCurve& c, double t, Vec3d& p, Vec3d& dp) {
  const SurfaceDerivs d =
      c.u_fixed ? evaluate_derivs(s, c.fixed, t, 1) : evaluate_derivs(s, t, c.fixed, 1);
  p = d.p;
  dp = c.u_fixed ? d.sv : d.su;
}

// What a node must keep besides lying on the curve.
enum class Keep : std::uint8_t { kNearest, kStation, kWaterline };

// Newton on the curve parameter, from t0, kept inside [lo, hi]: nearest point to q (kNearest),
// or the crossing with x = q.x (kStation) or with the plane of q's height along `up` (kWaterline).
// Empty when it does not converge to `tol` (m) in 30 steps.
std::optional<double> solve(const NurbsSurface& s, const EdgeCurve& c, const Vec3d& q, Keep keep,
                            const Vec3d& up, double t0, double lo, double hi, double tol) {
  double t = std::clamp(t0, lo, hi);
  for (int it = 0; it < 30; ++it) {
    Vec3d p, dp;
    curve_at(s, c, t, p, dp);
    double f = 0, df = 0;
    if (keep == Keep::kNearest) {
      // Gauss-Newton on |p - q|^2: step to the foot of the tangent.
      f = dot(p - q, dp);
      df = squared_norm(dp);
      if (std::abs(f) <= tol * std::sqrt(df)) return t;
    } else {
      f = keep == Keep::kStation ? p.x - q.x : dot(up, p) - dot(up, q);
      df = keep == Keep::kStation ? dp.x : dot(up, dp);
      if (std::abs(f) <= tol) return t;
    }
    if (!(std::abs(df) > 0)) return std::nullopt;
    const double next = std::clamp(t - f / df, lo, hi);
    if (next == t) {
      // Held at the window's end. For the nearest point that end is the answer (a patch corner);
      // a plane crossing lies outside the window.
      if (keep == Keep::kNearest) return t;
      return std::nullopt;
    }
    t = next;
  }
  return std::nullopt;
}

// The fine segment va-vb when it runs along a domain edge of one end's patch: the other end lies
// on that edge curve too, within `on_curve` (m; the merge moved welded border vertices by up to
// half a closed gap). Ends on two patches (a seam meeting a keel) are matched through the edge
// curve of either.
std::optional<CurveSegment> segment_on_edge(std::span<const Patch> patches,
                                            const SurfaceMesh& surface, Index va, Index vb,
                                            double on_curve, double tol) {
  if (surface.vertex_patch.empty() || surface.vertex_uv.empty()) return std::nullopt;
  for (const bool from_a : {true, false}) {
    const Index ve = from_a ? va : vb, vo = from_a ? vb : va;
    const PatchId p = surface.vertex_patch[ve];
    if (p == kInvalid || p >= patches.size()) continue;
    const NurbsSurface& s = patches[p].surface;
    const Vec2d ue = surface.vertex_uv[ve];
    const unsigned bits = edges_of(s, ue);
    for (const unsigned bit : {1u, 2u, 4u, 8u}) {
      if (!(bits & bit)) continue;
      EdgeCurve c;
      c.patch = p;
      c.u_fixed = bit <= 2;
      c.fixed = bit == 1 ? s.u0 : bit == 2 ? s.u1 : bit == 4 ? s.v0 : s.v1;
      const double te = c.u_fixed ? ue.y : ue.x;
      double to = 0;
      if (surface.vertex_patch[vo] == p) {
        const Vec2d uo = surface.vertex_uv[vo];
        if (!(edges_of(s, uo) & bit)) continue;
        to = c.u_fixed ? uo.y : uo.x;
      } else {
        const double lo = c.u_fixed ? s.v0 : s.u0, hi = c.u_fixed ? s.v1 : s.u1;
        const std::optional<double> t =
            solve(s, c, surface.positions[vo], Keep::kNearest, Vec3d{0, 0, 1}, te, lo, hi, tol);
        if (!t) continue;
        Vec3d q, dq;
        curve_at(s, c, *t, q, dq);
        if (!(norm(q - surface.positions[vo]) <= on_curve)) continue;
        to = *t;
      }
      if (to == te) continue;  // both ends at one point of the curve: no direction along it
      CurveSegment seg;
      seg.a = surface.positions[va];
      seg.b = surface.positions[vb];
      seg.curve = c;
      seg.ta = from_a ? te : to;
      seg.tb = from_a ? to : te;
      seg.x_lo = std::min(seg.a.x, seg.b.x);
      seg.x_hi = std::max(seg.a.x, seg.b.x);
      return seg;
    }
  }
  return std::nullopt;
}

}  // namespace

std::size_t snap_to_edge_curves(std::span<const Patch> patches, const SurfaceMesh& surface,
                                const FeatureSet& features, std::span<const Row> rows,
                                std::span<const NodeSlot> slots,
                                std::span<const std::array<Index, 2>> knuckle_edges,
                                double length_scale, const Vec3d& up, const Metric& metric,
                                SurfaceMesh& mesh) {
  // collect: the fine feature segments on a domain edge (waterline runs are cut lines, on no
  // patch edge), sorted by their low x for the slab search below.
  std::vector<CurveSegment> segs;
  double waterline_z = std::numeric_limits<double>::quiet_NaN();
  auto add_line = [&](const FeatureLine& l) {
    const std::size_t n = l.vertices.size();
    for (std::size_t i = 0; i + 1 < n + (l.closed ? 1 : 0); ++i) {
      if (auto s = segment_on_edge(patches, surface, l.vertices[i], l.vertices[(i + 1) % n],
                                   1e-4 * length_scale, 1e-12 * length_scale))
        segs.push_back(*s);
    }
  };
  // The waterline's height along `up`: the median of its runs' vertices (the cut put almost all of
  // them on the plane exactly; a run's end at the stem may lie a little off it).
  std::vector<double> waterline_zs;
  for (const BoundaryRun& r : features.boundaries) {
    if (r.kind == BoundaryKind::kWaterline) {
      for (Index v : r.vertices) waterline_zs.push_back(dot(up, surface.positions[v]));
      continue;
    }
    add_line(r);
  }
  if (!waterline_zs.empty()) {
    auto mid = waterline_zs.begin() + static_cast<std::ptrdiff_t>(waterline_zs.size() / 2);
    std::nth_element(waterline_zs.begin(), mid, waterline_zs.end());
    waterline_z = *mid;
  }
  for (const FeatureLine& k : features.knuckles) add_line(k);
  if (segs.empty()) return 0;
  std::stable_sort(segs.begin(), segs.end(),
                   [](const CurveSegment& a, const CurveSegment& b) { return a.x_lo < b.x_lo; });
  double longest = 0;
  for (const CurveSegment& s : segs) longest = std::max(longest, s.x_hi - s.x_lo);

  // The border and knuckle nodes of the panel mesh.
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  std::vector<std::uint8_t> pick(mesh.vertex_count(), 0);
  for (const BoundaryLoop& loop : adj.boundary_loops)
    for (Index v : loop.vertices) pick[v] = 1;
  for (const auto& e : knuckle_edges) pick[e[0]] = pick[e[1]] = 1;

  // A node is matched to a segment within `reach` of it: far more than the chord error that put
  // it off the curve, far less than a panel.
  const double reach = 0.05 * std::min({metric.size.x, metric.size.y, metric.size.z});
  const double tol = 1e-12 * length_scale;
  const double on_plane = 1e-9 * length_scale;
  std::vector<std::uint8_t> moved(mesh.vertex_count(), 0);
  parallel_for(0, mesh.vertex_count(), [&](std::size_t v) {
    if (!pick[v]) return;
    const Vec3d q = mesh.positions[v];
    // match: the nearest segment in the slab of x that can reach q.
    const auto first = std::lower_bound(segs.begin(), segs.end(), q.x - reach - longest,
                                        [](const CurveSegment& s, double x) { return s.x_lo < x; });
    const CurveSegment* best = nullptr;
    double best_d = reach, best_f = 0;
    for (auto it = first; it != segs.end() && it->x_lo <= q.x + reach; ++it) {
      if (it->x_hi < q.x - reach) continue;
      const Vec3d d = it->b - it->a;
      const double dd = squared_norm(d);
      const double f = dd > 0 ? std::clamp(dot(q - it->a, d) / dd, 0.0, 1.0) : 0.0;
      const double dist = norm(it->a + d * f - q);
      if (dist < best_d) {
        best_d = dist;
        best = &*it;
        best_f = f;
      }
    }
    if (best == nullptr) return;
    // solve: what the node keeps. A node on the waterline keeps the waterplane; a row node keeps
    // its station plane (a border row's end, a breakpoint on a knuckle). A row's end on the
    // waterline keeps the waterplane: a cut station planned at a patch border's fine vertices
    // may miss the exact border by the chord error, and the corner of the waterline and the
    // border is the exact place.
    const bool on_station = v < slots.size() && slots[v].row != kInvalid &&
                            std::abs(q.x - rows[slots[v].row].x) <= on_plane;
    const bool on_waterline =
        std::isfinite(waterline_z) && std::abs(dot(up, q) - waterline_z) <= on_plane;
    const Keep keep = on_waterline ? Keep::kWaterline
                      : on_station ? Keep::kStation
                                   : Keep::kNearest;
    const NurbsSurface& s = patches[best->curve.patch].surface;
    // The window: the segment's parameter span and one more on either side, inside the domain.
    const double span = std::abs(best->tb - best->ta);
    const double dlo = best->curve.u_fixed ? s.v0 : s.u0, dhi = best->curve.u_fixed ? s.v1 : s.u1;
    const double lo = std::max(dlo, std::min(best->ta, best->tb) - span);
    const double hi = std::min(dhi, std::max(best->ta, best->tb) + span);
    const double t0 = best->ta + (best->tb - best->ta) * best_f;
    std::optional<double> t = solve(s, best->curve, q, keep, up, t0, lo, hi, tol);
    // No crossing of the plane inside the window: a node at a patch corner, where the curve
    // ends before the plane. The nearest point of the curve keeps it within the chord error.
    if (!t && keep == Keep::kStation)
      t = solve(s, best->curve, q, Keep::kNearest, up, t0, lo, hi, tol);
    if (!t) return;
    Vec3d p, dp;
    curve_at(s, best->curve, *t, p, dp);
    // The plane kept exactly (the crossing is solved to 1e-12 L): other steps test it with ==.
    if (keep == Keep::kWaterline) {
      if (up.x == 0 && up.y == 0)
        p.z = waterline_z;
      else
        p = p + up * (waterline_z - dot(up, p));
    }
    if (keep == Keep::kStation && std::abs(p.x - q.x) <= tol) p.x = q.x;
    if (!(norm(p - q) <= reach)) return;
    // A node below the waterline stays below it (the curve may rise through the plane nearby).
    if (std::isfinite(waterline_z) && keep != Keep::kWaterline && dot(up, p) > waterline_z) return;
    // A node in the centre plane (put there exactly by the cut or the half hull's border) stays
    // within the centre plane's tolerance (kPlaneTolerance), which puts it back: the curve matched
    // may be a knuckle that leaves the plane. Property seed 4424: the corner of the centre plane
    // and the waterline on a transom immersed 5.5 mm went along the transom's lower edge to its
    // waterline crossing 0.079 m out, and the sliver between was left open below the waterline
    // in the mirrored hull.
    if (q.y == 0 && !(std::abs(p.y) <= kPlaneTolerance * length_scale)) return;
    // apply: this node's own slots only.
    mesh.positions[v] = p;
    mesh.vertex_patch[v] = best->curve.patch;
    mesh.vertex_uv[v] =
        best->curve.u_fixed ? Vec2d{best->curve.fixed, *t} : Vec2d{*t, best->curve.fixed};
    moved[v] = 1;
  });
  std::size_t count = 0;
  for (std::uint8_t m : moved) count += m;
  return count;
}

}  // namespace hm::structured
