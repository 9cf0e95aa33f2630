// Overlaps: where patches cover the same stretch of surface, the lowest-numbered patch keeps it
// and the others are cut away along the border of the patches below them, so that
// snap_borders can stitch them there.
//
// collect seeds (border vertices lying on a lower-numbered patch, checked on the NURBS through
// the Embree closest-point query) -> grow the covered region over each patch -> apply: drop
// covered faces, and move each covered corner of a straddling face onto the border of the
// patches below (the nearest point of their border edges inside its faces, else where its edges
// leave them, by bisection on their exact surfaces). An overlap narrower than an edge covers no
// face; its border vertices are cut the same way, so that the two borders meet for the snap.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

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

// A patch's border lying on a lower patch across less than this share of its border edges is
// left to the snap, as a gap would be.
constexpr double kNarrowShare = 0.25;

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
std::vector<Index> seed_candidates(const SurfaceMesh& m, const Border& b, const SegmentGrid& grid,
                                   const MergeOptions& options, double floor) {
  std::vector<double> tol(b.vertices.size());
  for (std::size_t i = 0; i < tol.size(); ++i) tol[i] = vertex_tolerance(options, b.edge_length[i]);
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
    const Vec3d a = m.positions[be.v0];
    const Vec3d on = a + best_sp.t * (m.positions[be.v1] - a);
    if (dot(p - on, edge_inward(m, be)) > 0) seed[i] = 1;
  });
  std::vector<Index> out;
  for (std::size_t i = 0; i < seed.size(); ++i) {
    if (seed[i]) out.push_back(b.vertices[i]);
  }
  return out;
}

// Bounding box of each patch's vertices, grown by `margin` (empty patches stay empty).
std::vector<BBox3d> patch_boxes(const SurfaceMesh& m, std::size_t patch_count, double margin) {
  std::vector<BBox3d> box(patch_count);
  for (std::size_t v = 0; v < m.vertex_count(); ++v) box[m.vertex_patch[v]].add(m.positions[v]);
  for (BBox3d& b : box) {
    if (b.empty()) continue;
    b.lo -= Vec3d{margin, margin, margin};
    b.hi += Vec3d{margin, margin, margin};
  }
  return box;
}

