// Overlaps: where patches cover the same stretch of surface, the lowest-numbered patch keeps it
// and the others are cut away along the border of the patches below them, so that
// snap_borders can stitch them there.
//
// collect seeds (border vertices lying on a lower-numbered patch, checked on the NURBS through
// the Embree closest-point query) -> grow the covered region over each patch -> insert the lower
// patches' corners into the edges the cut crosses -> split the edges that leave the patches
// below between two covered corners -> cut every face along the border
// of the patches below (marching triangles: each edge from a covered corner to an uncovered one
// is cut where it leaves them, found by bisection on their exact surfaces) and keep the part
// outside. An overlap narrower than an edge covers only border vertices; their edges are cut
// the same way. Corners never move.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/bbox.h"
#include "core/parallel.h"
#include "query/hull_query.h"
#include "unstructured/merge_border.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {
namespace {

// Seed grid cells of this many median border edges: a seed's ball (half a border edge) then
// meets one or two cells along each axis, and the entries' ball test drops the rest.
constexpr double kSeedGridMedianEdges = 2;

// Normals of coincident layers agree to this (either orientation: patches may arrive flipped).
constexpr double kMinNormalCos = 0.866;  // 30 degrees
// The normal beside a point, either side of a knot line through it: this share of the domain
// away.
constexpr double kBeside = 1e-6;

// A cut this close to a corner, as a share of its edge, is no cut: the corner lies on the
// border of the patches below and moves onto it (the snap closes the rest, as it closes a gap),
// and a cut there would leave a sliver.
constexpr double kOnBorder = 0.15;

// A point of an edge is on the patches below when it lies past none of their borders by more
// than this share of the overlap distance.
constexpr double kPastBorder = 0.1;

// A corner against the region the patches below its own cover.
enum class Side : std::int8_t { kIn, kOn, kOut };

// An edge from a covered corner to an uncovered one, and where it leaves the patches below: the
// covered share of the edge, from `in`.
struct EdgeCut {
  Index in = kInvalid, out = kInvalid;
  double t = 0;
};
std::uint64_t edge_key(Index u, Index v) {
  return (std::uint64_t{std::min(u, v)} << 32) | std::max(u, v);
}
bool edge_cut_less(const EdgeCut& a, const EdgeCut& b) {
  return a.in != b.in ? a.in < b.in : a.out < b.out;
}

// How a covering layer's normal runs against the covered vertex's: either way is asked of a
// seed (patches may arrive flipped); a covered region grows only over layers that run the way
// its seed's did.
enum class Way : std::int8_t { kEither = 0, kSame = 1, kOpposite = -1 };

// The patches with the side of su x sv their outside lies on (+1 or -1; none given: as each
// patch's own flag says, -1 where it is `reversed`). A layer is compared by its outward normal
// where that is known: a patch that arrived flipped under one that did not is then covered the
// same way as its neighbours are. Compared by su x sv, the way asked along a covered region
// changed where it passed from a flipped patch below onto an unflipped one, and the growth
// stopped there (generated Wigley hull, 100 patches, 5% overlaps, every third patch flipped: a
// corner of patch 39 stayed over patch 6, and the snap folded it).
struct Layers {
  std::span<const Patch> patches;
  std::span<const double> outward_sign;
  double sign(PatchId p) const {
    if (!outward_sign.empty()) return outward_sign[p];
    return patches[p].reversed ? -1.0 : 1.0;
  }
  Vec3d normal_at(PatchId p, double u, double v) const {
    return sign(p) * normal(patches[p].surface, u, v);
  }
  // A closest point's normal, which the query turns by the patch's own flag, turned as
  // normal_at turns the patch's su x sv. (Until 2026-12-07 the first merge set the vertex's
  // plain su x sv against the query's flag-turned normal, and the second turned the query's
  // normal by sign(p) on top of the flag. kcs.iges flags 22 patches reversed: a seed on its
  // patch 15 over patch 2 was found covered the opposite way, and the whole merge ran twice.)
  Vec3d query_normal(const ClosestPoint& cp) const {
    const double flag = patches[cp.patch].reversed ? -1.0 : 1.0;
    return (sign(cp.patch) * flag) * cp.normal;
  }
};

// How n agrees with the normal of the closest point cp, or with the normal just beside it on
// its patch (kEither: not at all, or not the way asked): on a knuckle inside a patch (a chine at
// a repeated knot) the normal at cp is one side's, and n, a knuckle vertex's own, may be the
// other's (property seed 1536: the chine vertices of an overlapping patch were left uncovered,
// and the faces between them stayed over the patch below).
Way normal_agrees(const Layers& layers, const ClosestPoint& cp, const Vec3d& n, Way asked) {
  const auto agrees = [&](const Vec3d& other) {
    const double c = dot(n, other);
    if (asked != Way::kOpposite && c >= kMinNormalCos) return Way::kSame;
    if (asked != Way::kSame && -c >= kMinNormalCos) return Way::kOpposite;
    return Way::kEither;
  };
  if (const Way w = agrees(layers.query_normal(cp)); w != Way::kEither) return w;
  const NurbsSurface& s = layers.patches[cp.patch].surface;
  const double du = kBeside * (s.u1 - s.u0), dv = kBeside * (s.v1 - s.v0);
  for (const Vec2d d : {Vec2d{du, 0}, Vec2d{-du, 0}, Vec2d{0, dv}, Vec2d{0, -dv}}) {
    const double u = std::clamp(cp.uv.x + d.x, s.u0, s.u1);
    const double v = std::clamp(cp.uv.y + d.y, s.v0, s.v1);
    if (const Way w = agrees(layers.normal_at(cp.patch, u, v)); w != Way::kEither) return w;
  }
  return Way::kEither;
}

// A patch below that covers a vertex, and the way its normal runs against the vertex's.
struct Cover {
  PatchId patch = kInvalid;
  Way way = Way::kEither;
};

// The closest point of x within `limit` on the patches first <= q < last whose normal agrees
// with n the way asked, with the way it does, or an invalid point. At a knuckle the nearest of
// them may be the patch across it, as near as the one x lies on: that one is searched around,
// twice at most.
std::pair<ClosestPoint, Way> closest_alike(const HullQuery& q, const Layers& layers, const Vec3d& x,
                                           const Vec3d& n, Way asked, PatchId first, PatchId last,
                                           double limit, int depth = 2) {
  if (first >= last) return {};
  // The triangles stray from the surface by up to the chord tolerance: search them wider than
  // the distance asked of the exact surfaces.
  const ClosestPoint cp = q.closest_point_in_range(x, first, last, 20 * limit);
  if (!cp.valid() || !(cp.distance <= limit)) return {};
  if (const Way w = normal_agrees(layers, cp, n, asked); w != Way::kEither) return {cp, w};
  if (depth == 0) return {};
  const auto below = closest_alike(q, layers, x, n, asked, first, cp.patch, limit, depth - 1);
  const auto above = closest_alike(q, layers, x, n, asked, cp.patch + 1, last, limit, depth - 1);
  if (!below.first.valid()) return above;
  if (!above.first.valid()) return below;
  return above.first.distance < below.first.distance ? above : below;
}

// The nearest patch below the vertex's own whose surface the vertex lies on with an agreeing
// normal, or kInvalid. (Its own normal at a domain border once came out as noise, property seed
// 4877: the knot span there was 1.1e-16 wide; the kernel's find_span now steps over such spans.)
Cover covering_patch(const HullQuery& q, const Layers& layers, const SurfaceMesh& m, Index v,
                     double distance, Way asked) {
  const PatchId own = m.vertex_patch[v];
  if (own == 0) return {};
  const Vec2d uv = m.vertex_uv[v];
  const Vec3d n = layers.normal_at(own, uv.x, uv.y);
  const auto [cp, way] = closest_alike(q, layers, m.positions[v], n, asked, 0, own, distance);
  return {cp.patch, way};
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
    grid.for_each_within(p, tol[i], [&](Index e) {
      const BorderEdge& be = b.edges[e];
      if (be.patch == m.vertex_patch[v] || !grid.may_be_within(e, p, best)) return;
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

// Longest edge of m's faces, m: the longest of each block of faces (each block its own slot),
// then of those. A maximum is exact, so the blocks do not change it.
double longest_edge(const SurfaceMesh& m) {
  constexpr std::size_t kBlock = 4096;
  std::vector<double> longest((m.face_count() + kBlock - 1) / kBlock, 0.0);
  parallel_for(
      0, longest.size(),
      [&](std::size_t b) {
        const std::size_t end = std::min(m.face_count(), (b + 1) * kBlock);
        for (std::size_t f = b * kBlock; f < end; ++f) {
          const Face& t = m.faces[f];
          for (int k = 0; k < 3; ++k) {
            longest[b] =
                std::max(longest[b], norm(m.positions[t[(k + 1) % 3]] - m.positions[t[k]]));
          }
        }
      },
      1, 2);
  return longest.empty() ? 0.0 : *std::max_element(longest.begin(), longest.end());
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
    // Each candidate as the diagonal of the box a face's reach can come from (its longest edge
    // plus the margin, at most `widest`): a face then looks only at the one cell its centroid
    // lies in, and most cells are empty. Until 2026-12-06 each face asked for the cells about
    // it, and on ship_449 at 470,000 triangles (2,504 candidates, 262,000 faces asked) that was
    // a tenth of the merge.
    const double widest = longest_edge(m) + margin;
    std::vector<Vec3d> ends(2 * candidates.size());
    std::vector<BorderEdge> boxes(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      const Vec3d& p = m.positions[candidates[i]];
      // Grown by 1e-9 of the reach and of the coordinates, far above the rounding of the
      // corners and of the distance, so that no centroid within reach falls outside.
      const double grown =
          widest + 1e-9 * (widest + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
      ends[2 * i] = p - Vec3d{grown, grown, grown};
      ends[2 * i + 1] = p + Vec3d{grown, grown, grown};
      boxes[i] = {Index(2 * i), Index(2 * i + 1), kInvalid, m.vertex_patch[candidates[i]]};
    }
    const SegmentGrid grid(ends, boxes, widest, 0);
    parallel_for(0, m.face_count(), [&](std::size_t f) {
      if (!keep[f]) return;
      const Face& t = m.faces[f];
      const Vec3d c = face_centroid(m.positions, t);
      double r = -1;  // the face's reach, once a candidate's box holds its centroid
      bool close = false;
      grid.for_each_near(c, 0, [&](Index i) {
        if (close || !(boxes[i].patch > m.face_patch[f])) return;
        if (r < 0) {
          double edge = 0;
          for (int k = 0; k < 3; ++k) {
            edge = std::max(edge, norm(m.positions[t[(k + 1) % 3]] - m.positions[t[k]]));
          }
          r = edge + margin;
        }
        close = norm(m.positions[candidates[i]] - c) <= r;
      });
      keep[f] = close;
    });
  }
  return faces_kept(m, keep);
}

// The faces that may cover any vertex of a patch with a covered seed (the covered regions grow
// over those patches only): faces of lower-numbered patches whose bounding box, grown by
// `margin` (the reach of every search made with them), meets that patch's. Taking whole patches
// instead gave kcs a query over 10,000 faces for two covered seeds. Vertices are kept as they
// are.
SurfaceMesh faces_under(const SurfaceMesh& m, std::span<const Index> candidates,
                        std::span<const Cover> seed_cover, std::size_t patch_count, double margin) {
  const std::vector<BBox3d> box = patch_boxes(m, patch_count, margin);
  std::vector<std::uint8_t> grows(patch_count, 0);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (seed_cover[i].patch != kInvalid) grows[m.vertex_patch[candidates[i]]] = 1;
  }
  std::vector<PatchId> growing;  // ascending
  for (std::size_t p = 0; p < patch_count; ++p) {
    if (grows[p] && !box[p].empty()) growing.push_back(PatchId(p));
  }
  std::vector<std::uint8_t> keep(m.face_count(), 0);
  parallel_for(0, m.face_count(), [&](std::size_t f) {
    const PatchId q = m.face_patch[f];
    BBox3d fb;
    for (int k = 0; k < 3; ++k) fb.add(m.positions[m.faces[f][k]]);
    for (auto it = std::upper_bound(growing.begin(), growing.end(), q); it != growing.end(); ++it) {
      if (fb.meets(box[*it])) {
        keep[f] = 1;
        return;
      }
    }
  });
  return faces_kept(m, keep);
}

// Appends the point at share t of edge a -> e (one patch's vertices) as a new vertex of w: on
// the chord, (u, v) interpolated, mapped back to the nearer end. Returns its index.
Index add_edge_point(Work& w, Index a, Index e, double t) {
  SurfaceMesh& m = w.mesh;
  const Index v = Index(m.vertex_count());
  m.positions.push_back(m.positions[a] + t * (m.positions[e] - m.positions[a]));
  m.vertex_patch.push_back(m.vertex_patch[a]);
  m.vertex_uv.push_back(m.vertex_uv[a] + t * (m.vertex_uv[e] - m.vertex_uv[a]));
  w.vert_old.push_back(w.vert_old[t <= 0.5 ? a : e]);
  return v;
}

// Splits every face at the new vertices on its edges (mid_of(a, e): the vertex on edge a-e, or
// kInvalid): one, two or three split edges give two, three or four triangles. Only faces with a
// covered corner are looked at: every split edge has a covered end (most faces have none, and the
// searches cost 3 ms over kcs's 41,000 faces). Faces keep their provenance; new pieces go last.
template <class MidOf>
void split_faces_at(Work& w, std::span<const PatchId> cover, const MidOf& mid_of) {
  SurfaceMesh& m = w.mesh;
  const std::size_t faces = m.face_count();
  for (std::size_t f = 0; f < faces; ++f) {
    const Face t = m.faces[f];
    if (cover[t[0]] == kInvalid && cover[t[1]] == kInvalid && cover[t[2]] == kInvalid) continue;
    std::array<Index, 3> e;  // the new vertex on edge t[c] -> t[c + 1], or kInvalid
    int n = 0;
    for (int c = 0; c < 3; ++c) n += (e[c] = mid_of(t[c], t[(c + 1) % 3])) != kInvalid;
    if (n == 0) continue;
    std::vector<Face> pieces;
    if (n == 3) {
      pieces = {{t[0], e[0], e[2], kInvalid},
                {e[0], t[1], e[1], kInvalid},
                {e[2], e[1], t[2], kInvalid},
                {e[0], e[1], e[2], kInvalid}};
    } else {
      // Rotate so that the split edges come first: 0 (and 1 when two are split).
      int r = 0;
      while (!(e[r] != kInvalid && (n == 1 || e[(r + 1) % 3] != kInvalid))) ++r;
      const Index a = t[r], b = t[(r + 1) % 3], c = t[(r + 2) % 3];
      const Index ab = e[r], bc = e[(r + 1) % 3];
      if (n == 1) {
        pieces = {{a, ab, c, kInvalid}, {ab, b, c, kInvalid}};
      } else {
        pieces = {{ab, b, bc, kInvalid}, {a, ab, bc, kInvalid}, {a, bc, c, kInvalid}};
      }
    }
    m.faces[f] = pieces[0];
    for (std::size_t k = 1; k < pieces.size(); ++k) {
      m.faces.push_back(pieces[k]);
      m.face_patch.push_back(m.face_patch[f]);
      w.face_old.push_back(w.face_old[f]);
    }
  }
}

// Splits every edge between corners covered by different lower patches at the first of its
// points at 1/2, 1/4 and 3/4 that is on none of them (on_lower(x, patch) false), and the faces
// on it (split_faces_at). The new vertices are uncovered.
template <class OnLower>
void split_edges_off(Work& w, std::vector<PatchId>& cover, const OnLower& on_lower) {
  SurfaceMesh& m = w.mesh;
  std::vector<std::pair<Index, Index>> edges;  // (lower, higher) vertex
  for (const Face& t : m.faces) {
    for (int c = 0; c < 3; ++c) {
      const Index a = t[c], e = t[(c + 1) % 3];
      if (cover[a] == kInvalid || cover[e] == kInvalid || cover[a] == cover[e]) continue;
      edges.push_back({std::min(a, e), std::max(a, e)});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  if (edges.empty()) return;
  std::vector<double> at(edges.size(), -1);  // where the edge is split, or -1
  parallel_for(0, edges.size(), [&](std::size_t i) {
    const Vec3d a = m.positions[edges[i].first], e = m.positions[edges[i].second];
    for (double t : {0.5, 0.25, 0.75}) {
      if (!on_lower(a + t * (e - a), m.vertex_patch[edges[i].first])) {
        at[i] = t;
        return;
      }
    }
  });
  if (std::all_of(at.begin(), at.end(), [](double t) { return t < 0; })) return;
  std::vector<Index> mid(edges.size(), kInvalid);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (at[i] < 0) continue;
    mid[i] = add_edge_point(w, edges[i].first, edges[i].second, at[i]);
    cover.push_back(kInvalid);
  }
  const auto mid_of = [&](Index a, Index e) {
    const std::pair<Index, Index> k{std::min(a, e), std::max(a, e)};
    const auto it = std::lower_bound(edges.begin(), edges.end(), k);
    return it != edges.end() && *it == k ? mid[std::size_t(it - edges.begin())] : kInvalid;
  };
  split_faces_at(w, cover, mid_of);
}

// Corners of the patches below (their border turns by more than this there) are inserted into
// the edges the cut crosses; see insert_lower_corners.
constexpr double kCornerCos = 0.866;  // 30 degrees
// A corner lies on a face's edge when its barycentric coordinate across that edge is within this
// (either side) and the other two are not.
constexpr double kOnEdge = 0.05;

// The cut runs straight between the points where a face's edges leave the patches below. Where a
// corner of a patch below lies on such an edge, between its covered and its uncovered end, the
// straight cut passes it by and keeps the piece of that patch beyond the corner doubled. This is
// gaps and overlaps together: the upper patch's border runs a little outside the lower one's, its
// covered border vertex then counts as on the lower border (its border edge leaves at once), and
// the faces round it keep a chord across the lower patch's corner. Each such corner (of a patch
// numbered below the edge's, within three overlap distances of the face's plane, further than
// kOnBorder of the edge from either end, where the cut's own rule turns already) is inserted into
// the edge as a new vertex covered by its patch, splitting the faces on that edge, so that the
// cut turns there. An edge takes the lowest-numbered such corner. Returns the corners inserted.
// Inserting corners inside faces too was tried: it left as many merges broken as it mended.
std::size_t insert_lower_corners(Work& w, const Border& b, std::vector<PatchId>& cover,
                                 double distance) {
  SurfaceMesh& m = w.mesh;
  // Collect: border vertices where their patch's border turns (one edge in, one out).
  const std::size_t nv = m.vertex_count();
  std::vector<Vec3d> in_dir(nv), out_dir(nv);
  std::vector<std::uint8_t> ins(nv, 0), outs(nv, 0);
  for (const BorderEdge& e : b.edges) {
    const Vec3d d = m.positions[e.v1] - m.positions[e.v0];
    in_dir[e.v1] = d;
    out_dir[e.v0] = d;
    ins[e.v1] += ins[e.v1] < 2;
    outs[e.v0] += outs[e.v0] < 2;
  }
  std::vector<BorderEdge> corners;  // as points: v0 == v1
  for (Index v : b.vertices) {
    if (ins[v] != 1 || outs[v] != 1) continue;
    const double li = norm(in_dir[v]), lo = norm(out_dir[v]);
    if (!(li > 0 && lo > 0) || dot(in_dir[v], out_dir[v]) >= kCornerCos * li * lo) continue;
    corners.push_back({v, v, kInvalid, m.vertex_patch[v]});
  }
  if (corners.empty()) return 0;
  // Score: per crossed face (a covered corner and an uncovered one), the lowest-numbered corner of
  // a patch below on one of its edges, as (edge key, corner).
  const std::size_t nf = m.face_count();
  std::vector<std::pair<std::uint64_t, Index>> found(nf, {0, kInvalid});
  const SegmentGrid grid(m.positions, corners, longest_edge(m) + distance);
  parallel_for(0, nf, [&](std::size_t f) {
    const Face& t = m.faces[f];
    int covered = 0;
    for (int c = 0; c < 3; ++c) covered += cover[t[c]] != kInvalid;
    if (covered == 0 || covered == 3) return;
    const Vec3d &p0 = m.positions[t[0]], &p1 = m.positions[t[1]], &p2 = m.positions[t[2]];
    const Vec3d n = cross(p1 - p0, p2 - p0);
    const double n2 = squared_norm(n);
    if (!(n2 > 0)) return;
    const Vec3d centre = (p0 + p1 + p2) / 3.0;
    double reach = distance;
    for (int c = 0; c < 3; ++c) reach = std::max(reach, norm(m.positions[t[c]] - centre));
    std::pair<std::uint64_t, Index> best{0, kInvalid};
    grid.for_each_near(centre, reach + distance, [&](Index i) {
      const Index c = corners[i].v0;
      if (corners[i].patch >= m.face_patch[f] || (best.second != kInvalid && c >= best.second))
        return;
      const Vec3d x = m.positions[c];
      if (std::abs(dot(x - p0, n)) > 3 * distance * std::sqrt(n2)) return;
      // Barycentric coordinates of x's projection onto the face's plane: the edge is the one
      // opposite the smallest.
      const std::array<double, 3> l = {dot(cross(p2 - p1, x - p1), n) / n2,
                                       dot(cross(p0 - p2, x - p2), n) / n2,
                                       dot(cross(p1 - p0, x - p0), n) / n2};
      const int k = int(std::min_element(l.begin(), l.end()) - l.begin());
      if (std::abs(l[k]) > kOnEdge || l[(k + 1) % 3] < kOnEdge || l[(k + 2) % 3] < kOnEdge) return;
      // Edge t[k + 1] -> t[k + 2], opposite t[k]; near either end the cut turns there already.
      const Index a = t[(k + 1) % 3], e = t[(k + 2) % 3];
      if ((cover[a] == kInvalid) == (cover[e] == kInvalid)) return;
      const Vec3d &pa = m.positions[a], &pe = m.positions[e];
      const double s = dot(x - pa, pe - pa) / squared_norm(pe - pa);
      if (s < kOnBorder || s > 1 - kOnBorder) return;
      best = {edge_key(a, e), c};
    });
    found[f] = best;
  });
  // Select: each edge once, with the lowest-numbered corner any of its faces found.
  std::vector<std::pair<std::uint64_t, Index>> split;
  for (const auto& fc : found) {
    if (fc.second != kInvalid) split.push_back(fc);
  }
  std::sort(split.begin(), split.end());
  split.erase(std::unique(split.begin(), split.end(),
                          [](const auto& x, const auto& y) { return x.first == y.first; }),
              split.end());
  if (split.empty()) return 0;
  // Apply: a new vertex per edge (in key order) where the corner projects onto it, then the faces
  // on the split edges.
  std::vector<Index> split_vertex(split.size());
  for (std::size_t i = 0; i < split.size(); ++i) {
    const Index a = Index(split[i].first >> 32), e = Index(split[i].first & 0xffffffffu);
    const Vec3d pa = m.positions[a], pe = m.positions[e], x = m.positions[split[i].second];
    split_vertex[i] = add_edge_point(w, a, e, dot(x - pa, pe - pa) / squared_norm(pe - pa));
    cover.push_back(m.vertex_patch[split[i].second]);
  }
  const auto split_of = [&](Index a, Index e) {
    const std::uint64_t k = edge_key(a, e);
    const auto it =
        std::lower_bound(split.begin(), split.end(), std::pair<std::uint64_t, Index>{k, 0});
    return it != split.end() && it->first == k ? split_vertex[std::size_t(it - split.begin())]
                                               : kInvalid;
  };
  split_faces_at(w, cover, split_of);
  return split.size();
}

// Grows the covered region of each patch from its covered seeds across its own edges
// (breadth-first, ring by ring: each ring is checked in parallel and committed in order), over
// layers whose normals run against the vertices' the way the seed's did: where a full hull's
// two halves meet at a knife edge (a Wigley hull's bow and keel), each half lies within the
// overlap distance of the other with its normal opposite, and a region grown from a true overlap
// of one half's patches spread into the other half and cut away the strip along the keel
// (generated Wigley hull, 100 patches, 5% overlaps). A vertex is reached first from the first
// frontier vertex in ring order, and takes the way asked of it there.
// Returns the covering patch per vertex (kInvalid: uncovered), or nothing when cancelled.
std::vector<PatchId> grow_cover(const SurfaceMesh& m, const Layers& layers, const HullQuery& query,
                                std::span<const Index> candidates,
                                std::span<const Cover> seed_cover, double distance,
                                Progress& progress) {
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
  std::vector<Way> way(m.vertex_count(), Way::kEither);
  std::vector<std::uint8_t> checked(m.vertex_count(), 0);
  std::vector<Index> frontier;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const Index v = candidates[i];
    checked[v] = 1;
    if (seed_cover[i].patch != kInvalid) {
      cover[v] = seed_cover[i].patch;
      way[v] = seed_cover[i].way;
      frontier.push_back(v);
    }
  }
  while (!frontier.empty()) {
    std::vector<Index> next;
    std::vector<Way> asked;
    for (Index v : frontier) {
      for (Index k = ring_first[v]; k < ring_first[v + 1]; ++k) {
        const Index u = ring[k];
        if (!checked[u]) {
          checked[u] = 1;
          next.push_back(u);
          asked.push_back(way[v]);
        }
      }
    }
    std::vector<Cover> found(next.size());
    parallel_for(0, next.size(), [&](std::size_t i) {
      found[i] = covering_patch(query, layers, m, next[i], distance, asked[i]);
    });
    frontier.clear();
    for (std::size_t i = 0; i < next.size(); ++i) {
      if (found[i].patch == kInvalid) continue;
      cover[next[i]] = found[i].patch;
      way[next[i]] = found[i].way;
      frontier.push_back(next[i]);
    }
    if (progress.cancelled()) return {};
  }

  return cover;
}

// Moves each corner that counts as on the border of the patches below (side kOn) to the nearest
// of the exits that made it so, by under kOnBorder of an edge: the snap then has only the
// other border to meet, not an overlap or a gap of its own as well. A corner on its patch's
// border takes only exits along that border, so that the outline keeps its place. A move that
// would turn a face around the corner over is not made (moves are tried in vertex order).
void move_onto_border(Work& w, const Border& b, std::span<const EdgeCut> cuts,
                      std::span<const Side> side) {
  SurfaceMesh& m = w.mesh;
  std::vector<std::uint64_t> border_keys(b.edges.size());
  for (std::size_t e = 0; e < b.edges.size(); ++e) {
    border_keys[e] = edge_key(b.edges[e].v0, b.edges[e].v1);
  }
  std::sort(border_keys.begin(), border_keys.end());
  const auto along_border = [&](Index u, Index v) {
    const bool on = std::binary_search(b.vertices.begin(), b.vertices.end(), u);
    return !on || std::binary_search(border_keys.begin(), border_keys.end(), edge_key(u, v));
  };
  // Per corner: how far its nearest such exit is, and where (infinity: no move).
  std::vector<double> best(m.vertex_count(), std::numeric_limits<double>::infinity());
  std::vector<Vec3d> onto(m.vertex_count());
  const auto offer = [&](Index v, Index other, double d, const Vec3d& x) {
    if (side[v] != Side::kOn || !along_border(v, other) || !(d < best[v])) return;
    best[v] = d;
    onto[v] = x;
  };
  for (const EdgeCut& c : cuts) {
    const Vec3d a = m.positions[c.in], e = m.positions[c.out];
    const Vec3d x = a + c.t * (e - a);
    const double len = norm(e - a);
    if (c.t < kOnBorder) offer(c.in, c.out, c.t * len, x);
    if (c.t > 1 - kOnBorder) offer(c.out, c.in, (1 - c.t) * len, x);
  }
  const auto moves = [&](Index v) { return best[v] < std::numeric_limits<double>::infinity(); };
  std::vector<std::pair<Index, Index>> corner_face;  // (corner, face), sorted
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    for (int c = 0; c < 3; ++c) {
      if (moves(m.faces[f][c])) corner_face.push_back({m.faces[f][c], Index(f)});
    }
  }
  if (corner_face.empty()) return;
  std::sort(corner_face.begin(), corner_face.end());
  const auto normal_of = [&](const Face& t) {
    return cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
  };
  for (auto lo = corner_face.begin(); lo != corner_face.end();) {
    const Index v = lo->first;
    std::vector<Vec3d> before;
    for (auto it = lo; it != corner_face.end() && it->first == v; ++it) {
      before.push_back(normal_of(m.faces[it->second]));
    }
    const Vec3d from = m.positions[v];
    m.positions[v] = onto[v];
    auto it = lo;
    for (std::size_t k = 0; it != corner_face.end() && it->first == v; ++it, ++k) {
      if (!(dot(normal_of(m.faces[it->second]), before[k]) > 0)) m.positions[v] = from;
    }
    lo = it;
  }
}

// Cuts every face along the border of the patches below its own (marching triangles): an edge
// from a covered corner to an uncovered one is cut where it leaves them, and each face keeps
// its part outside them. Corners never move, so no face turns over.
template <class OnLower>
void cut_faces(Work& w, const Border& b, std::span<const PatchId> cover, const OnLower& on_lower,
               double distance, OverlapStats& stats) {
  SurfaceMesh& m = w.mesh;
  // Score: where each edge from a covered corner to an uncovered one leaves the patches below
  // (bisection on their exact surfaces), as the share of the edge from its covered end.
  std::vector<EdgeCut> cuts;
  for (const Face& t : m.faces) {
    for (int c = 0; c < 3; ++c) {
      const Index a = t[c], e = t[(c + 1) % 3];
      if ((cover[a] == kInvalid) == (cover[e] == kInvalid)) continue;
      cuts.push_back(cover[a] != kInvalid ? EdgeCut{a, e} : EdgeCut{e, a});
    }
  }
  std::sort(cuts.begin(), cuts.end(), edge_cut_less);
  cuts.erase(std::unique(
                 cuts.begin(), cuts.end(),
                 [](const EdgeCut& x, const EdgeCut& y) { return x.in == y.in && x.out == y.out; }),
             cuts.end());
  parallel_for(0, cuts.size(), [&](std::size_t i) {
    const Vec3d from = m.positions[cuts[i].in], to = m.positions[cuts[i].out];
    const PatchId p = m.vertex_patch[cuts[i].in];
    const double len = norm(to - from);
    double lo = 0, hi = 1;  // covered at lo, not at hi
    for (int it = 0; it < 40 && (hi - lo) * len > 1e-3 * distance; ++it) {
      const double mid = 0.5 * (lo + hi);
      (on_lower(from + mid * (to - from), p) ? lo : hi) = mid;
    }
    cuts[i].t = lo;
  });

  // Select: a corner within kOnBorder of an edge from where that edge leaves the patches below
  // lies on their border (the snap closes the rest); the cuts left run between corners inside
  // and outside, each a new vertex (in edge order).
  std::vector<Side> side(m.vertex_count(), Side::kOut);
  for (std::size_t v = 0; v < side.size(); ++v) {
    if (cover[v] != kInvalid) side[v] = Side::kIn;
  }
  for (const EdgeCut& c : cuts) {
    if (c.t < kOnBorder) side[c.in] = Side::kOn;
    if (c.t > 1 - kOnBorder) side[c.out] = Side::kOn;
  }
  move_onto_border(w, b, cuts, side);
  std::vector<Index> cut_vertex(cuts.size(), kInvalid);
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const EdgeCut& c = cuts[i];
    if (side[c.in] != Side::kIn || side[c.out] != Side::kOut) continue;
    cut_vertex[i] = add_edge_point(w, c.in, c.out, c.t);
  }
  const auto cut_on = [&](Index in, Index out) {
    const auto it = std::lower_bound(cuts.begin(), cuts.end(), EdgeCut{in, out}, edge_cut_less);
    return cut_vertex[std::size_t(it - cuts.begin())];
  };

  // Apply: each face keeps its part outside the patches below (Sutherland-Hodgman against the
  // cut), as one or two triangles; a face with every corner on the border stays if its centroid
  // is off them. Faces come out in input order, each piece with its face's provenance.
  std::vector<std::uint8_t> centroid_off(m.face_count(), 1);
  parallel_for(0, m.face_count(), [&](std::size_t f) {
    const Face& t = m.faces[f];
    if (side[t[0]] == Side::kOn && side[t[1]] == Side::kOn && side[t[2]] == Side::kOn) {
      centroid_off[f] = !on_lower(face_centroid(m.positions, t), m.face_patch[f]);
    }
  });
  std::vector<Face> faces;
  std::vector<PatchId> face_patch;
  std::vector<Index> face_old;
  faces.reserve(m.face_count());
  face_patch.reserve(m.face_count());
  face_old.reserve(m.face_count());
  const auto emit = [&](Index a, Index b, Index c, std::size_t f) {
    faces.push_back({a, b, c, kInvalid});
    face_patch.push_back(m.face_patch[f]);
    face_old.push_back(w.face_old[f]);
  };
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const Face t = m.faces[f];
    bool any_in = false, any_out = false;
    for (int c = 0; c < 3; ++c) {
      any_in |= side[t[c]] == Side::kIn;
      any_out |= side[t[c]] == Side::kOut;
    }
    if (!any_in && (any_out || centroid_off[f])) {
      emit(t[0], t[1], t[2], f);
      continue;
    }
    const double area = face_area(m.positions, t);
    if (!any_out) {
      ++stats.triangles;
      stats.area += area;
      continue;
    }
    std::array<Index, 4> poly;
    int n = 0;
    for (int c = 0; c < 3; ++c) {
      const Index a = t[c], e = t[(c + 1) % 3];
      if (side[a] != Side::kIn) poly[n++] = a;
      if (side[a] == Side::kIn && side[e] == Side::kOut) poly[n++] = cut_on(a, e);
      if (side[a] == Side::kOut && side[e] == Side::kIn) poly[n++] = cut_on(e, a);
    }
    const std::size_t first = faces.size();
    if (n == 3) {
      emit(poly[0], poly[1], poly[2], f);
    } else {
      // The shorter diagonal of the quadrilateral.
      const auto& x = m.positions;
      if (norm(x[poly[2]] - x[poly[0]]) <= norm(x[poly[3]] - x[poly[1]])) {
        emit(poly[0], poly[1], poly[2], f);
        emit(poly[0], poly[2], poly[3], f);
      } else {
        emit(poly[1], poly[2], poly[3], f);
        emit(poly[1], poly[3], poly[0], f);
      }
    }
    double kept = 0;
    for (std::size_t k = first; k < faces.size(); ++k) kept += face_area(m.positions, faces[k]);
    stats.area += area - kept;
  }
  m.faces = std::move(faces);
  m.face_patch = std::move(face_patch);
  w.face_old = std::move(face_old);
}

}  // namespace

