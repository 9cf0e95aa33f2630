// Topology: boundary edges by where they lie, orientation (consistency and direction), very close
// panel centres.
#include <algorithm>
#include <cmath>
#include <deque>

#include "core/bbox.h"
#include "core/parallel.h"
#include "quality/hydrostatics.h"
#include "quality/quality_steps.h"

namespace hm {
namespace {

enum class BoundaryKind { kCentrePlane, kWaterline, kAboveWater, kFreeBelow };

bool on_centre_plane(const Vec3d& p, const Vec3d& q, const ResolvedSettings& s) {
  return s.half_hull && std::abs(p.y) <= s.tol && std::abs(q.y) <= s.tol;
}

BoundaryKind classify(const Vec3d& p, const Vec3d& q, const ResolvedSettings& s) {
  if (on_centre_plane(p, q, s)) return BoundaryKind::kCentrePlane;
  if (std::abs(p.z - s.waterline_z) <= s.tol && std::abs(q.z - s.waterline_z) <= s.tol)
    return BoundaryKind::kWaterline;
  if (std::min(p.z, q.z) >= s.waterline_z - s.tol) return BoundaryKind::kAboveWater;
  return BoundaryKind::kFreeBelow;
}

// The upper edge of a mesh not cut at a waterplane, per edge: each run of consecutive boundary
// edges off the centre plane, along a boundary loop, that has a vertex at the top of the mesh. A
// half hull's loop runs down the centre plane from the deck at one end, along the keel, up to the
// deck at the other and back along the deck edge; a gap beside the keel splits the centre-plane
// part, and its run stays below the top.
std::vector<std::uint8_t> upper_edge(const SurfaceMesh& mesh, const EdgeAdjacency& adj,
                                     const ResolvedSettings& s) {
  std::vector<std::uint8_t> upper(adj.edges.size(), 0);
  auto centre = [&](Index e) {
    return on_centre_plane(mesh.positions[adj.edges[e].v0], mesh.positions[adj.edges[e].v1], s);
  };
  auto at_top = [&](Index v) { return mesh.positions[v].z >= s.waterline_z - s.tol; };
  for (const BoundaryLoop& loop : adj.boundary_loops) {
    const std::size_t n = loop.edges.size();
    // A closed loop is read from just after a centre-plane edge, so that no run wraps round.
    std::size_t start = 0;
    if (loop.closed) {
      for (std::size_t i = 0; i < n; ++i) {
        if (centre(loop.edges[i])) {
          start = i + 1;
          break;
        }
      }
    }
    auto edge = [&](std::size_t i) { return loop.edges[(start + i) % n]; };
    for (std::size_t i = 0; i < n;) {
      if (centre(edge(i))) {
        ++i;
        continue;
      }
      std::size_t j = i;
      bool top = false;
      for (; j < n && !centre(edge(j)); ++j) {
        top = top || at_top(adj.edges[edge(j)].v0) || at_top(adj.edges[edge(j)].v1);
      }
      if (top) {
        for (std::size_t k = i; k < j; ++k) upper[edge(k)] = 1;
      }
      i = j;
    }
  }
  return upper;
}

// Orientation parity of every face relative to the first face of its component (breadth-first
// over manifold edges; an edge used twice in one direction flips the parity). The minority parity
// of each component is "flipped"; on a tie, the faces disagreeing with the component's lowest face.
std::size_t mark_flipped(const SurfaceMesh& mesh, const EdgeAdjacency& adj,
                         std::vector<double>& flipped) {
  const std::size_t nf = mesh.face_count();
  std::vector<std::uint8_t> parity(nf, 0);
  std::vector<Index> component(nf, kInvalid);
  flipped.assign(nf, 0.0);
  std::size_t components = 0;
  std::vector<Index> members;
  for (std::size_t seed = 0; seed < nf; ++seed) {
    if (component[seed] != kInvalid) continue;
    const Index id = static_cast<Index>(components++);
    members.clear();
    std::deque<Index> queue{static_cast<Index>(seed)};
    component[seed] = id;
    while (!queue.empty()) {
      const Index f = queue.front();
      queue.pop_front();
      members.push_back(f);
      for (int c = 0; c < 4; ++c) {
        const Index g = adj.opposite_face[4 * f + c];
        if (g == kInvalid || component[g] != kInvalid) continue;
        component[g] = id;
        parity[g] = parity[f] ^ (adj.edges[adj.slot_edge[4 * f + c]].same_direction ? 1 : 0);
        queue.push_back(g);
      }
    }
    std::size_t odd = 0;
    for (Index f : members) odd += parity[f];
    const std::uint8_t minority = 2 * odd <= members.size() ? 1 : 0;
    for (Index f : members) flipped[f] = parity[f] == minority ? 1.0 : 0.0;
  }
  return components;
}

}  // namespace

void check_topology(const SurfaceMesh& mesh, const EdgeAdjacency& adj, const ResolvedSettings& s,
                    QualityReport& r, std::vector<std::uint8_t>& free_edge_face,
                    std::vector<std::uint8_t>& nonmanifold_face) {
  TopologyFacts& t = r.topology;
  t.waterline_z = s.waterline_z;
  t.uncut = s.uncut;
  t.edges = adj.edges.size();
  t.boundary_edges = adj.boundary_edges.size();
  t.boundary_loops = adj.boundary_loops.size();
  t.nonmanifold_edges = adj.nonmanifold_edges.size();
  t.inconsistent_edges = adj.inconsistent_edges.size();
  t.watertight = adj.watertight();
  t.orientation_consistent = adj.inconsistent_edges.empty();
  free_edge_face.assign(mesh.face_count(), 0);
  nonmanifold_face.assign(mesh.face_count(), 0);
  const std::vector<std::uint8_t> upper =
      s.uncut ? upper_edge(mesh, adj, s) : std::vector<std::uint8_t>{};
  for (Index e : adj.boundary_edges) {
    const MeshEdge& m = adj.edges[e];
    BoundaryKind kind = classify(mesh.positions[m.v0], mesh.positions[m.v1], s);
    // Uncut, there is no waterline: the flat parts of the upper edge count with the rest.
    if (kind != BoundaryKind::kCentrePlane && !upper.empty() && upper[e]) {
      kind = BoundaryKind::kAboveWater;
    }
    switch (kind) {
      case BoundaryKind::kCentrePlane:
        ++t.centre_plane_edges;
        break;
      case BoundaryKind::kWaterline:
        ++t.waterline_edges;
        break;
      case BoundaryKind::kAboveWater:
        ++t.above_water_edges;
        break;
      case BoundaryKind::kFreeBelow:
        ++t.free_edges_below;
        free_edge_face[m.first_slot / 4] = 1;
        break;
    }
  }
  auto on_plane = [&](Index v) { return std::abs(mesh.positions[v].z - s.waterline_z) <= s.tol; };
  for (const Face& f : mesh.faces) {
    const int n = corner_count(f);
    bool above = false, below = false, edge_on_plane = false;
    for (int c = 0; c < n; ++c) {
      const double z = mesh.positions[f[c]].z;
      above |= z > s.waterline_z + s.tol;
      below |= z < s.waterline_z - s.tol;
      edge_on_plane |= on_plane(f[c]) && on_plane(f[(c + 1) % n]);
    }
    t.panels_across_waterline += above && below ? 1 : 0;
    t.panels_above_on_waterline += above && !below && edge_on_plane ? 1 : 0;
  }
  // Every face using a non-manifold edge: the slots of an edge are not stored, so scan them.
  if (!adj.nonmanifold_edges.empty()) {
    std::vector<std::uint8_t> bad(adj.edges.size(), 0);
    for (Index e : adj.nonmanifold_edges) bad[e] = 1;
    for (std::size_t slot = 0; slot < adj.slot_edge.size(); ++slot)
      if (adj.slot_edge[slot] != kInvalid && bad[adj.slot_edge[slot]])
        nonmanifold_face[slot / 4] = 1;
  }
  t.components = mark_flipped(mesh, adj, r.per_face.flipped);
  for (double f : r.per_face.flipped) t.flipped_faces += f != 0;
  // Sign of the enclosed volume (normals out of the body into the fluid: positive).
  FloatingPosition position;
  position.waterline_z = s.waterline_z;
  t.enclosed_volume = hydrostatics_mesh(mesh, position).volume;
  t.normals_into_fluid = t.enclosed_volume > 0;
}

void find_close_centres(const QualityOptions& o, QualityReport& r) {
  FaceQuality& fq = r.per_face;
  const std::size_t nf = fq.centroid.size();
  fq.close_centre.assign(nf, 0.0);
  if (nf < 2) return;
  // Radius of face i: fraction * sqrt(area_i). A pair is close when nearer than the smaller of the
  // two radii; it is searched for from that smaller face only (ties: the lower index), with its
  // own radius, so each pair is found once.
  std::vector<double> radius(nf);
  BBox3d box;
  for (std::size_t f = 0; f < nf; ++f) {
    radius[f] = o.close_centre_fraction * std::sqrt(fq.area[f]);
    box.add(fq.centroid[f]);
  }
  std::vector<double> sorted = radius;
  const std::size_t p90 = nf * 9 / 10;
  std::nth_element(sorted.begin(), sorted.begin() + p90, sorted.end());
  // Grid cell: the 90th-percentile radius (most searches visit at most 8 cells), kept above 1e-6 of
  // the box so that cell coordinates fit in 21 bits.
  const double h = std::max({sorted[p90], 1e-6 * box.diagonal(), 1e-300});
  auto cell = [&](const Vec3d& p, int axis) {
    return static_cast<std::int64_t>(std::floor((p[axis] - box.lo[axis]) / h));
  };
  auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return (static_cast<std::uint64_t>(i) << 42) | (static_cast<std::uint64_t>(j) << 21) |
           static_cast<std::uint64_t>(k);
  };
  std::vector<std::pair<std::uint64_t, Index>> grid(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const Vec3d& c = fq.centroid[f];
    grid[f] = {key(cell(c, 0), cell(c, 1), cell(c, 2)), static_cast<Index>(f)};
  }
  std::sort(grid.begin(), grid.end());
  std::vector<std::vector<Index>> partners(nf);  // written by face i only
  parallel_for(0, nf, [&](std::size_t i) {
    const Vec3d& c = fq.centroid[i];
    // The cells the ball of radius r_i touches: at most 2 per axis when r_i <= h.
    std::int64_t lo[3], hi[3];
    for (int axis = 0; axis < 3; ++axis) {
      Vec3d p = c;
      p[axis] -= radius[i];
      lo[axis] = std::max<std::int64_t>(cell(p, axis), 0);
      p[axis] = c[axis] + radius[i];
      hi[axis] = cell(p, axis);
    }
    for (std::int64_t a = lo[0]; a <= hi[0]; ++a)
      for (std::int64_t b = lo[1]; b <= hi[1]; ++b)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          const std::uint64_t kk = key(a, b, k);
          auto it = std::lower_bound(grid.begin(), grid.end(), std::pair{kk, Index{0}});
          for (; it != grid.end() && it->first == kk; ++it) {
            const Index j = it->second;
            const bool larger = radius[j] > radius[i] || (radius[j] == radius[i] && j > i);
            if (larger && norm(fq.centroid[j] - c) < radius[i]) partners[i].push_back(j);
          }
        }
  });
  for (std::size_t i = 0; i < nf; ++i) {
    r.close_centre_pairs += partners[i].size();
    for (Index j : partners[i]) fq.close_centre[i] = fq.close_centre[j] = 1;
  }
}

}  // namespace hm
