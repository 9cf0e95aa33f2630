// Closest point on the hull: rtcPointQuery over the triangles gives the nearest triangle of each
// nearby patch, Newton on the NURBS (hm::closest_point) gives the exact point.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "query/embree_device.h"
#include "query/query_scene.h"

namespace hm {
namespace query {
namespace {

using Impl = HullQuery::Impl;

struct TrianglePoint {
  Vec3d point;
  double b1 = 0, b2 = 0;  // barycentric weights of corners 1 and 2
};

// Closest point to p on triangle (a, b, c), by the Voronoi regions of its vertices and edges
// (Ericson, Real-Time Collision Detection, 5.1.5). Degenerate triangles fall into a vertex or
// edge region, never divide by zero.
TrianglePoint closest_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {a, 0, 0};
  const Vec3d bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {b, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, v, 0};
  }
  const Vec3d cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {c, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), 1 - w, w};
  }
  const double denom = 1 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {a + v * ab + w * ac, v, w};
}

struct SearchState {
  const Impl* m = nullptr;
  Vec3d q;  // local frame
  double margin = 0;
  double best = std::numeric_limits<double>::infinity();
  PatchCandidates found;  // best triangle per patch, in the order met
  std::exception_ptr error;
};

void offer(SearchState& s, PatchId patch, Index t, double d, double b1, double b2) {
  PatchCandidates& f = s.found;
  for (int i = 0; i < f.count; ++i) {
    if (f.items[i].patch != patch) continue;
    if (d < f.items[i].distance) f.items[i] = {patch, t, d, {b1, b2}};
    return;
  }
  if (f.count < kMaxCandidates) {
    f.items[f.count++] = {patch, t, d, {b1, b2}};
    return;
  }
  auto worst = std::max_element(f.items.begin(), f.items.end(), [](const auto& a, const auto& b) {
    return a.distance < b.distance;
  });
  if (d < worst->distance) *worst = {patch, t, d, {b1, b2}};
}

// Called by Embree for every triangle whose box meets the query sphere. Shrinks the sphere to the
// nearest distance so far plus the margin. Must not throw into Embree.
bool visit_triangle(RTCPointQueryFunctionArguments* args) noexcept {
  auto& s = *static_cast<SearchState*>(args->userPtr);
  try {
    const Impl& m = *s.m;
    const Index t = m.triangle(args->geomID, args->primID);
    const auto& tri = m.tri[t];
    const TrianglePoint cp =
        closest_on_triangle(s.q, m.local[tri[0]], m.local[tri[1]], m.local[tri[2]]);
    const double d = norm(cp.point - s.q);
    offer(s, args->geomID, t, d, cp.b1, cp.b2);
    if (d < s.best) {
      s.best = d;
      const float r =
          std::nextafter(static_cast<float>(d + s.margin), std::numeric_limits<float>::infinity());
      if (r < args->query->radius) {
        args->query->radius = r;
        return true;
      }
    }
  } catch (...) {
    if (!s.error) s.error = std::current_exception();
  }
  return false;
}

struct VertexSearch {
  const Impl* m = nullptr;
  Vec3d q;  // local frame
  PatchId patch = kInvalid;
  double best = std::numeric_limits<double>::infinity();
  Index vertex = kInvalid;
};

// Called by Embree for every triangle whose box meets the query sphere: its corners made on the
// patch sought are offered, and the sphere shrinks to the nearest. Cannot throw.
bool visit_corners(RTCPointQueryFunctionArguments* args) noexcept {
  auto& s = *static_cast<VertexSearch*>(args->userPtr);
  const Impl& m = *s.m;
  bool shrunk = false;
  for (Index v : m.tri[m.triangle(args->geomID, args->primID)]) {
    if (m.vertex_patch[v] != s.patch) continue;
    const double d = norm(m.local[v] - s.q);
    if (d < s.best || (d == s.best && v < s.vertex)) {
      s.best = d;
      s.vertex = v;
      const float r = std::nextafter(static_cast<float>(d), std::numeric_limits<float>::infinity());
      if (r < args->query->radius) {
        args->query->radius = r;
        shrunk = true;
      }
    }
  }
  return shrunk;
}

