// merge_patches: the driver. Each step is its own file (see merge_steps.h).
#include "unstructured/merge.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/bbox.h"
#include "core/error.h"
#include "mesh/adjacency.h"
#include "unstructured/merge_steps.h"

namespace hm {
namespace {

void check_input(std::span<const Patch> patches, const SurfaceMesh& t) {
  const std::size_t nv = t.vertex_count(), nf = t.face_count();
  if (t.vertex_patch.size() != nv || t.vertex_uv.size() != nv || t.face_patch.size() != nf) {
    throw GeometryError("merge: the triangulation lacks per-vertex patch/(u, v) or face patches");
  }
  for (std::size_t f = 0; f < nf; ++f) {
    if (!is_triangle(t.faces[f]))
      throw GeometryError("merge: face " + std::to_string(f) + " is not a triangle");
    if (t.face_patch[f] >= patches.size()) {
      throw GeometryError("merge: face " + std::to_string(f) + " names patch " +
                          std::to_string(t.face_patch[f]) + " of " +
                          std::to_string(patches.size()));
    }
    for (int c = 0; c < 3; ++c) {
      if (t.faces[f][c] >= nv)
        throw GeometryError("merge: face " + std::to_string(f) + " names a vertex out of range");
    }
  }
  for (std::size_t v = 0; v < nv; ++v) {
    if (t.vertex_patch[v] >= patches.size()) {
      throw GeometryError("merge: vertex " + std::to_string(v) + " names an unknown patch");
    }
  }
}

// Snapping is tried at most this many times more (see close_seams).
constexpr int kSnapRetries = 3;

// Closes the small holes the snap left (fill_small_holes), a few passes: holes that touch at a
// vertex chain as one loop until one of them is closed. `adj` is the mesh's adjacency on entry
// and is kept current. Returns the holes filled; left_open gets the edges of those it could not.
std::size_t fill_holes(merge::Work& w, EdgeAdjacency& adj, const MergeOptions& options,
                       double length, std::vector<std::array<Index, 2>>& left_open) {
  std::size_t total = 0;
  for (int pass = 0; pass < 3; ++pass) {
    const merge::HoleStats filled = merge::fill_small_holes(w, adj, options, &left_open);
    total += filled.filled;
    if (filled.filled == 0) break;
    if (filled.left_degenerate > 0) merge::drop_degenerate(w, length);
    adj = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  }
  return total;
}

// Snaps the borders, drops the degenerate faces, orients the faces and closes the small holes
// (`adj` gets the final adjacency; the loops must follow one winding to be closed against it).
// Then it looks for what a snap too wide made: edges with three faces or more, and small holes
// folded so that they cannot be closed. Two patches whose borders come within tolerance of each
// other across the tip of a third, narrower than that tolerance there (kcs.iges at 40,000
// triangles), weld straight across it, and the third patch's tip then lies on their seam. Two
// transom patches of the generated 1,000-patch round-bilge hull at 40,000 triangles snap so that
// one's vertex lies inside the other's face, which leaves a hole of four vertices whose both
// diagonals are edges. Where either is found, all steps run again from the same start with the
// tolerance halved at the border vertices near it. `start` is the mesh before the snap; `w` gets
// the result.
merge::SnapStats close_seams(std::span<const Patch> patches, const merge::Work& start,
                             merge::Work& w, const merge::Border& border,
                             const MergeOptions& options, double length, std::vector<double> scale,
                             MergeReport& r, EdgeAdjacency& adj) {
  w = start;
  std::vector<std::array<Index, 2>> trouble;
  // The best attempt so far, when a retry may have to be undone: fewest edges with three faces,
  // then fewest edges of holes left open. A retry for a fold must not make a non-manifold edge.
  struct Attempt {
    merge::Work w;
    EdgeAdjacency adj;
    merge::SnapStats stats;
    MergeReport report;
    std::pair<std::size_t, std::size_t> rank;
  };
  std::optional<Attempt> best;
  for (int attempt = 0;; ++attempt) {
    const merge::SnapStats s = merge::snap_borders(w, border, options, length, scale);
    r.degenerate_faces_dropped = merge::drop_degenerate(w, length);
    r.patches_flipped = merge::orient_faces(patches, w, adj);
    r.holes_filled = fill_holes(w, adj, options, length, trouble);
    const std::pair<std::size_t, std::size_t> rank{adj.nonmanifold_edges.size(), trouble.size()};
    for (Index e : adj.nonmanifold_edges) trouble.push_back({adj.edges[e].v0, adj.edges[e].v1});
    bool changed = false;
    if (attempt < kSnapRetries && !trouble.empty()) {
      for (std::size_t i = 0; i < border.vertices.size(); ++i) {
        const Vec3d& p = start.mesh.positions[border.vertices[i]];
        const double reach = 2 * merge::vertex_tolerance(options, border.edge_length[i]) * scale[i];
        for (const auto& [a, b] : trouble) {
          const merge::SegmentPoint sp =
              merge::closest_on_segment(p, w.mesh.positions[a], w.mesh.positions[b]);
          if (sp.distance <= reach) {
            scale[i] *= 0.5;
            changed = true;
            break;
          }
        }
      }
    }
    if (!changed) {
      if (!best || !(best->rank < rank)) return s;
      // An earlier attempt was better: it stands, with the retries counted.
      best->report.snap_retries = r.snap_retries;
      w = std::move(best->w);
      adj = std::move(best->adj);
      r = std::move(best->report);
      return best->stats;
    }
    if (!best || rank < best->rank) best = Attempt{std::move(w), std::move(adj), s, r, rank};
    w = start;
    ++r.snap_retries;
  }
}

// The default tolerance, half the local border edge, leaves open the gaps wider than that: on a
// fine tessellation a gap of 1e-3 L is several border edges wide. One global floor wide enough
// for them opened holes in clean hulls (ship_449, kcs, the generated 300- and 1,000-patch chine
// hulls: 2026-12-04), so the gap width is measured where a gap stayed open instead: each border
// vertex facing another patch's border across more than its tolerance (up to kWidestGap /
// kWiden of the length away) gets kWiden times that width as its tolerance, and the snap runs
// again from the same start. The new attempt stands when it has fewer boundary
// loops and no more edges with three faces; a merge with no open gap never runs it, so clean
// hulls merge as before.
constexpr double kWiden = 1.25;
constexpr double kWidestGap = 2e-3;  // of the hull's length
constexpr double kShorterBorder = 0.9;

void widen_to_open_gaps(std::span<const Patch> patches, const merge::Work& before_snap,
                        const merge::Border& border, const MergeOptions& options, double length,
                        merge::Work& w, MergeReport& r, EdgeAdjacency& adj, merge::SnapStats& s) {
  const std::vector<merge::OpenGapVertex> open =
      merge::find_open_gap_vertices(w, adj, options, kWidestGap * length / kWiden);
  if (open.empty()) return;
  std::vector<double> scale(border.vertices.size(), 1.0);
  std::size_t widened = 0;
  double widest = 0;
  // The open vertices are numbered as after the snap, whose welds dropped vertices and so
  // renumbered the rest; the border is numbered as before it. A vertex across an open gap was
  // not moved, so it is found by its position (until 2026-12-05 it was looked up by its number,
  // and most of the widened tolerances went to other vertices).
  std::vector<std::pair<std::array<double, 3>, std::size_t>> by_position(border.vertices.size());
  for (std::size_t i = 0; i < border.vertices.size(); ++i) {
    const Vec3d& p = before_snap.mesh.positions[border.vertices[i]];
    by_position[i] = {{p.x, p.y, p.z}, i};
  }
  std::sort(by_position.begin(), by_position.end());
  for (const merge::OpenGapVertex& o : open) {
    const Vec3d& p = w.mesh.positions[o.vertex];
    const std::array<double, 3> key{p.x, p.y, p.z};
    const auto it = std::lower_bound(by_position.begin(), by_position.end(), key,
                                     [](const std::pair<std::array<double, 3>, std::size_t>& e,
                                        const std::array<double, 3>& k) { return e.first < k; });
    if (it == by_position.end() || it->first != key) continue;
    const std::size_t i = it->second;
    const double base = merge::vertex_tolerance(options, border.edge_length[i]);
    const double want = std::min(kWiden * o.width, kWidestGap * length);
    if (!(base > 0) || !(want > base)) continue;
    scale[i] = want / base;
    ++widened;
    widest = std::max(widest, want);
  }
  if (widened == 0) return;
  merge::Work again;
  MergeReport ra = r;
  ra.snap_retries = 0;  // of the attempt that stands
  EdgeAdjacency adj_again;
  const merge::SnapStats sa = close_seams(patches, before_snap, again, border, options, length,
                                          std::move(scale), ra, adj_again);
  // Fewer loops, or a border shorter by kShorterBorder whatever the loop count: a gap that
  // opened onto the hull's outline was no loop of its own, and closing it can leave small holes
  // for the zipper (the chine of chine 100 with every defect at 128,000 triangles, 0.07-0.1 m
  // apart from the transom to the stem: 1 loop and 397 m of border -> 7 loops and 220 m).
  const auto border_length = [](const merge::Work& m, const EdgeAdjacency& a) {
    double sum = 0;
    for (Index e : a.boundary_edges) {
      sum += norm(m.mesh.positions[a.edges[e].v1] - m.mesh.positions[a.edges[e].v0]);
    }
    return sum;
  };
  const bool fewer = adj_again.boundary_loops.size() < adj.boundary_loops.size() ||
                     border_length(again, adj_again) < kShorterBorder * border_length(w, adj);
  if (!(fewer && adj_again.nonmanifold_edges.size() <= adj.nonmanifold_edges.size())) return;
  ra.gap_vertices_widened = widened;
  ra.widened_to = widest;
  w = std::move(again);
  r = std::move(ra);
  adj = std::move(adj_again);
  s = sa;
}

// Edges with three faces that the retries left, where a face of one patch lies on another's
// across the edge (drop_folded_faces): the remnant goes, and the small hole it leaves, if any, is
// closed. Where there is none, edges both faces traverse the same way are treated alike
// (drop_inconsistent_remnants). Only a merge that would otherwise fail, or keep an inconsistent
// edge, runs it, so every other comes out as before.
void drop_folds(merge::Work& w, EdgeAdjacency& adj, const MergeOptions& options, double length,
                MergeReport& r) {
  if (adj.nonmanifold_edges.empty() && adj.inconsistent_edges.empty()) return;
  merge::FoldStats folds = merge::drop_folded_faces(w, adj);
  if (folds.faces == 0) folds = merge::drop_inconsistent_remnants(w, adj);
  if (folds.faces == 0) return;
  r.folded_faces_dropped = folds.faces;
  r.overlap_triangles_removed += folds.faces;
  r.overlap_area_removed += folds.area;
  r.degenerate_faces_dropped += merge::drop_degenerate(w, length);  // and the unused vertices
  adj = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  std::vector<std::array<Index, 2>> left_open;
  r.holes_filled += fill_holes(w, adj, options, length, left_open);
}

// Folds on interior edges (folded_edge_welds): the two third corners of each are welded and the
// double layer that makes goes. Kept only when the surface has no more non-manifold or
// inconsistent edges and no more boundary loops than before; a merge with no fold is untouched.
void weld_folds(merge::Work& w, EdgeAdjacency& adj, double length, MergeReport& r) {
  const std::vector<std::pair<Index, Index>> welds = merge::folded_edge_welds(w, adj);
  if (welds.empty()) return;
  merge::Work before = w;
  std::vector<Index> onto(w.mesh.vertex_count());
  std::iota(onto.begin(), onto.end(), Index{0});
  for (const auto& [from, to] : welds) onto[from] = to;
  for (Face& t : w.mesh.faces) {
    for (int c = 0; c < 3; ++c) t[c] = onto[t[c]];
  }
  const std::size_t dropped = merge::drop_degenerate(w, length);
  EdgeAdjacency again = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  if (again.nonmanifold_edges.size() > adj.nonmanifold_edges.size() ||
      again.inconsistent_edges.size() > adj.inconsistent_edges.size() ||
      again.boundary_loops.size() > adj.boundary_loops.size()) {
    w = std::move(before);
    return;
  }
  r.folds_welded = welds.size();
  r.degenerate_faces_dropped += dropped;
  adj = std::move(again);
}

// One merge of the checked triangulation. outward_sign: see remove_overlaps; covered_opposite
// gets the overlap step's.
MergedSurface merge_pass(std::span<const Patch> patches, const SurfaceMesh& triangulation,
                         const MergeOptions& options, std::span<const double> outward_sign,
                         std::vector<std::pair<PatchId, PatchId>>& covered_opposite,
                         Progress& progress) {
  BBox3d box;
  for (const Vec3d& p : triangulation.positions) box.add(p);
  const Vec3d e = box.extent();
  const double length = std::max({e.x, e.y, e.z, 1e-300});

  merge::Work w;
  w.mesh = triangulation;
  w.mesh.face_block.clear();
  w.face_old.resize(triangulation.face_count());
  w.vert_old.resize(triangulation.vertex_count());
  for (std::size_t f = 0; f < w.face_old.size(); ++f) w.face_old[f] = Index(f);
  for (std::size_t v = 0; v < w.vert_old.size(); ++v) w.vert_old[v] = Index(v);

  MergedSurface out;
  MergeReport& r = out.report;
  r.input_triangles = triangulation.face_count();
  progress.stage("merge");
  // The border of the patch triangulations, collected again only when the overlaps changed it.
  merge::Border border = merge::collect_border(w.mesh);
  if (options.remove_overlaps) {
    merge::OverlapStats o =
        merge::remove_overlaps(patches, w, border, options, length, outward_sign, progress);
    covered_opposite = std::move(o.covered_opposite);
    r.overlap_triangles_removed = o.triangles;
    r.overlap_area_removed = o.area;
    if (o.changed) border = merge::collect_border(w.mesh);
  }
  if (progress.cancelled()) throw UsageError("merge cancelled");
  progress.update(0.4);
  EdgeAdjacency adj;  // of the oriented mesh
  // The mesh before the snap, which every attempt starts from.
  const merge::Work before_snap = std::move(w);
  merge::SnapStats s = close_seams(patches, before_snap, w, border, options, length,
                                   std::vector<double>(border.vertices.size(), 1.0), r, adj);
  if (options.gap_tolerance <= 0 && options.widen_to_gaps) {
    widen_to_open_gaps(patches, before_snap, border, options, length, w, r, adj, s);
  }
  drop_folds(w, adj, options, length, r);
  // Gaps wider than the border edges on both sides stay open (no vertex of one border comes near
  // the other's): thin loops along two patches. They are zipped shut up to the tolerance, or
  // kWidestGap of the length by default.
  if (options.bridge_gaps) {
    r.gaps_bridged = merge::bridge_gaps(
        w, adj, options.gap_tolerance > 0 ? options.gap_tolerance : kWidestGap * length);
  }
  if (r.gaps_bridged > 0) adj = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  weld_folds(w, adj, length, r);
  r.flat_faces_split = merge::split_flat_faces(w, length);
  if (r.flat_faces_split > 0) adj = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  // A few passes: a hole that shares a vertex with one closed waits for the next.
  for (int pass = 0; pass < 3; ++pass) {
    const std::size_t closed = merge::close_flat_holes(w, adj);
    if (closed == 0) break;
    r.holes_filled += closed;
    adj = build_edge_adjacency(w.mesh.faces, w.mesh.vertex_count());
  }
  r.folds_flipped = merge::flip_folded_flaps(w, adj);
  r.vertices_welded = s.welded;
  r.tjunctions_split = s.split;
  r.gaps_closed = s.gaps_closed;
  r.widest_gap_closed = s.widest;
  progress.update(0.7);
  // The report before the Morton order: none of it depends on the numbering, and the adjacency
  // of the last pass is current.
  r.open_gaps = merge::find_open_gaps(w, adj, options);
  r.boundary_loops = adj.boundary_loops.size();
  r.nonmanifold_edges = adj.nonmanifold_edges.size();
  r.inconsistent_edges = adj.inconsistent_edges.size();
  r.enclosed_volume = merge::enclosed_volume(w.mesh, adj);
  merge::reorder_morton(w);
  progress.update(1.0);

  out.mesh = std::move(w.mesh);
  out.vert_new2old = std::move(w.vert_old);
  out.face_new2old = std::move(w.face_old);
  return out;
}

// The side of su x sv each patch's outside lies on, +1 or -1, as the merge oriented it.
std::vector<double> outward_signs(std::span<const Patch> patches, std::span<const PatchId> turned) {
  std::vector<double> sign(patches.size());
  for (std::size_t p = 0; p < patches.size(); ++p) sign[p] = patches[p].reversed ? -1.0 : 1.0;
  for (PatchId p : turned) sign[p] = -sign[p];
  return sign;
}

}  // namespace

MergedSurface merge_patches(std::span<const Patch> patches, const SurfaceMesh& triangulation,
                            const MergeOptions& options, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  check_input(patches, triangulation);
  std::vector<std::pair<PatchId, PatchId>> opposite;
  MergedSurface out = merge_pass(patches, triangulation, options, {}, opposite, progress);
  // The overlap step compares the normals of coincident layers as the patches' own flags turn
  // them, and lets a covered region grow only over layers that run the way its seed's did.
  // Where a patch that arrived flipped (no flag says so) overlaps one that did not (a seed
  // covered the opposite way as compared, the same way out of the hull as oriented: exactly one
  // of the two was turned), that way changes along the region, and part of the overlap stays
  // uncut. Then the whole merge runs again with every patch turned as this one oriented it; the
  // second stands unless its surface is worse. Layers whose outsides face each other (a knife
  // edge, two layers back to back) are no reason to.
  const std::vector<double> sign = outward_signs(patches, out.report.patches_flipped);
  const auto turned = [&](PatchId p) { return sign[p] != (patches[p].reversed ? -1.0 : 1.0); };
  const bool flipped_overlap = std::any_of(opposite.begin(), opposite.end(), [&](const auto& pq) {
    return turned(pq.first) != turned(pq.second);
  });
  if (flipped_overlap) {
    MergedSurface again = merge_pass(patches, triangulation, options, sign, opposite, progress);
    const auto rank = [](const MergeReport& r) {
      return std::array<std::size_t, 3>{r.nonmanifold_edges, r.inconsistent_edges,
                                        r.boundary_loops};
    };
    if (!(rank(out.report) < rank(again.report))) {
      out = std::move(again);
      out.report.overlaps_cut_oriented = true;
    }
  }
  out.report.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace hm
