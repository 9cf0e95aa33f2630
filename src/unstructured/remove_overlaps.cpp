// Overlaps: where patches cover the same stretch of surface, the lowest-numbered patch keeps it
// and the others are cut away along the border of the patches below them, so that
// snap_borders can stitch them there.
//
// collect seeds (border vertices lying on a lower-numbered patch, checked on the NURBS through
// the Embree closest-point query) -> grow the covered region over each patch -> apply: drop
// covered faces, and move each covered corner of a straddling face to where its edges leave the
// patches below (bisection on their exact surfaces).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/bbox.h"
#include "core/parallel.h"
#include "mesh/adjacency.h"
#include "query/hull_query.h"
#include "unstructured/merge_border.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

// Normals of coincident layers agree to this (either orientation: patches may arrive flipped).
constexpr double kMinNormalCos = 0.866;  // 30 degrees

// The lowest-numbered patch below the vertex's own whose surface the vertex lies on, or
// kInvalid.
PatchId covering_patch(const HullQuery& q, std::span<const Patch> patches, const SurfaceMesh& m,
                       Index v, double distance) {
  const PatchId own = m.vertex_patch[v];
  if (own == 0) return kInvalid;
  // The triangles stray from the surface by up to the chord tolerance: search them wider than
  // the distance asked of the exact surfaces.
  const ClosestPoint cp = q.closest_point_in_range(m.positions[v], 0, own, 20 * distance);
  if (!cp.valid() || !(cp.distance <= distance)) return kInvalid;
  const Vec2d uv = m.vertex_uv[v];
  const Vec3d n = normal(patches[own].surface, uv.x, uv.y);
  if (std::abs(dot(n, cp.normal)) < kMinNormalCos) return kInvalid;
  return cp.patch;
}

// Border vertices that may lie inside another patch: no other patch's border edge near them, or
// the nearest such edge has them on its face's side (the vertex is past the border, on the
// other patch). Vertices exactly on another border (a shared edge, a knuckle) are not seeds.
std::vector<Index> seed_candidates(const SurfaceMesh& m, const Border& b,
                                   const MergeOptions& options, double floor) {
  std::vector<double> tol(b.vertices.size());
  for (std::size_t i = 0; i < tol.size(); ++i) tol[i] = vertex_tolerance(options, b.edge_length[i]);
  const SegmentGrid grid(m.positions, b.edges);
  std::vector<std::uint8_t> seed(b.vertices.size(), 0);
  parallel_for(0, b.vertices.size(), [&](std::size_t i) {
    const Index v = b.vertices[i];
    const Vec3d& p = m.positions[v];
    double best = std::numeric_limits<double>::infinity();
    Index best_edge = kInvalid;
    SegmentPoint best_sp;
    grid.for_each_near(p, tol[i], [&](Index e) {
      const BorderEdge& be = b.edges[e];
      if (be.patch == m.vertex_patch[v]) return;
      const SegmentPoint sp = closest_on_segment(p, m.positions[be.v0], m.positions[be.v1]);
      if (sp.distance < best || (sp.distance == best && e < best_edge)) {
        best = sp.distance;
        best_edge = e;
        best_sp = sp;
      }
    });
    if (best_edge == kInvalid || best > tol[i]) {
      seed[i] = 1;
      return;
    }
    if (best <= floor) return;
    const BorderEdge& be = b.edges[best_edge];
    const Face& f = m.faces[be.face];
    Index apex = f[0];
    for (int c = 0; c < 3; ++c) {
      if (f[c] != be.v0 && f[c] != be.v1) apex = f[c];
    }
    const Vec3d a = m.positions[be.v0], d = m.positions[be.v1] - a;
    const Vec3d on = a + best_sp.t * d;
    Vec3d inward = m.positions[apex] - a;
    const double dd = dot(d, d);
    if (dd > 0) inward -= (dot(inward, d) / dd) * d;
    if (dot(p - on, inward) > 0) seed[i] = 1;
  });
  std::vector<Index> out;
  for (std::size_t i = 0; i < seed.size(); ++i) {
    if (seed[i]) out.push_back(b.vertices[i]);
  }
  return out;
}