// Embree's point query about q (local frame) over the hull's triangles: the sphere starts
// unbounded and the callback shrinks it.
void point_query(const Impl& m, const Vec3d& q, RTCPointQueryFunction visit, void* state) {
  RTCPointQuery query;
  query.x = static_cast<float>(q.x);
  query.y = static_cast<float>(q.y);
  query.z = static_cast<float>(q.z);
  query.time = 0;
  query.radius = std::numeric_limits<float>::infinity();
  RTCPointQueryContext ctx;
  rtcInitPointQueryContext(&ctx);
  rtcPointQuery(m.scene.get(), &query, &ctx, visit, state);
}

}  // namespace

Index nearest_vertex_on(const Impl& m, const Vec3d& q_model, PatchId p) {
  if (m.vertex_patch.empty()) return kInvalid;
  VertexSearch s;
  s.m = &m;
  s.q = q_model - m.centre;
  s.patch = p;
  point_query(m, s.q, visit_corners, &s);
  return s.vertex;
}

PatchCandidates patches_near(const Impl& m, const Vec3d& q_model, double extra) {
  SearchState s;
  s.m = &m;
  s.q = q_model - m.centre;
  s.margin = 2 * m.max_deviation + 1e-9 * m.length + extra;
  point_query(m, s.q, visit_triangle, &s);
  if (s.error) std::rethrow_exception(s.error);

  // Keep the patches within reach of the nearest, nearest first (ties by patch: deterministic).
  // Insertion sort: at most kMaxCandidates items.
  auto before = [](const PatchCandidate& a, const PatchCandidate& b) {
    return a.distance != b.distance ? a.distance < b.distance : a.patch < b.patch;
  };
  PatchCandidates out;
  for (int i = 0; i < s.found.count; ++i) {
    const PatchCandidate& c = s.found.items[i];
    if (!(c.distance <= s.best + s.margin)) continue;
    int k = out.count++;
    for (; k > 0 && before(c, out.items[k - 1]); --k) out.items[k] = out.items[k - 1];
    out.items[k] = c;
  }
  // The candidates' uv fields held barycentric weights; turn them into (u, v).
  for (int i = 0; i < out.count; ++i) {
    PatchCandidate& c = out.items[i];
    c.uv = m.uv_at(c.triangle, c.uv.x, c.uv.y);
  }
  return out;
}

}  // namespace query

