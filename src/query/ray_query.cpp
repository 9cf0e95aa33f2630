// Ray queries: Embree finds the triangle, Newton on (t, u, v) puts the hit on the NURBS.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <tuple>

#include "core/error.h"
#include "core/parallel.h"
#include "query/embree_device.h"
#include "query/query_scene.h"

namespace hm {
namespace {

using Impl = HullQuery::Impl;

// Rays per rtcIntersect1M call; also the grain of the parallel loop over a batch.
constexpr std::size_t kStreamSize = 256;

RTCRayHit make_ray(const Impl& m, const Ray& r) {
  RTCRayHit rh{};
  const Vec3d o = r.origin - m.centre;
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(r.dir.x);
  rh.ray.dir_y = static_cast<float>(r.dir.y);
  rh.ray.dir_z = static_cast<float>(r.dir.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = r.tmax >= std::numeric_limits<float>::max() ? std::numeric_limits<float>::infinity()
                                                            : static_cast<float>(r.tmax);
  rh.ray.mask = ~0u;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

bool usable(const Ray& r) {
  return is_finite(r.origin) && is_finite(r.dir) && squared_norm(r.dir) > 0 && r.tmax > 0;
}

// The triangle hit (geom, prim) at barycentric (b1, b2) and ray parameter t0, refined onto the
// NURBS. When Newton fails on the triangle's own patch (the exact crossing lies just across a
// patch border), the patches near where it was heading are tried.
RayHit refine_hit(const Impl& m, const Ray& r, unsigned geom, unsigned prim, float b1, float b2,
                  float t0) {
  const Index t = m.triangle(geom, prim);
  const PatchId p = geom;
  const double tol = m.accept_tolerance();
  RayHit h;
  h.patch = p;
  h.face = m.tri_face[t];
  const Vec2d uv0 = m.uv_at(t, b1, b2);
  query::RefinedRay rr =
      query::refine_ray(m.patches[p].surface, m.domains[p], r.origin, r.dir, t0, uv0, tol);
  if (!rr.converged) {
    const Vec3d estimate = r.origin + double{t0} * r.dir;
    const query::PatchCandidates near =
        query::patches_near(m, estimate, 2 * norm(estimate - rr.point));
    for (int i = 0; i < near.count && !rr.converged; ++i) {
      const query::PatchCandidate& c = near.items[i];
      if (c.patch == p) continue;
      const query::RefinedRay other = query::refine_ray(
          m.patches[c.patch].surface, m.domains[c.patch], r.origin, r.dir, t0, c.uv, tol);
      if (other.converged) {
        rr = other;
        h.patch = c.patch;
        h.face = m.tri_face[c.triangle];
      }
    }
  }
  h.on_surface = rr.converged;
  h.uv = rr.converged ? rr.uv : uv0;
  h.t = rr.converged ? rr.t : double{t0};
  h.point = rr.converged ? rr.point : r.origin + h.t * r.dir;
  h.normal = m.oriented_normal(h.patch, h.uv);
  return h;
}

// Mesh crossings past which the first-hit search gives up looking for a surface crossing.
constexpr int kMaxSkips = 8;

// The first surface crossing, from Embree's first mesh crossing rh. A mesh crossing that is not
// a surface crossing (a ray grazing the hull within the chord error) is skipped and the ray
// traced on from just beyond it.
RayHit resolve_first(const Impl& m, const Ray& r, RTCRayHit rh) {
  RayHit first_unrefined;
  for (int k = 0; k < kMaxSkips && rh.hit.geomID != RTC_INVALID_GEOMETRY_ID; ++k) {
    const RayHit h =
        refine_hit(m, r, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar);
    if (h.on_surface) return h;
    if (k == 0) first_unrefined = h;
    const float t = rh.ray.tfar;
    rh = make_ray(m, r);
    rh.ray.tnear = std::nextafter(t, std::numeric_limits<float>::infinity());
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect1(m.scene.get(), &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return RayHit{};
  }
  return first_unrefined;
}

// An intersection context that carries the list the filter appends to. The Embree context is
// the first member, so the pointer Embree hands back converts to the whole.
struct RawHit {
  float t, b1, b2;
  unsigned geom, prim;
};
struct CollectContext {
  RTCIntersectContext base;
  std::vector<RawHit>* hits;
  std::exception_ptr error;
};

// Records every candidate crossing and rejects it, so traversal goes on to the next one. Must
// not throw into Embree: a failure is stored and rethrown after the call.
void collect_hits(const RTCFilterFunctionNArguments* args) noexcept {
  auto* ctx = reinterpret_cast<CollectContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    try {
      ctx->hits->push_back({RTCRayN_tfar(args->ray, args->N, i), RTCHitN_u(args->hit, args->N, i),
                            RTCHitN_v(args->hit, args->N, i), RTCHitN_geomID(args->hit, args->N, i),
                            RTCHitN_primID(args->hit, args->N, i)});
    } catch (...) {
      if (!ctx->error) ctx->error = std::current_exception();
    }
    args->valid[i] = 0;
  }
}

}  // namespace

RayHit HullQuery::first_hit(const Ray& ray) const {
  if (!usable(ray)) return RayHit{};
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = make_ray(*impl_, ray);
  rtcIntersect1(impl_->scene.get(), &ctx, &rh);
  return resolve_first(*impl_, ray, rh);
}

std::vector<RayHit> HullQuery::all_hits(const Ray& ray) const {
  std::vector<RayHit> out;
  if (!usable(ray)) return out;
  std::vector<RawHit> raw;
  CollectContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.base.filter = collect_hits;
  ctx.hits = &raw;
  RTCRayHit rh = make_ray(*impl_, ray);
  rtcIntersect1(impl_->scene.get(), &ctx.base, &rh);
  if (ctx.error) std::rethrow_exception(ctx.error);

  // A triangle split into several BVH leaves (spatial splits) may report twice.
  std::sort(raw.begin(), raw.end(), [](const RawHit& a, const RawHit& b) {
    return std::tie(a.geom, a.prim, a.t) < std::tie(b.geom, b.prim, b.t);
  });
  raw.erase(std::unique(raw.begin(), raw.end(),
                        [](const RawHit& a, const RawHit& b) {
                          return a.geom == b.geom && a.prim == b.prim;
                        }),
            raw.end());
  out.reserve(raw.size());
  for (const RawHit& h : raw) {
    // Mesh crossings that are not surface crossings (grazing rays) are dropped.
    RayHit hit = refine_hit(*impl_, ray, h.geom, h.prim, h.b1, h.b2, h.t);
    if (hit.on_surface) out.push_back(hit);
  }
  std::sort(out.begin(), out.end(), [](const RayHit& a, const RayHit& b) {
    return std::tie(a.t, a.patch, a.face) < std::tie(b.t, b.patch, b.face);
  });
  // One crossing reported by the triangles around a shared edge or vertex, or by two patches at
  // their border, refines to one point: keep the first.
  const double merge = 1e-9 * impl_->length;
  std::vector<RayHit> merged;
  for (const RayHit& h : out) {
    if (!merged.empty() && norm(h.point - merged.back().point) <= merge) continue;
    merged.push_back(h);
  }
  return merged;
}

void HullQuery::first_hits(std::span<const Ray> rays, std::span<RayHit> out) const {
  if (out.size() != rays.size()) throw InternalError("first_hits: output size differs from input");
  const std::size_t chunks = (rays.size() + kStreamSize - 1) / kStreamSize;
  parallel_for_each_item(chunks, [&](std::size_t c) {
    const std::size_t begin = c * kStreamSize;
    const std::size_t end = std::min(rays.size(), begin + kStreamSize);
    RTCRayHit stream[kStreamSize];
    for (std::size_t i = begin; i < end; ++i) {
      stream[i - begin] = make_ray(*impl_, rays[i]);
      // An unusable ray gets an empty segment, so Embree skips it.
      if (!usable(rays[i])) stream[i - begin].ray.tfar = -1.0f;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    rtcIntersect1M(impl_->scene.get(), &ctx, stream, static_cast<unsigned>(end - begin),
                   sizeof(RTCRayHit));
    for (std::size_t i = begin; i < end; ++i)
      out[i] = resolve_first(*impl_, rays[i], stream[i - begin]);
  });
}

}  // namespace hm