// The faces that may cover a candidate: of patches numbered below the candidate's whose
// bounding box (grown by `margin`) holds it; with `close_only`, further only the faces whose
// centroid lies within their longest edge plus `margin` of a candidate. Vertices are kept as
// they are (unused ones are harmless).
SurfaceMesh faces_near(const SurfaceMesh& m, std::span<const Index> candidates,
                       std::size_t patch_count, double margin, bool close_only) {
  std::vector<BBox3d> box(patch_count);
  for (std::size_t v = 0; v < m.vertex_count(); ++v) box[m.vertex_patch[v]].add(m.positions[v]);
  for (BBox3d& b : box) {
    if (b.empty()) continue;
    b.lo -= Vec3d{margin, margin, margin};
    b.hi += Vec3d{margin, margin, margin};
  }
  std::vector<std::uint8_t> needed(patch_count, 0);
  PatchId highest = 0;
  for (Index v : candidates) {
    const Vec3d& p = m.positions[v];
    highest = std::max(highest, m.vertex_patch[v]);
    for (std::size_t q = 0; q < m.vertex_patch[v]; ++q) {
      const BBox3d& b = box[q];
      if (!needed[q] && p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y &&
          p.z >= b.lo.z && p.z <= b.hi.z) {
        needed[q] = 1;
      }
    }
  }
  std::vector<std::uint8_t> keep(m.face_count(), 0);
  parallel_for(0, m.face_count(), [&](std::size_t f) { keep[f] = needed[m.face_patch[f]]; });
  if (close_only) {
    // Candidates as zero-length segments in the segment grid: "near a point" is then a query.
    std::vector<BorderEdge> points(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      points[i] = {candidates[i], candidates[i], kInvalid, m.vertex_patch[candidates[i]]};
    }
    double longest = 0;
    for (const Face& t : m.faces) {
      for (int k = 0; k < 3; ++k) {
        longest = std::max(longest, norm(m.positions[t[(k + 1) % 3]] - m.positions[t[k]]));
      }
    }
    const SegmentGrid grid(m.positions, points, longest + margin);
    parallel_for(0, m.face_count(), [&](std::size_t f) {
      if (!keep[f]) return;
      const Face& t = m.faces[f];
      const Vec3d c = face_centroid(m.positions, t);
      double edge = 0;
      for (int k = 0; k < 3; ++k) {
        edge = std::max(edge, norm(m.positions[t[(k + 1) % 3]] - m.positions[t[k]]));
      }
      const double r = edge + margin;
      bool close = false;
      grid.for_each_near(c, r, [&](Index i) {
        close |= points[i].patch > m.face_patch[f] && norm(m.positions[points[i].v0] - c) <= r;
      });
      keep[f] = close;
    });
  }
  SurfaceMesh sub;
  sub.positions = m.positions;
  sub.vertex_patch = m.vertex_patch;
  sub.vertex_uv = m.vertex_uv;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    if (!keep[f]) continue;
    sub.faces.push_back(m.faces[f]);
    sub.face_patch.push_back(m.face_patch[f]);
  }
  return sub;
}

}  // namespace