namespace query {
namespace {

// The nearest point to q in the knot spans around (u, v), one span either way in each
// direction, by Newton kept inside each span from the nearest of a grid of points in it. A patch
// that wraps two faces about a knuckle (a transom and the bottom, about a repeated knot) has a
// nearest point on each, and Newton from one face does not reach the other's: from the bottom a
// step overshoots the knot onto the transom and ends there.
constexpr int kSpanSamples = 8;
constexpr double kSpanInset = 1e-9;  // of the span

struct SpanNearest {
  Vec2d uv;
  Vec3d point;
  double distance = std::numeric_limits<double>::infinity();
};

SpanNearest nearest_in_spans(const NurbsSurface& s, double net, const Vec2d& uv, const Vec3d& q) {
  const auto spans = [](const std::vector<double>& knots, int degree, double at) {
    std::vector<double> k;  // the distinct knots of the domain
    for (std::size_t i = static_cast<std::size_t>(degree);
         i + static_cast<std::size_t>(degree) < knots.size(); ++i) {
      if (k.empty() || knots[i] > k.back()) k.push_back(knots[i]);
    }
    std::vector<std::array<double, 2>> out;
    if (k.size() < 2) return out;
    std::size_t at_span = 0;
    while (at_span + 2 < k.size() && at >= k[at_span + 1]) ++at_span;
    for (std::size_t i = at_span > 0 ? at_span - 1 : 0; i <= at_span + 1 && i + 1 < k.size(); ++i)
      out.push_back({k[i], k[i + 1]});
    return out;
  };
  SpanNearest best;
  if (s.degree_u < 1 || s.degree_v < 1) return best;
  NurbsSurface span = s;  // the same surface, its domain narrowed to one span at a time
  for (const auto& su : spans(s.knots_u, s.degree_u, uv.x)) {
    for (const auto& sv : spans(s.knots_v, s.degree_v, uv.y)) {
      double nearest = std::numeric_limits<double>::infinity();
      Vec2d start;
      for (int i = 0; i < kSpanSamples; ++i) {
        for (int j = 0; j < kSpanSamples; ++j) {
          const Vec2d at{su[0] + (su[1] - su[0]) * (i + 0.5) / kSpanSamples,
                         sv[0] + (sv[1] - sv[0]) * (j + 0.5) / kSpanSamples};
          const double d = norm(q - evaluate(s, at.x, at.y));
          if (d < nearest) nearest = d, start = at;
        }
      }
      // A hair inside the span: on a knot the derivatives are the next span's, and where the
      // surface folds there (the transom's edge) they point along the wrong face.
      const double iu = kSpanInset * (su[1] - su[0]), iv = kSpanInset * (sv[1] - sv[0]);
      span.u0 = su[0] + iu, span.u1 = su[1] - iu, span.v0 = sv[0] + iv, span.v1 = sv[1] - iv;
      const SurfaceProjection p = closest_point(span, q, start.x, start.y, net);
      const double d = norm(q - p.point);
      if (d < best.distance) best = {{p.u, p.v}, p.point, d};
    }
  }
  return best;
}

// The nearest point on the NURBS among the candidates that `take` accepts, each refined from its
// triangle's (u, v).
template <class Take>
ClosestPoint refine_nearest(const HullQuery::Impl& m, const Vec3d& q, const PatchCandidates& near,
                            Take&& take) {
  ClosestPoint best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int i = 0; i < near.count; ++i) {
    const PatchCandidate& c = near.items[i];
    if (!take(c)) continue;
    auto refine_on = [&](PatchId p, Vec2d start, Vec2d& uv, Vec3d& point) {
      const NurbsSurface& surface = m.patches[p].surface;
      // Positions do not depend on the derivative order asked for (kernels/evaluate_nurbs.h), so
      // Newton's and the polish's last evaluations serve in place of evaluating again.
      SurfaceDerivs at_answer;
      const SurfaceProjection proj =
          hm::closest_point(surface, q, start.x, start.y, m.nets[p], at_answer);
      uv = polish_closest(surface, m.domains[p], q, {proj.u, proj.v}, at_answer, point);
      return norm(q - point);
    };
    auto refine_from = [&](Vec2d start, Vec2d& uv, Vec3d& point) {
      return refine_on(c.patch, start, uv, point);
    };
    const NurbsSurface& surface = m.patches[c.patch].surface;
    PatchId patch = c.patch;
    Vec2d uv;
    Vec3d point;
    double d = refine_from(c.uv, uv, point);
    // The triangle lies within the chord error of its NURBS, so the NURBS point is at most that
    // much farther than the triangle. Farther means Newton stopped where the surface folds at a
    // knuckle inside the patch (a repeated knot): a triangle across it takes corner (u, v) from
    // the face beyond, and a face that barely moves with u (a transom that narrows to the keel)
    // looks converged. Sample the triangle's (u, v) box and its surroundings instead, and start
    // again from the nearest sample.
    const double too_far = c.distance + 2 * m.max_deviation + 1e-9 * m.length;
    if (d > too_far) {
      const Vec2d corner[3] = {m.uv_at(c.triangle, 0, 0), m.uv_at(c.triangle, 1, 0),
                               m.uv_at(c.triangle, 0, 1)};
      Vec2d lo = corner[0], hi = corner[0];
      for (const Vec2d& k : corner) {
        lo = {std::min(lo.x, k.x), std::min(lo.y, k.y)};
        hi = {std::max(hi.x, k.x), std::max(hi.y, k.y)};
      }
      const ParamDomain& dom = m.domains[c.patch];
      const Vec2d pad = 0.5 * (hi - lo);
      lo = {std::max(dom.u0, lo.x - pad.x), std::max(dom.v0, lo.y - pad.y)};
      hi = {std::min(dom.u1, hi.x + pad.x), std::min(dom.v1, hi.y + pad.y)};
      constexpr int kSamples = 12;
      Vec2d start = uv;
      double start_d = d;
      for (int i = 0; i <= kSamples; ++i) {
        for (int j = 0; j <= kSamples; ++j) {
          const Vec2d at{lo.x + (hi.x - lo.x) * i / kSamples, lo.y + (hi.y - lo.y) * j / kSamples};
          const double d_at = norm(q - evaluate(surface, at.x, at.y));
          if (d_at < start_d) start_d = d_at, start = at;
        }
      }
      Vec2d uv_s;
      Vec3d point_s;
      const double d_s = refine_from(start, uv_s, point_s);
      if (d_s < d) d = d_s, uv = uv_s, point = point_s;
      // And from the triangle's corners, which lie on the NURBS: where one parameter moves the
      // surface hundreds of times faster on one side of a knuckle than on the other (a keel
      // running aft from a transom wrapped into the same patch: 450 m of x per unit of u against
      // a transom a few metres wide), the samples miss the fast side, while a corner on it
      // starts Newton there (property seed 1535: 0.81 m reported on a keel point).
      for (const Vec2d& k : corner) {
        if (d <= too_far) break;
        const double d_k = refine_from(k, uv_s, point_s);
        if (d_k < d) d = d_k, uv = uv_s, point = point_s;
      }
      // Still too far: the triangle reaches past its patch's surface, as a merge's stitch from
      // a patch's end to an overlapping patch's cut does, named for the first patch but up to a
      // panel long (property seed 6056: 0.57 m reported on a chine the panels followed
      // exactly). A corner made on another patch says which surface lies under it.
      for (int k = 0; k < 3 && d > too_far && !m.vertex_patch.empty(); ++k) {
        const Index v = m.tri[c.triangle][k];
        const PatchId p = m.vertex_patch[v];
        if (p == c.patch) continue;
        const double d_k = refine_on(p, m.domains[p].map(m.vertex_uv[v]), uv_s, point_s);
        if (d_k < d) d = d_k, uv = uv_s, point = point_s, patch = p;
      }
      // Still too far: the triangle lies over neither patch of its corners. A merge closes the
      // notch a gap opens at a transom's foot with a triangle from one patch's transom edge to
      // the other's keel, named for the first; from its (u, v) and its corners' Newton ends on a
      // keel 0.14 m away where the first patch's bottom lies under a millimetre off (property
      // seed 1385: a full chine hull of 2 patches with 0.0088 m gaps failed --validate on its
      // panels). The nearest vertex made on the patch lies on its surface, near the answer.
      // Newton from it may end on the wrong face of a patch that wraps two about a knuckle (it
      // did: on the transom, 0.22 m off), so it starts again in each knot span around.
      if (d > too_far) {
        const Index v = nearest_vertex_on(m, q, c.patch);
        if (v != kInvalid) {
          const double d_v =
              refine_on(c.patch, m.domains[c.patch].map(m.vertex_uv[v]), uv_s, point_s);
          if (d_v < d) d = d_v, uv = uv_s, point = point_s, patch = c.patch;
          if (d > too_far) {
            const SpanNearest n = nearest_in_spans(surface, m.nets[c.patch], uv_s, q);
            if (n.distance < d) d = n.distance, uv = n.uv, point = n.point, patch = c.patch;
          }
        }
      }
    }
    if (!(d < best.distance)) continue;
    best.patch = patch;
    best.face = m.tri_face[c.triangle];
    best.uv = uv;
    best.point = point;
    best.distance = d;
    best.on_surface = true;
  }
  if (best.valid()) best.normal = m.oriented_normal(best.patch, best.uv);
  return best;
}

}  // namespace
}  // namespace query

ClosestPoint HullQuery::closest_point(const Vec3d& q) const {
  if (!is_finite(q)) return {};
  return query::refine_nearest(*impl_, q, query::patches_near(*impl_, q, 0.0),
                               [](const query::PatchCandidate&) { return true; });
}

ClosestPoint HullQuery::closest_point_in_range(const Vec3d& q, PatchId first, PatchId last,
                                               double reach) const {
  if (!is_finite(q)) return {};
  return query::refine_nearest(*impl_, q, query::patches_near(*impl_, q, std::max(reach, 0.0)),
                               [&](const query::PatchCandidate& c) {
                                 return c.patch >= first && c.patch < last && c.distance <= reach;
                               });
}

void HullQuery::closest_points(std::span<const Vec3d> queries, std::span<ClosestPoint> out) const {
  if (out.size() != queries.size()) {
    throw InternalError("closest_points: output size differs from input");
  }
  parallel_for(0, queries.size(), [&](std::size_t i) { out[i] = closest_point(queries[i]); });
}

}  // namespace hm