OverlapStats remove_overlaps(std::span<const Patch> patches, Work& w, const Border& b,
                             const MergeOptions& options, double length,
                             std::span<const double> outward_sign, Progress& progress) {
  OverlapStats stats;
  const Layers layers{patches, outward_sign};
  SurfaceMesh& m = w.mesh;
  const double distance = options.overlap_distance > 0 ? options.overlap_distance : 1e-4 * length;
  // Collect: seeds, checked on the NURBS in parallel (each writes its own slot).
  const SegmentGrid border_grid(m.positions, b.edges, 0, kSeedGridMedianEdges);
  const std::vector<Index> candidates = seed_candidates(m, b, border_grid, options, distance);
  if (candidates.empty()) return stats;
  // The seeds need only the faces around them; building a BVH over the whole hull would cost
  // more than the merge itself. Only when a seed is covered is a query built over the patches
  // that may lie under a patch with a covered seed, for growing the covered regions and cutting
  // them.
  std::vector<Cover> seed_cover(candidates.size());
  {
    const SurfaceMesh near = faces_near(m, candidates, patches.size(), 20 * distance);
    if (near.faces.empty()) return stats;
    const HullQuery seed_query(patches, near);
    parallel_for(0, candidates.size(), [&](std::size_t i) {
      seed_cover[i] = covering_patch(seed_query, layers, m, candidates[i], distance, Way::kEither);
    });
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (seed_cover[i].way != Way::kOpposite) continue;
    stats.covered_opposite.push_back({m.vertex_patch[candidates[i]], seed_cover[i].patch});
  }
  auto& opposite = stats.covered_opposite;
  std::sort(opposite.begin(), opposite.end());
  opposite.erase(std::unique(opposite.begin(), opposite.end()), opposite.end());
  if (progress.cancelled()) return stats;
  if (std::all_of(seed_cover.begin(), seed_cover.end(),
                  [](const Cover& c) { return c.patch == kInvalid; })) {
    return stats;
  }
  const HullQuery query(patches,
                        faces_under(m, candidates, seed_cover, patches.size(), 20 * distance));
  stats.changed = true;  // from here on faces may be cut

  std::vector<PatchId> cover =
      grow_cover(m, layers, query, candidates, seed_cover, distance, progress);
  if (cover.empty()) return stats;

  const auto on_lower = [&](const Vec3d& x, PatchId p) {
    // The chord of an edge strays from the surface by up to the tessellation tolerance, so the
    // distance alone would count points up to that far past the border of the patches below as
    // on them. Inside a patch the closest point lies straight below x; past its border it is on
    // that border, off to the side by how far x is past it.
    const ClosestPoint cp = query.closest_point_in_range(x, 0, p, 20 * distance);
    if (!cp.valid() || !(cp.distance <= 3 * distance)) return false;
    if (!cp.on_surface) return true;
    const Vec3d d = x - cp.point;
    return norm(d - dot(d, cp.normal) * cp.normal) <= kPastBorder * distance;
  };
  // The corners of the lower patches on the edges the cut crosses become vertices, so that the
  // cut turns at them.
  insert_lower_corners(w, b, cover, distance);
  // An edge between corners on different lower patches may leave them on its way (across a
  // gap between them, or round the inner corner where they meet): it is split there, so that
  // the cut below can keep that part.
  split_edges_off(w, cover, on_lower);
  if (progress.cancelled()) return stats;

  cut_faces(w, b, cover, on_lower, distance, stats);
  return stats;
}

}  // namespace hm::merge