OverlapStats remove_overlaps(std::span<const Patch> patches, Work& w, const Border& b,
                             const MergeOptions& options, double length, Progress& progress) {
  OverlapStats stats;
  SurfaceMesh& m = w.mesh;
  const double distance = options.overlap_distance > 0 ? options.overlap_distance : 1e-4 * length;
  // Collect: seeds, checked on the NURBS in parallel (each writes its own slot).
  const std::vector<Index> candidates = seed_candidates(m, b, options, distance);
  if (candidates.empty()) return stats;
  // The seeds need only the faces around them; building a BVH over the whole hull would cost
  // more than the merge itself. Only when a seed is covered is a query over every patch that
  // may cover a candidate built, for growing the covered regions and cutting them.
  std::vector<PatchId> seed_cover(candidates.size(), kInvalid);
  {
    const SurfaceMesh near = faces_near(m, candidates, patches.size(), 20 * distance, true);
    if (near.faces.empty()) return stats;
    const HullQuery seed_query(patches, near);
    parallel_for(0, candidates.size(), [&](std::size_t i) {
      seed_cover[i] = covering_patch(seed_query, patches, m, candidates[i], distance);
    });
  }
  if (progress.cancelled()) return stats;
  if (std::all_of(seed_cover.begin(), seed_cover.end(), [](PatchId p) { return p == kInvalid; })) {
    return stats;
  }
  const HullQuery query(patches, faces_near(m, candidates, patches.size(), 20 * distance, false));
  stats.changed = true;  // from here on faces may go and corners move

  // Grow the covered region of each patch from its seeds across its own edges (breadth-first,
  // ring by ring: each ring is checked in parallel and committed in order).
  std::vector<std::vector<Index>> ring(m.vertex_count());
  for (const Face& f : m.faces) {
    for (int c = 0; c < 3; ++c) ring[f[c]].push_back(f[(c + 1) % 3]);
  }
  std::vector<PatchId> cover(m.vertex_count(), kInvalid);
  std::vector<std::uint8_t> checked(m.vertex_count(), 0);
  std::vector<Index> frontier;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Index v = candidates[i];
    checked[v] = 1;
    if (seed_cover[i] != kInvalid) {
      cover[v] = seed_cover[i];
      frontier.push_back(v);
    }
  }
  while (!frontier.empty()) {
    std::vector<Index> next;
    for (Index v : frontier) {
      for (Index u : ring[v]) {
        if (!checked[u]) {
          checked[u] = 1;
          next.push_back(u);
        }
      }
    }
    std::vector<PatchId> found(next.size(), kInvalid);
    parallel_for(0, next.size(), [&](std::size_t i) {
      found[i] = covering_patch(query, patches, m, next[i], distance);
    });
    frontier.clear();
    for (std::size_t i = 0; i < next.size(); ++i) {
      if (found[i] == kInvalid) continue;
      cover[next[i]] = found[i];
      frontier.push_back(next[i]);
    }
    if (progress.cancelled()) return stats;
  }

  // A covered vertex that no fully covered face holds lies on a covered sliver one edge wide;
  // moving it would fold the faces on its two sides over each other. It stays, and snapping
  // handles the sliver.
  {
    std::vector<std::uint8_t> in_removed(m.vertex_count(), 0);
    for (const Face& t : m.faces) {
      if (cover[t[0]] != kInvalid && cover[t[1]] != kInvalid && cover[t[2]] != kInvalid) {
        for (int c = 0; c < 3; ++c) in_removed[t[c]] = 1;
      }
    }
    for (std::size_t v = 0; v < cover.size(); ++v) {
      if (!in_removed[v]) cover[v] = kInvalid;
    }
  }

  // Border neighbours of each border vertex (along its own patch's border).
  std::vector<std::vector<Index>> border_next(m.vertex_count());
  for (const BorderEdge& e : b.edges) {
    border_next[e.v0].push_back(e.v1);
    border_next[e.v1].push_back(e.v0);
  }

  // Apply, patch by patch: covered faces go, and covered corners of straddling faces move to
  // where their edges leave the patches below (tested on the exact surfaces, which cuts do not
  // change, so the order of the patches does not matter).
  std::vector<std::vector<Index>> faces_of(patches.size());
  for (std::size_t f = 0; f < m.face_count(); ++f) faces_of[m.face_patch[f]].push_back(Index(f));
  std::vector<std::uint8_t> keep(m.face_count(), 1);
  for (std::size_t p = 1; p < patches.size(); ++p) {
    // Faces with every corner covered go; covered corners of the others move.
    double before = 0;
    std::vector<Index> straddling;
    for (Index f : faces_of[p]) {
      const Face& t = m.faces[f];
      const int covered =
          (cover[t[0]] != kInvalid) + (cover[t[1]] != kInvalid) + (cover[t[2]] != kInvalid);
      if (covered == 0) continue;
      const double area = face_area(m.positions, t);
      if (covered == 3) {
        keep[f] = 0;
        ++stats.triangles;
        stats.area += area;
      } else {
        straddling.push_back(f);
        before += area;
      }
    }
    std::vector<Index> moved;
    for (Index f : straddling) {
      for (int c = 0; c < 3; ++c) {
        if (cover[m.faces[f][c]] != kInvalid) moved.push_back(m.faces[f][c]);
      }
    }
    std::sort(moved.begin(), moved.end());
    moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
    // Each moved corner goes to where its edges towards uncovered corners leave the covered
    // region (bisection on the exact surfaces of the patches below), the nearest such point:
    // that is the cut along the covering patches' border.
    // A corner on the patch's border (the hull's outline, say) leaves along that border, so
    // that the outline keeps its place.
    std::vector<std::vector<Index>> out_to(moved.size());
    for (Index f : straddling) {
      const Face& t = m.faces[f];
      for (int c = 0; c < 3; ++c) {
        if (cover[t[c]] == kInvalid) continue;
        const std::size_t i =
            std::size_t(std::lower_bound(moved.begin(), moved.end(), t[c]) - moved.begin());
        for (int d = 1; d < 3; ++d) {
          const Index u = t[(c + d) % 3];
          if (cover[u] == kInvalid) out_to[i].push_back(u);
        }
      }
    }
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const auto& along = border_next[moved[i]];
      std::vector<Index> on_border;
      for (Index u : out_to[i]) {
        if (std::find(along.begin(), along.end(), u) != along.end()) on_border.push_back(u);
      }
      if (!along.empty() && !on_border.empty()) out_to[i] = std::move(on_border);
    }
    const auto on_lower = [&](const Vec3d& x) {
      // The chord of an edge strays from the surface by up to the tessellation tolerance.
      const ClosestPoint cp = query.closest_point_in_range(x, 0, PatchId(p), 20 * distance);
      return cp.valid() && cp.distance <= 3 * distance;
    };
    std::vector<Vec3d> target(moved.size());
    parallel_for(0, moved.size(), [&](std::size_t i) {
      const Vec3d from = m.positions[moved[i]];
      double best = std::numeric_limits<double>::infinity();
      target[i] = from;
      for (Index u : out_to[i]) {
        const Vec3d to = m.positions[u];
        double lo = 0, hi = 1;  // covered at lo, not at hi
        for (int it = 0; it < 40 && (hi - lo) * norm(to - from) > 1e-3 * distance; ++it) {
          const double mid = 0.5 * (lo + hi);
          (on_lower(from + mid * (to - from)) ? lo : hi) = mid;
        }
        const Vec3d exit = from + lo * (to - from);
        const double d = norm(exit - from);
        if (d < best) {
          best = d;
          target[i] = exit;
        }
      }
    });
    for (std::size_t i = 0; i < moved.size(); ++i) m.positions[moved[i]] = target[i];
    double after = 0;
    for (Index f : straddling) after += face_area(m.positions, m.faces[f]);
    stats.area += before - after;
  }

  compact_faces(w, keep);
  return stats;
}

}  // namespace hm::merge