// The faces with keep[f] set, over all of m's vertices (unused ones are harmless).
SurfaceMesh faces_kept(const SurfaceMesh& m, std::span<const std::uint8_t> keep) {
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

// The faces that may cover a candidate: of patches numbered below the candidate's whose
// bounding box (grown by `margin`) holds it, and whose centroid lies within their longest edge
// plus `margin` of a candidate.
SurfaceMesh faces_near(const SurfaceMesh& m, std::span<const Index> candidates,
                       std::size_t patch_count, double margin) {
  const std::vector<BBox3d> box = patch_boxes(m, patch_count, margin);
  std::vector<std::uint8_t> needed(patch_count, 0);
  for (Index v : candidates) {
    const Vec3d& p = m.positions[v];
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
  {
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
  return faces_kept(m, keep);
}

// The faces that may cover any vertex of a patch with a covered seed (the covered regions grow
// over those patches only): of lower-numbered patches whose bounding box, grown by `margin`,
// meets that patch's. Vertices are kept as they are.
SurfaceMesh faces_under(const SurfaceMesh& m, std::span<const Index> candidates,
                        std::span<const PatchId> seed_cover, std::size_t patch_count,
                        double margin) {
  const std::vector<BBox3d> box = patch_boxes(m, patch_count, 0);
  const auto meet = [&](const BBox3d& a, const BBox3d& b) {
    return a.lo.x <= b.hi.x + margin && b.lo.x <= a.hi.x + margin && a.lo.y <= b.hi.y + margin &&
           b.lo.y <= a.hi.y + margin && a.lo.z <= b.hi.z + margin && b.lo.z <= a.hi.z + margin;
  };
  std::vector<std::uint8_t> grows(patch_count, 0), needed(patch_count, 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (seed_cover[i] != kInvalid) grows[m.vertex_patch[candidates[i]]] = 1;
  }
  for (std::size_t p = 0; p < patch_count; ++p) {
    if (!grows[p] || box[p].empty()) continue;
    for (std::size_t q = 0; q < p; ++q) {
      if (!needed[q] && !box[q].empty() && meet(box[q], box[p])) needed[q] = 1;
    }
  }
  std::vector<std::uint8_t> keep(m.face_count());
  for (std::size_t f = 0; f < m.face_count(); ++f) keep[f] = needed[m.face_patch[f]];
  return faces_kept(m, keep);
}

// The nearest point within `reach` of covered vertex v (patch p) on the border of the region the
// patches below p cover: on a lower patch's border edge, and on no other lower patch. Empty when
// there is none.
std::optional<Vec3d> nearest_exit(const SurfaceMesh& m, const Border& b, const SegmentGrid& grid,
                                  const HullQuery& query, Index v, PatchId p,
                                  std::span<const Index> star, double reach, double distance) {
  const Vec3d& x = m.positions[v];
  // q lies on a chord of a border, which strays from the surface by up to the tessellation
  // tolerance (as on_lower allows).
  const auto covered_by = [&](const Vec3d& q, PatchId first, PatchId last) {
    if (first >= last) return false;
    const ClosestPoint cp = query.closest_point_in_range(q, first, last, 20 * distance);
    return cp.valid() && cp.distance <= 3 * distance;
  };
  std::optional<Vec3d> best;
  double best_d = reach;
  Index best_edge = kInvalid;
  grid.for_each_near(x, reach, [&](Index e) {
    const BorderEdge& be = b.edges[e];
    if (be.patch >= p) return;
    const SegmentPoint sp = closest_on_segment(x, m.positions[be.v0], m.positions[be.v1]);
    if (sp.distance > best_d || (sp.distance == best_d && e > best_edge)) return;
    const Vec3d q = m.positions[be.v0] + sp.t * (m.positions[be.v1] - m.positions[be.v0]);
    if (covered_by(q, 0, be.patch) || covered_by(q, be.patch + 1, p)) return;
    // A lower border that runs along p's own border (the hull's outline, where both patches
    // end) is no cut: the region ends there for p as well.
    const Vec3d d = normalized(m.positions[be.v1] - m.positions[be.v0]);
    bool alongside = false;
    grid.for_each_near(q, 3 * distance, [&](Index o) {
      const BorderEdge& ob = b.edges[o];
      if (alongside || ob.patch != p) return;
      const Vec3d a = m.positions[ob.v0], c = m.positions[ob.v1];
      if (closest_on_segment(q, a, c).distance > 3 * distance) return;
      alongside = std::abs(dot(normalized(c - a), d)) > 0.9;
    });
    if (alongside) return;
    // The cut must run through what is left of p around v: q within one of v's faces.
    bool inside = false;
    for (Index f : star) {
      const Face& t = m.faces[f];
      const Vec3d a = m.positions[t[0]], e1 = m.positions[t[1]] - a, e2 = m.positions[t[2]] - a;
      const Vec3d n = cross(e1, e2);
      const double nn = dot(n, n);
      if (!(nn > 0)) continue;
      const Vec3d r = q - a;
      const double l1 = dot(cross(r, e2), n) / nn, l2 = dot(cross(e1, r), n) / nn;
      const double off = std::abs(dot(r, n)) / std::sqrt(nn);
      constexpr double kSlack = 1e-6;
      if (l1 >= -kSlack && l2 >= -kSlack && l1 + l2 <= 1 + kSlack && off <= 3 * distance) {
        inside = true;
        break;
      }
    }
    if (!inside) return;
    best_d = sp.distance;
    best_edge = e;
    best = q;
  });
  return best;
}

// Collapses each moved[i] into onto_vertex[i] (where valid) among the kept faces of one patch:
// the faces on their edge go, the others take the neighbour. Skipped where the two have a common
// neighbour off that edge (the collapse would pinch the patch).
void collapse_onto_neighbours(SurfaceMesh& m, std::span<const Index> patch_faces,
                              std::span<const Index> moved, std::span<const Index> onto_vertex,
                              std::vector<std::uint8_t>& keep, OverlapStats& stats) {
  if (std::all_of(onto_vertex.begin(), onto_vertex.end(), [](Index u) { return u == kInvalid; })) {
    return;
  }
  std::vector<std::pair<Index, Index>> vertex_face;  // (vertex, face) of kept faces, sorted
  for (Index f : patch_faces) {
    if (!keep[f]) continue;
    for (int c = 0; c < 3; ++c) vertex_face.push_back({m.faces[f][c], f});
  }
  std::sort(vertex_face.begin(), vertex_face.end());
  const auto faces_at = [&](Index v) {
    const auto lo =
        std::lower_bound(vertex_face.begin(), vertex_face.end(), std::pair{v, Index(0)});
    auto hi = lo;
    while (hi != vertex_face.end() && hi->first == v) ++hi;
    return std::span<const std::pair<Index, Index>>(vertex_face.data() + (lo - vertex_face.begin()),
                                                    std::size_t(hi - lo));
  };
  const auto neighbours = [&](Index v) {
    std::vector<Index> n;
    for (const auto& [_, f] : faces_at(v)) {
      for (int c = 0; c < 3; ++c) {
        if (m.faces[f][c] != v) n.push_back(m.faces[f][c]);
      }
    }
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    return n;
  };
  // The face lists are of the patch before any collapse: a collapse next to an earlier one
  // waits (the vertex stays where it is).
  std::vector<Index> touched;
  const auto untouched = [&](Index v) {
    for (const auto& [_, f] : faces_at(v)) {
      if (std::binary_search(touched.begin(), touched.end(), f)) return false;
    }
    return true;
  };
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const Index v = moved[i], u = onto_vertex[i];
    if (u == kInvalid || !untouched(v) || !untouched(u)) continue;
    const std::vector<Index> nv = neighbours(v), nu = neighbours(u);
    std::vector<Index> common;
    std::set_intersection(nv.begin(), nv.end(), nu.begin(), nu.end(), std::back_inserter(common));
    std::vector<Index> on_edge, apexes;
    for (const auto& [_, f] : faces_at(v)) {
      const Face& t = m.faces[f];
      if (!keep[f] || (t[0] != u && t[1] != u && t[2] != u)) continue;
      on_edge.push_back(f);
      for (int c = 0; c < 3; ++c) {
        if (t[c] != u && t[c] != v) apexes.push_back(t[c]);
      }
    }
    std::sort(apexes.begin(), apexes.end());
    if (on_edge.empty() || apexes != common) continue;
    for (const auto& [_, f] : faces_at(v)) touched.push_back(f);
    for (const auto& [_, f] : faces_at(u)) touched.push_back(f);
    std::sort(touched.begin(), touched.end());
    for (const auto& [_, f] : faces_at(v)) {
      if (!keep[f]) continue;
      if (std::find(on_edge.begin(), on_edge.end(), f) != on_edge.end()) {
        keep[f] = 0;
        ++stats.triangles;
        stats.area += face_area(m.positions, m.faces[f]);
        continue;
      }
      for (int c = 0; c < 3; ++c) {
        if (m.faces[f][c] == v) m.faces[f][c] = u;
      }
    }
  }
}

}  // namespace

OverlapStats remove_overlaps(std::span<const Patch> patches, Work& w, const Border& b,
                             const MergeOptions& options, double length, Progress& progress) {
  OverlapStats stats;
  SurfaceMesh& m = w.mesh;
  const double distance = options.overlap_distance > 0 ? options.overlap_distance : 1e-4 * length;
  // Collect: seeds, checked on the NURBS in parallel (each writes its own slot).
  const SegmentGrid border_grid(m.positions, b.edges);
  const std::vector<Index> candidates = seed_candidates(m, b, border_grid, options, distance);
  if (candidates.empty()) return stats;
  // The seeds need only the faces around them; building a BVH over the whole hull would cost
  // more than the merge itself. Only when a seed is covered is a query built over the patches
  // that may lie under a patch with a covered seed, for growing the covered regions and cutting
  // them.
  std::vector<PatchId> seed_cover(candidates.size(), kInvalid);
  {
    const SurfaceMesh near = faces_near(m, candidates, patches.size(), 20 * distance);
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
  const HullQuery query(patches,
                        faces_under(m, candidates, seed_cover, patches.size(), 20 * distance));
  stats.changed = true;  // from here on faces may go and corners move

  // A border vertex on a border it shares with a lower patch (the two continue each other:
  // inward directions opposite) lies on that patch without overlapping it: no cut starts there
  // unless faces around it are covered. Along the hull's outline, where both patches end side by
  // side, a cut does start. Asked only of the few covered border vertices without a covered face.
  std::vector<Index> local(m.vertex_count(), kInvalid);  // mesh vertex -> border index
  for (std::size_t i = 0; i < b.vertices.size(); ++i) local[b.vertices[i]] = Index(i);
  const std::vector<Vec3d> inward = vertex_inward(m, b, local);
  const auto on_shared_border = [&](Index v) {
    const Vec3d& x = m.positions[v];
    double best = 3 * distance;
    Index best_edge = kInvalid;
    border_grid.for_each_near(x, best, [&](Index e) {
      const BorderEdge& be = b.edges[e];
      if (be.patch >= m.vertex_patch[v]) return;
      const double d = closest_on_segment(x, m.positions[be.v0], m.positions[be.v1]).distance;
      if (d < best || (d == best && e < best_edge)) {
        best = d;
        best_edge = e;
      }
    });
    return best_edge != kInvalid && dot(edge_inward(m, b.edges[best_edge]), inward[local[v]]) < 0;
  };

  // Grow the covered region of each patch from its seeds across its own edges (breadth-first,
  // ring by ring: each ring is checked in parallel and committed in order).
  // Neighbours by face edge, both ways (a border vertex's last neighbour follows it in no face),
  // as one array per vertex range: count -> exclusive scan -> fill in face order.
  std::vector<Index> ring_first(m.vertex_count() + 1, 0), ring;
  for (const Face& f : m.faces) {
    for (int c = 0; c < 3; ++c) ring_first[f[c] + 1] += 2;
  }
  for (std::size_t v = 0; v < m.vertex_count(); ++v) ring_first[v + 1] += ring_first[v];
  ring.resize(ring_first.back());
  {
    std::vector<Index> next(ring_first.begin(), ring_first.end() - 1);
    for (const Face& f : m.faces) {
      for (int c = 0; c < 3; ++c) {
        ring[next[f[c]]++] = f[(c + 1) % 3];
        ring[next[f[(c + 1) % 3]]++] = f[c];
      }
    }
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
      for (Index k = ring_first[v]; k < ring_first[v + 1]; ++k) {
        const Index u = ring[k];
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

  // Border neighbours of each border vertex (along its own patch's border).
  std::vector<std::vector<Index>> border_next(m.vertex_count());
  for (const BorderEdge& e : b.edges) {
    border_next[e.v0].push_back(e.v1);
    border_next[e.v1].push_back(e.v0);
  }

  // Which covered vertices are cut: strip_only marks the border vertices of an overlap narrower
  // than an edge.
  std::vector<std::uint8_t> strip_only(m.vertex_count(), 0);
  {
    // A face whose corners lie on different lower patches may span a gap between them: it is
    // covered only if its centroid is too. Where it is not, its corners stay.
    std::vector<std::uint8_t> spans_gap(m.face_count(), 0);
    parallel_for(0, m.face_count(), [&](std::size_t f) {
      const Face& t = m.faces[f];
      if (cover[t[0]] == kInvalid || cover[t[1]] == kInvalid || cover[t[2]] == kInvalid) return;
      if (cover[t[0]] == cover[t[1]] && cover[t[1]] == cover[t[2]]) return;
      const ClosestPoint cp = query.closest_point_in_range(face_centroid(m.positions, t), 0,
                                                           m.face_patch[f], 20 * distance);
      spans_gap[f] = !(cp.valid() && cp.distance <= 3 * distance);
    });
    for (std::size_t f = 0; f < m.face_count(); ++f) {
      if (!spans_gap[f]) continue;
      for (int c = 0; c < 3; ++c) cover[m.faces[f][c]] = kInvalid;
    }
    // An inner covered vertex that no fully covered face holds lies under a covered sliver one
    // edge wide (a thin strip lying on the patch); moving it would fold the faces on its two
    // sides over each other. It stays, and snapping handles the sliver. A covered vertex on the
    // patch's own border is where an overlap narrower than an edge begins: it moves inwards to
    // where the patch leaves the one below, which cuts the overlap away.
    std::vector<std::uint8_t> in_removed(m.vertex_count(), 0);
    for (const Face& t : m.faces) {
      if (cover[t[0]] != kInvalid && cover[t[1]] != kInvalid && cover[t[2]] != kInvalid) {
        for (int c = 0; c < 3; ++c) in_removed[t[c]] = 1;
      }
    }
    for (std::size_t v = 0; v < cover.size(); ++v) {
      if (in_removed[v] || cover[v] == kInvalid) continue;
      if (border_next[v].empty() || on_shared_border(Index(v))) {
        cover[v] = kInvalid;
      } else {
        strip_only[v] = 1;
      }
    }
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
    const auto slot = [&](Index v) {
      return std::size_t(std::lower_bound(moved.begin(), moved.end(), v) - moved.begin());
    };
    // Each moved corner goes to where its edges towards uncovered corners leave the covered
    // region (bisection on the exact surfaces of the patches below), the nearest such point:
    // that is the cut along the covering patches' border.
    // A corner on the patch's border (the hull's outline, say) leaves along that border, so
    // that the outline keeps its place. star: the faces that stay around each moved corner.
    std::vector<std::vector<Index>> out_to(moved.size()), star(moved.size());
    for (Index f : straddling) {
      const Face& t = m.faces[f];
      for (int c = 0; c < 3; ++c) {
        if (cover[t[c]] == kInvalid) continue;
        const std::size_t i = slot(t[c]);
        star[i].push_back(f);
        for (int d = 1; d < 3; ++d) {
          const Index u = t[(c + d) % 3];
          if (cover[u] == kInvalid) out_to[i].push_back(u);
        }
      }
    }
    std::vector<std::uint8_t> keeps_outline(moved.size(), 0);
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const auto& along = border_next[moved[i]];
      std::vector<Index> on_border;
      for (Index u : out_to[i]) {
        if (std::find(along.begin(), along.end(), u) != along.end()) on_border.push_back(u);
      }
      if (!along.empty() && !on_border.empty()) {
        out_to[i] = std::move(on_border);
        keeps_outline[i] = 1;
      }
    }
    const auto on_lower = [&](const Vec3d& x) {
      // The chord of an edge strays from the surface by up to the tessellation tolerance.
      const ClosestPoint cp = query.closest_point_in_range(x, 0, PatchId(p), 20 * distance);
      return cp.valid() && cp.distance <= 3 * distance;
    };
    std::vector<Vec3d> along_edge(moved.size()), onto_border(moved.size());
    std::vector<Index> onto_vertex(moved.size(), kInvalid);
    parallel_for(0, moved.size(), [&](std::size_t i) {
      const Vec3d from = m.positions[moved[i]];
      double best = std::numeric_limits<double>::infinity();
      along_edge[i] = from;
      double reach = 0, fraction = 1;
      Index toward = kInvalid;
      for (Index u : out_to[i]) {
        const Vec3d to = m.positions[u];
        reach = std::max(reach, norm(to - from));
        double lo = 0, hi = 1;  // covered at lo, not at hi
        for (int it = 0; it < 40 && (hi - lo) * norm(to - from) > 1e-3 * distance; ++it) {
          const double mid = 0.5 * (lo + hi);
          (on_lower(from + mid * (to - from)) ? lo : hi) = mid;
        }
        const Vec3d exit = from + lo * (to - from);
        const double d = norm(exit - from);
        if (d < best) {
          best = d;
          along_edge[i] = exit;
          fraction = lo;
          toward = u;
        }
      }
      // An outline vertex whose border does not leave the patches below before its neighbour
      // would land on that neighbour: it collapses into it instead (below).
      if (keeps_outline[i] && fraction > 0.99) {
        onto_vertex[i] = toward;
        along_edge[i] = onto_border[i] = from;
        return;
      }
      onto_border[i] = keeps_outline[i] ? along_edge[i]
                                        : nearest_exit(m, b, border_grid, query, moved[i],
                                                       PatchId(p), star[i], reach, distance)
                                              .value_or(along_edge[i]);
    });
    // The nearest point of the covering border is the cut itself, also where the overlap is
    // narrower than an edge and no edge leaves the patches below near it. A face it would turn
    // over takes the exits along its edges instead.
    std::vector<Vec3d> target = onto_border;
    for (Index f : straddling) {
      const Face& t = m.faces[f];
      std::array<Vec3d, 3> x;
      for (int c = 0; c < 3; ++c) {
        x[c] = cover[t[c]] != kInvalid ? target[slot(t[c])] : m.positions[t[c]];
      }
      const Vec3d before_n =
          cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
      if (dot(cross(x[1] - x[0], x[2] - x[0]), before_n) > 0) continue;
      for (int c = 0; c < 3; ++c) {
        if (cover[t[c]] != kInvalid) target[slot(t[c])] = along_edge[slot(t[c])];
      }
    }
    // An overlap this narrow is a gap of the other sign: snapping closes it as it closes gaps,
    // and a cut would leave edges a fraction of their length.
    for (std::size_t i = 0; i < moved.size(); ++i) {
      const Index v = moved[i];
      if (!strip_only[v]) continue;
      const auto at = std::lower_bound(b.vertices.begin(), b.vertices.end(), v);
      const double edge = b.edge_length[std::size_t(at - b.vertices.begin())];
      if (norm(target[i] - m.positions[v]) < kNarrowShare * edge) target[i] = m.positions[v];
    }
    for (std::size_t i = 0; i < moved.size(); ++i) m.positions[moved[i]] = target[i];
    collapse_onto_neighbours(m, faces_of[p], moved, onto_vertex, keep, stats);
    double after = 0;
    for (Index f : straddling) after += face_area(m.positions, m.faces[f]);
    stats.area += before - after;
  }

  compact_faces(w, keep);
  return stats;
}

}  // namespace hm::merge
