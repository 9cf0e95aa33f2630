// Border gaps, found on the panel mesh's own boundary: an edge between the end nodes of two rows
// whose boundary path on the surface strays from the straight edge by a quarter panel or more.
#include "structured/close_border_gaps.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/bbox.h"
#include "mesh/adjacency.h"
#include "structured/border_path.h"

namespace hm::structured {
namespace {

// A path straying less than this from the edge (in panels) is no gap.
constexpr double kGapPanels = 0.25;
// A cap's edge has both ends on the boundary within this share of the rows' tolerance (they are
// copies of the surface's boundary vertices).
constexpr double kOnBorder = 1e-6;
// A corner cut by less than this (panels) is rounding, not a gap: its fan would have no area.
constexpr double kMinStray = 1e-6;
// A node this close to y = 0 (share of the hull's largest extent) is in the centre plane.
constexpr double kCentreRounding = 1e-6;

// Largest metric distance of the points from the segment a-b.
double stray(const std::vector<Vec3d>& pts, const Vec3d& a, const Vec3d& b, const Metric& m) {
  const Vec3d d = b - a;
  const double dd = squared_norm(d);
  double worst = 0;
  for (const Vec3d& p : pts) {
    const double f = dd > 0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
    worst = std::max(worst, m.length(a + d * f, p));
  }
  return worst;
}

// Appends a fixed boundary node at p, lending it u's patch and (u, v).
Index add_node(const Vec3d& p, Index u, SurfaceMesh& mesh, std::vector<NodeSlot>& slots) {
  mesh.positions.push_back(p);
  mesh.vertex_patch.push_back(mesh.vertex_patch[u]);
  mesh.vertex_uv.push_back(mesh.vertex_uv[u]);
  slots.push_back(NodeSlot{});
  return static_cast<Index>(mesh.positions.size() - 1);
}

// Fills the region between the panel edge u -> w (one end in the centre plane, the other off it,
// on the waterplane) and the boundary path from u to w, which leaves the centre plane and reaches
// the waterplane at a corner, then runs along it. The two pieces of path either side of the
// corner, resampled, are zipped against each other, so that every triangle has a corner off the
// centre plane and one off the waterplane: a fan from either end could lay panels flat in one of
// the planes.
// top_z: the surface's greatest height along `up` (the waterplane's unit normal), the waterplane
// where it was cut there; a point within plane_tol (m) below it is on it (a cut in the file's
// frame rounds). Returns false, and adds nothing, when
// the end off the centre plane is not on it: the edge cuts no corner of the waterline.
// centre_tol (m): a point this close to y = 0 is in the centre plane.
bool fill_cut_corner(const std::vector<Vec3d>& path, Index u, Index w, const Vec3d& up,
                     double top_z, double plane_tol, double centre_tol, const Metric& metric,
                     SurfaceMesh& mesh, std::vector<NodeSlot>& slots) {
  const auto on_plane = [&](const Vec3d& p) { return top_z - dot(up, p) <= plane_tol; };
  const bool u_central = std::abs(mesh.positions[u].y) <= centre_tol;
  std::vector<Vec3d> from_central(path.begin(), path.end());
  if (!u_central) std::reverse(from_central.begin(), from_central.end());
  // Both ends on the waterplane: the edge lies along the waterline and cuts no corner.
  if (!on_plane(from_central.back()) || on_plane(from_central.front())) return false;
  // The corner: the first point on the waterplane (it may be the other end itself).
  std::size_t c = 1;
  while (c + 1 < from_central.size() && !on_plane(from_central[c])) ++c;
  if (!(std::abs(from_central[c].y) <= centre_tol)) {
    // The fine mesh cuts across the corner where the centre plane meets the waterplane (a chord
    // of a fine triangle: the property test's seeds 1209 at a transom and 1295 at a stem): the
    // corner is put back below the point where the path reaches the waterplane, the way the
    // waterline runs across a transom or round a fine stem.
    const double x = from_central[c].x;
    from_central.insert(from_central.begin() + static_cast<std::ptrdiff_t>(c),
                        Vec3d{x, 0.0, (top_z - up.x * x) / up.z});
  }
  const std::vector<Vec3d> central_run(from_central.begin(),
                                       from_central.begin() + static_cast<std::ptrdiff_t>(c + 1));
  std::vector<Vec3d> other_run(from_central.begin() + static_cast<std::ptrdiff_t>(c),
                               from_central.end());
  std::reverse(other_run.begin(), other_run.end());
  const Index central = u_central ? u : w, other = u_central ? w : u;
  const Index corner = add_node(from_central[c], u, mesh, slots);
  // Chains from each end of the edge to the corner.
  auto chain = [&](Index end, const std::vector<Vec3d>& run) {
    std::vector<Index> ids{end};
    for (const Vec3d& p : resample(run, metric)) ids.push_back(add_node(p, u, mesh, slots));
    ids.push_back(corner);
    return ids;
  };
  const std::vector<Index> from_c = chain(central, central_run);
  const std::vector<Index> from_o = chain(other, other_run);
  const std::vector<Index>& a = u_central ? from_c : from_o;
  const std::vector<Index>& b = u_central ? from_o : from_c;
  // The edge's face runs u -> w, so the fill runs w -> u -> a ... corner ... b -> w: a step
  // along a is the triangle (b[j], a[i], a[i + 1]), one along b is (a[i], b[j + 1], b[j]).
  // The chains share the corner, their last node: a chain whose other has reached it stops
  // one short of it.
  const auto& pos = mesh.positions;
  std::size_t i = 0, j = 0;
  for (;;) {
    const bool can_a = i + (j + 1 < b.size() ? 1 : 2) < a.size();
    const bool can_b = j + (i + 1 < a.size() ? 1 : 2) < b.size();
    if (!can_a && !can_b) break;
    const bool along_a = !can_b || (can_a && squared_norm(pos[a[i + 1]] - pos[b[j]]) <=
                                                 squared_norm(pos[a[i]] - pos[b[j + 1]]));
    if (along_a) {
      mesh.faces.push_back({b[j], a[i], a[i + 1], kInvalid});
      ++i;
    } else {
      mesh.faces.push_back({a[i], b[j + 1], b[j], kInvalid});
      ++j;
    }
  }
  return true;
}

// The faces closing a ring (a gap's outline, its faces' way round): the fan from its first
// node, the row end w, as always, unless that fan has a corner under kSliverAngle. Along a
// straight run of border a fan from its end lays triangles of next to no area on the run (kcs.iges
// at 0.446 m heeled 15 degrees, 3,000 panels: the waterline from a row end to the stem, a panel
// of 1.2e-5 m^2 by one of 0.0026). Then the triangulation of the ring with the largest smallest
// angle whose every face turns the ring's way (dynamic programming over its chords), if one
// does better than the fan.
constexpr double kSliverAngle = 5 * M_PI / 180;
constexpr std::size_t kMaxRing = 64;  // nodes; longer rings keep the fan

void close_ring(const std::vector<Index>& ring, std::span<const Vec3d> pos,
                std::vector<Face>& faces) {
  const std::size_t n = ring.size();
  Vec3d normal{0, 0, 0};  // Newell's
  for (std::size_t i = 0; i < n; ++i) normal = normal + cross(pos[ring[i]], pos[ring[(i + 1) % n]]);
  // Face (i, k, j) of ring places i < k < j: its smallest angle, or -1 where it turns against the
  // ring.
  const auto quality = [&](std::size_t i, std::size_t k, std::size_t j) {
    const Vec3d &a = pos[ring[i]], &b = pos[ring[k]], &c = pos[ring[j]];
    if (!(dot(cross(b - a, c - a), normal) > 0)) return -1.0;
    return min_angle(a, b, c);
  };
  double fan = M_PI;
  for (std::size_t k = 1; k + 1 < n; ++k) fan = std::min(fan, quality(0, k, k + 1));
  std::vector<std::size_t> split;  // best[i][j]'s apex k, row-major; n = none
  if (n >= 4 && n <= kMaxRing && fan < kSliverAngle) {
    std::vector<double> best(n * n, -2);
    split.assign(n * n, n);
    for (std::size_t i = 0; i + 1 < n; ++i) best[i * n + i + 1] = M_PI;  // an edge: no face
    for (std::size_t len = 2; len < n; ++len) {
      for (std::size_t i = 0; i + len < n; ++i) {
        const std::size_t j = i + len;
        for (std::size_t k = i + 1; k < j; ++k) {
          const double q = std::min({best[i * n + k], best[k * n + j], quality(i, k, j)});
          if (q > best[i * n + j]) best[i * n + j] = q, split[i * n + j] = k;
        }
      }
    }
    if (!(best[n - 1] > fan)) split.clear();
  }
  if (split.empty()) {
    for (std::size_t k = 1; k + 1 < n; ++k)
      faces.push_back({ring[0], ring[k], ring[k + 1], kInvalid});
    return;
  }
  std::vector<std::array<std::size_t, 2>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j < i + 2) continue;
    const std::size_t k = split[i * n + j];
    faces.push_back({ring[i], ring[k], ring[j], kInvalid});
    stack.push_back({i, k});
    stack.push_back({k, j});
  }
}

}  // namespace

