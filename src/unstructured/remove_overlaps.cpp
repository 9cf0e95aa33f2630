// Overlaps: where two patches cover the same stretch of surface, one layer is cut away along the
// other patch's border, so that snap_borders can stitch the two there.
//
// collect seeds (border vertices lying inside another patch, checked on the NURBS through the
// Embree closest-point query) -> select which patch of each overlapping pair is cut -> grow the
// covered region over the cut patch -> apply: drop covered faces, move the covered corners of
// straddling faces onto the covering patch's border.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/parallel.h"
#include "mesh/adjacency.h"
#include "query/hull_query.h"
#include "unstructured/merge_border.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

// Normals of coincident layers agree to this (either orientation: patches may arrive flipped).
constexpr double kMinNormalCos = 0.866;  // 30 degrees

struct Cover {
  PatchId by = kInvalid;  // the covering patch, or kInvalid
};

// The patch (other than the vertex's own) whose surface the vertex lies on, or kInvalid.
PatchId covering_patch(const HullQuery& q, std::span<const Patch> patches, const SurfaceMesh& m,
                       Index v, double distance) {
  const PatchId own = m.vertex_patch[v];
  // The triangles stray from the surface by up to the chord tolerance: search them wider than
  // the distance asked of the exact surfaces.
  const ClosestPoint cp = q.closest_point_excluding(m.positions[v], own, 20 * distance);
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
  double reach = 0;
  for (std::size_t i = 0; i < tol.size(); ++i) {
    tol[i] = vertex_tolerance(options, b.edge_length[i]);
    reach = std::max(reach, tol[i]);
  }
  const SegmentGrid grid(m.positions, b.edges, reach);
  std::vector<std::uint8_t> seed(b.vertices.size(), 0);
  parallel_for(0, b.vertices.size(), [&](std::size_t i) {
    const Index v = b.vertices[i];
    const Vec3d& p = m.positions[v];
    double best = std::numeric_limits<double>::infinity();
    Index best_edge = kInvalid;
    SegmentPoint best_sp;
    grid.for_each_near(p, [&](Index e) {
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

}  // namespace

OverlapStats remove_overlaps(std::span<const Patch> patches, Work& w, const MergeOptions& options,
                             double length, Progress& progress) {
  OverlapStats stats;
  SurfaceMesh& m = w.mesh;
  const double distance = options.overlap_distance > 0 ? options.overlap_distance : 1e-4 * length;
  const Border b = collect_border(m);
  // Collect: seeds, checked on the NURBS in parallel (each writes its own slot).
  const std::vector<Index> candidates = seed_candidates(m, b, options, distance);
  if (candidates.empty()) return stats;
  const HullQuery query(patches, m);
  std::vector<PatchId> seed_cover(candidates.size(), kInvalid);
  parallel_for(0, candidates.size(), [&](std::size_t i) {
    seed_cover[i] = covering_patch(query, patches, m, candidates[i], distance);
  });
  if (progress.cancelled()) return stats;

  // Select: of two patches that cover each other, cut the higher-numbered one.
  std::set<std::pair<PatchId, PatchId>> covers;  // (covered, by)
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (seed_cover[i] != kInvalid) covers.insert({m.vertex_patch[candidates[i]], seed_cover[i]});
  }
  if (covers.empty()) return stats;
  const auto cut = [&](PatchId covered, PatchId by) {
    return covers.count({covered, by}) && (covered > by || !covers.count({by, covered}));
  };

  // Grow the covered region of each cut patch from its seeds across its own edges (serial
  // breadth-first walk in seed order; each vertex is checked once).
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
    if (seed_cover[i] != kInvalid && cut(m.vertex_patch[v], seed_cover[i])) {
      cover[v] = seed_cover[i];
      frontier.push_back(v);
    }
  }
  while (!frontier.empty()) {
    // Evaluate the next ring in parallel, commit in order.
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
      if (found[i] != kInvalid && cut(m.vertex_patch[next[i]], found[i])) {
        cover[next[i]] = found[i];
        frontier.push_back(next[i]);
      }
    }
    if (progress.cancelled()) return stats;
  }

  // Apply: faces with every corner covered go; covered corners of the others move onto the
  // covering patch's border (its nearest border edge).
  std::vector<std::uint8_t> keep(m.face_count(), 1);
  std::vector<std::uint8_t> straddles(m.face_count(), 0);
  double before = 0;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
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
      straddles[f] = 1;
      before += area;
    }
  }
  // Only corners of kept faces need a place; the others vanish with their faces.
  std::vector<std::uint8_t> on_kept(m.vertex_count(), 0);
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    if (!straddles[f]) continue;
    for (int c = 0; c < 3; ++c) on_kept[m.faces[f][c]] = 1;
  }
  std::vector<Index> moved;
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    if (cover[v] != kInvalid && on_kept[v]) moved.push_back(Index(v));
  }
  std::vector<Vec3d> target(moved.size());
  std::set<PatchId> covering;
  for (const auto& [covered, by] : covers) covering.insert(by);
  std::vector<BorderEdge> edges_by;  // border edges of the covering patches
  double longest = 0;
  for (const BorderEdge& e : b.edges) {
    if (!covering.count(e.patch)) continue;
    edges_by.push_back(e);
    longest = std::max(longest, norm(m.positions[e.v1] - m.positions[e.v0]));
  }
  // A straddling corner lies within about one edge of the covering border.
  const SegmentGrid grid(m.positions, edges_by, 2 * longest);
  parallel_for(0, moved.size(), [&](std::size_t i) {
    const Index v = moved[i];
    const Vec3d& p = m.positions[v];
    double best = std::numeric_limits<double>::infinity();
    target[i] = p;
    Index best_edge = kInvalid;
    grid.for_each_near(p, [&](Index e) {
      const BorderEdge& be = edges_by[e];
      if (be.patch != cover[v]) return;
      const SegmentPoint sp = closest_on_segment(p, m.positions[be.v0], m.positions[be.v1]);
      if (sp.distance < best || (sp.distance == best && e < best_edge)) {
        best = sp.distance;
        best_edge = e;
        target[i] = m.positions[be.v0] + sp.t * (m.positions[be.v1] - m.positions[be.v0]);
      }
    });
  });
  for (std::size_t i = 0; i < moved.size(); ++i) m.positions[moved[i]] = target[i];
  double after = 0;
  std::size_t kept = 0;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    if (straddles[f]) after += face_area(m.positions, m.faces[f]);
    if (!keep[f]) continue;
    m.faces[kept] = m.faces[f];
    m.face_patch[kept] = m.face_patch[f];
    w.face_old[kept] = w.face_old[f];
    ++kept;
  }
  m.faces.resize(kept);
  m.face_patch.resize(kept);
  w.face_old.resize(kept);
  stats.area += before - after;
  return stats;
}

}  // namespace hm::merge