GapCounts close_border_gaps(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                            std::span<const std::uint8_t> row_end, const Vec3d& up,
                            const Metric& metric, SurfaceMesh& mesh, std::vector<NodeSlot>& slots) {
  GapCounts counts;
  const EdgeAdjacency panels = build_edge_adjacency(mesh.faces, mesh.vertex_count());
  const double tol = 0.25 * std::min({metric.size.x, metric.size.y, metric.size.z});
  const std::size_t face_count = mesh.faces.size();
  double top_z = -std::numeric_limits<double>::infinity();
  BBox3d box;
  for (const Vec3d& p : surface.positions) {
    top_z = std::max(top_z, dot(up, p));
    box.add(p);
  }
  // A node counts as in the centre plane within rounding of y = 0: a file may draw its
  // centre-plane edge a hair off it (kcs.iges, 2.5e-6 m, 3e-7 L), and the command puts those
  // nodes onto it after meshing. Not within the plane's snap tolerance (2e-4 L): a row end a
  // millimetre off the plane (DTMB 5415's transition patch by the skeg, 1.5e-4 L) is no corner
  // of it, and fans taken from there crossed the rows' panels (800 panels at a 0.319 m draft:
  // 1 -> 4 pairs through each other).
  const Vec3d extent = box.extent();
  const double centre_tol = kCentreRounding * std::max({extent.x, extent.y, extent.z});
  const auto central = [&](const Vec3d& p) { return std::abs(p.y) <= centre_tol; };
  for (Index e : panels.boundary_edges) {
    const Index slot = panels.edges[e].first_slot;
    const Face& f = mesh.faces[slot / 4];
    const Index u = f[slot % 4], w = f[(slot % 4 + 1) % corner_count(f)];
    const Vec3d pu = mesh.positions[u], pw = mesh.positions[w];
    // One end on the centre plane and the other off it, on another plane (the waterline): the
    // boundary turns a corner between them, however little the path strays.
    const bool turns = dot(up, pu) != dot(up, pw) && central(pu) != central(pw);
    const bool row_ends = u < row_end.size() && w < row_end.size() && row_end[u] && row_end[w];
    // Any other panel edge (an end cap's) is a gap only where it cuts such a corner, both ends
    // on the boundary itself: a transom immersed a few hundredths of a panel, whose corner below
    // the waterline the cap's resampling drops (the property test's seeds 1205-1231).
    if (!row_ends) {
      if (!turns) continue;
      const std::vector<Vec3d> best =
          shortest_border_path(surface, adj, pu, pw, metric, kOnBorder * tol);
      if (best.size() < 3 || stray(best, pu, pw, metric) < kMinStray) continue;
      if (fill_cut_corner(best, u, w, up, top_z, kOnBorder * tol, centre_tol, metric, mesh, slots))
        ++counts.gaps;
      continue;
    }
    if (slots[u].row == slots[w].row) continue;
    const std::vector<Vec3d> best = shortest_border_path(surface, adj, pu, pw, metric, tol);
    if (best.empty()) continue;
    if (!turns && stray(best, pu, pw, metric) < kGapPanels) continue;
    if (best.size() < 3) continue;  // nothing between the ends
    std::vector<Vec3d> inner = resample(best, metric);
    if (inner.empty()) {
      // Shorter than a panel but bent: its farthest point alone.
      const Vec3d d = pw - pu;
      double far = -1;
      Vec3d at = best[best.size() / 2];
      for (const Vec3d& p : best) {
        const double f = std::clamp(dot(p - pu, d) / std::max(squared_norm(d), 1e-300), 0.0, 1.0);
        const double h = norm(pu + d * f - p);
        if (h > far) {
          far = h;
          at = p;
        }
      }
      inner.push_back(at);
    }
    // Round the corner of the centre plane and the waterline, a fan that misses the corner
    // itself cuts it off (seeds 1293 and 1295, at a stem: the path's middle or its farthest
    // point from the edge lay on the stem below it); its two sides are zipped instead. A fan
    // through the corner is kept: where a concave stem runs aft of the last station, the
    // zip's nodes on the stem would cross the rows' panels (seed 1257).
    const bool has_corner = std::any_of(inner.begin(), inner.end(), [&](const Vec3d& p) {
      return central(p) && top_z - dot(up, p) <= kOnBorder * tol;
    });
    if (turns && !has_corner &&
        fill_cut_corner(best, u, w, up, top_z, kOnBorder * tol, centre_tol, metric, mesh, slots)) {
      ++counts.gaps;
      continue;
    }
    // The gap lies across the edge from its face, which runs u -> w: its ring w, u, q1, ... runs
    // w -> u (close_ring).
    std::vector<Index> ring{w, u};
    for (const Vec3d& p : inner) ring.push_back(add_node(p, u, mesh, slots));
    close_ring(ring, mesh.positions, mesh.faces);
    ++counts.gaps;
  }
  counts.triangles = mesh.faces.size() - face_count;
  return counts;
}

}  // namespace hm::structured
