// End caps. Beyond the first station (the stern, or a transom) and the last (the stem) the hull
// is a small region bounded by the end row and by the surface's boundary (keel and centre plane,
// the waterline, a transom edge). Its boundary path is resampled at the panel size, keeping its
// corners, and zipped against the row.
#include "structured/cap_ends.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "mesh/adjacency.h"
#include "structured/border_path.h"

namespace hm::structured {
namespace {

// The knuckle edges beyond an end station as a neighbour map: both ends beyond it (both_beyond)
// or at least one.
template <class Beyond>
std::map<Index, std::vector<Index>> knuckle_neighbours(const FeatureSet& features,
                                                       const Beyond& beyond, bool both_beyond) {
  std::map<Index, std::vector<Index>> next;
  for (const FeatureLine& l : features.knuckles) {
    const std::size_t n = l.vertices.size();
    for (std::size_t i = 0; i + 1 < n + (l.closed ? 1 : 0); ++i) {
      const Index a = l.vertices[i], b = l.vertices[(i + 1) % n];
      const int count = (beyond(a) ? 1 : 0) + (beyond(b) ? 1 : 0);
      if (count < (both_beyond ? 2 : 1)) continue;
      next[a].push_back(b);
      next[b].push_back(a);
    }
  }
  return next;
}

// The transverse knuckle beyond an end station (a transom's edge): a path of knuckle edges, every
// vertex beyond the station, from one vertex of the boundary path to another. Returns its
// vertices from the one nearer the row's lower end, and their places p0 < p1 in `path`; empty
// when there is none at least two panels long.
std::vector<Index> end_knuckle(const SurfaceMesh& surface, const FeatureSet& features,
                               const std::vector<Index>& path, double x, bool aft,
                               const Metric& metric, std::size_t& p0, std::size_t& p1) {
  auto beyond = [&](Index v) {
    return aft ? surface.positions[v].x < x : surface.positions[v].x > x;
  };
  std::map<Index, std::vector<Index>> next = knuckle_neighbours(features, beyond, true);
  std::map<Index, std::size_t> place;
  for (std::size_t i = 0; i < path.size(); ++i) place.emplace(path[i], i);
  std::vector<Index> best;
  std::size_t best_span = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (!next.count(path[i])) continue;
    // Breadth-first over knuckle edges from path[i]; the path vertex reached farthest along the
    // path wins.
    std::map<Index, Index> from{{path[i], path[i]}};
    std::vector<Index> queue{path[i]};
    for (std::size_t q = 0; q < queue.size(); ++q) {
      for (Index w : next[queue[q]]) {
        if (from.count(w)) continue;
        from[w] = queue[q];
        queue.push_back(w);
      }
    }
    for (Index w : queue) {
      const auto it = place.find(w);
      if (it == place.end() || it->second <= i || it->second - i <= best_span) continue;
      std::vector<Index> k{w};
      while (k.back() != path[i]) k.push_back(from[k.back()]);
      std::reverse(k.begin(), k.end());
      double len = 0;
      for (std::size_t m = 1; m < k.size(); ++m)
        len += metric.length(surface.positions[k[m - 1]], surface.positions[k[m]]);
      if (len < 2) continue;
      best = k;
      best_span = it->second - i;
      p0 = i;
      p1 = it->second;
    }
  }
  return best;
}

// Knuckles that cross the end station and end on the boundary beyond it (the waterline of a hull
// meshed above it, a chine running into the stem): each pairs the row node where the knuckle
// breaks the row (its index in the row's nodes) with the boundary path vertex it ends on (its
// place in `path`), so that the cap can be zipped in pieces and no panel straddles the line.
// Pairs ascend in both; one that would cross another is dropped.
struct CapSplit {
  std::size_t node = 0, place = 0;
};
std::vector<CapSplit> cap_splits(const SurfaceMesh& surface, const FeatureSet& features,
                                 const std::vector<Index>& path, const RowCurve& c,
                                 const std::vector<double>& node_s, double x, bool aft,
                                 double tol) {
  std::vector<CapSplit> out;
  if (path.size() < 3 || c.breaks.size() < 3) return out;
  auto beyond = [&](Index v) {
    return aft ? surface.positions[v].x < x : surface.positions[v].x > x;
  };
  // Knuckle edges with at least one end beyond the station.
  std::map<Index, std::vector<Index>> next = knuckle_neighbours(features, beyond, false);
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    if (!next.count(path[i]) || !beyond(path[i])) continue;
    // Follow the knuckle from the path vertex to where it crosses the station plane.
    std::vector<Index> queue{path[i]};
    std::map<Index, bool> seen{{path[i], true}};
    std::optional<Vec3d> crossing;
    for (std::size_t q = 0; q < queue.size() && !crossing; ++q) {
      for (Index w : next[queue[q]]) {
        if (seen.count(w)) continue;
        seen[w] = true;
        if (beyond(w)) {
          queue.push_back(w);
          continue;
        }
        const Vec3d& pa = surface.positions[queue[q]];
        const Vec3d& pb = surface.positions[w];
        const double f = (x - pa.x) / (pb.x - pa.x);
        crossing = pa + f * (pb - pa);
        break;
      }
    }
    if (!crossing) continue;
    for (std::size_t b = 1; b + 1 < c.breaks.size(); ++b) {
      const Breakpoint& br = c.breaks[b];
      // A knuckle's break, or a plane's where the knuckle lies in the plane (the waterline).
      if (br.label.kind != BreakKind::kKnuckle && br.label.kind != BreakKind::kPlane) continue;
      if (norm(c.points[br.point] - *crossing) > tol) continue;
      const auto it = std::lower_bound(node_s.begin(), node_s.end(), br.s);
      if (it == node_s.end() || *it != br.s) continue;
      const std::size_t node = static_cast<std::size_t>(it - node_s.begin());
      if (node == 0 || node + 1 == node_s.size()) continue;
      if (!out.empty() && (node <= out.back().node || i <= out.back().place)) continue;
      out.push_back({node, i});
    }
  }
  return out;
}

}  // namespace

CapCounts cap_ends(const SurfaceMesh& surface, const EdgeAdjacency& adj, const FeatureSet& features,
                   std::span<const Row> rows, std::span<const RowNodes> nodes,
                   std::span<const std::vector<Index>> first_vertex, const Metric& metric,
                   const ZipOptions& zip_options, SurfaceMesh& mesh, std::vector<NodeSlot>& slots) {
  CapCounts counts;
  if (rows.empty()) return counts;
  const double tol = 0.25 * std::min({metric.size.x, metric.size.y, metric.size.z});
  for (const bool aft : {true, false}) {
    const std::size_t j = aft ? 0 : rows.size() - 1;
    const Row& row = rows[j];
    if (row.curves.size() != 1) {
      counts.open[aft ? 0 : 1] = true;
      continue;
    }
    const RowCurve& c = row.curves[0];
    const LoopSpot sa = nearest_boundary_edge(surface, adj, c.points.front());
    const LoopSpot sb = nearest_boundary_edge(surface, adj, c.points.back());
    if (sa.loop != sb.loop || sa.distance > tol || sb.distance > tol) {
      counts.open[aft ? 0 : 1] = true;
      continue;
    }
    const std::vector<Index>& loop = adj.boundary_loops[sa.loop].vertices;
    // Of the two ways round the loop, the one beyond the station.
    std::vector<Index> best;
    double best_score = 0;
    for (const bool forward : {true, false}) {
      const std::vector<Index> path = loop_path(loop, sa.edge, sb.edge, forward);
      double mean = row.x;
      if (!path.empty()) {
        mean = 0;
        for (Index v : path) mean += surface.positions[v].x;
        mean /= static_cast<double>(path.size());
      }
      const double score = aft ? row.x - mean : mean - row.x;
      if (best.empty() || score > best_score) {
        best = path;
        best_score = score;
      }
    }
    if (best.empty() || best_score <= 0) {
      counts.open[aft ? 0 : 1] = true;
      continue;
    }
    // New fixed nodes resampled along a polyline of the surface's boundary or knuckles, between
    // two existing nodes; the nearest of `near` lends each its patch and (u, v).
    // With on_vertices, each node moves onto the nearest of `near` (a knuckle's own vertices,
    // which lie on the NURBS, where a point between them would lie on a chord).
    auto add_nodes = [&](const std::vector<Vec3d>& pts, Index first, Index last,
                         const std::vector<Index>& near, bool on_vertices = false) {
      std::vector<Index> ids{first};
      Index previous = kInvalid;
      for (const Vec3d& p : resample(pts, metric)) {
        Index nv = near.front();
        double nd = std::numeric_limits<double>::infinity();
        for (Index v : near) {
          const double d = squared_norm(surface.positions[v] - p);
          if (d < nd) {
            nd = d;
            nv = v;
          }
        }
        if (on_vertices && (nv == previous || nv == near.front() || nv == near.back())) continue;
        previous = nv;
        ids.push_back(static_cast<Index>(mesh.positions.size()));
        mesh.positions.push_back(on_vertices ? surface.positions[nv] : p);
        mesh.vertex_patch.push_back(surface.vertex_patch.empty() ? 0 : surface.vertex_patch[nv]);
        mesh.vertex_uv.push_back(surface.vertex_uv.empty() ? Vec2d{} : surface.vertex_uv[nv]);
        slots.push_back(NodeSlot{});
      }
      ids.push_back(last);
      return ids;
    };
    auto new_vertex = [&](Index v) {
      mesh.positions.push_back(surface.positions[v]);
      mesh.vertex_patch.push_back(surface.vertex_patch.empty() ? 0 : surface.vertex_patch[v]);
      mesh.vertex_uv.push_back(surface.vertex_uv.empty() ? Vec2d{} : surface.vertex_uv[v]);
      slots.push_back(NodeSlot{});
      return static_cast<Index>(mesh.positions.size() - 1);
    };
    auto points_of = [&](std::span<const Index> vs) {
      std::vector<Vec3d> p;
      for (Index v : vs) p.push_back(surface.positions[v]);
      return p;
    };
    auto zip = [&](const std::vector<Index>& inner, const std::vector<Index>& outer) {
      // inner runs along the station side, outer beyond it; both from the lower end.
      const std::vector<double> fi = chain_fractions(inner, mesh, metric);
      const std::vector<double> fo = chain_fractions(outer, mesh, metric);
      const ZipCounts n =
          aft ? zip_chains(outer, fo, inner, fi, mesh.positions, zip_options, mesh.faces)
              : zip_chains(inner, fi, outer, fo, mesh.positions, zip_options, mesh.faces);
      counts.quads += n.quads;
      counts.triangles += n.triangles;
    };
    const Index row_first = first_vertex[j][0];
    const Index row_last = row_first + static_cast<Index>(nodes[j].s[0].size() - 1);
    std::vector<Index> row_ids(nodes[j].s[0].size());
    for (std::size_t i = 0; i < row_ids.size(); ++i) row_ids[i] = row_first + static_cast<Index>(i);
    std::size_t p0 = 0, p1 = 0;
    const std::vector<Index> knuckle =
        end_knuckle(surface, features, best, row.x, aft, metric, p0, p1);
    if (knuckle.empty()) {
      // In pieces between the knuckles that run from the row to the boundary beyond it; each
      // knuckle's piece of line is the panel edge from its row node to its boundary vertex.
      const std::vector<CapSplit> splits =
          cap_splits(surface, features, best, c, nodes[j].s[0], row.x, aft, tol);
      std::size_t node0 = 0, place0 = 0;
      Index outer0 = row_first;
      std::vector<Vec3d> pts{c.points.front()};
      for (std::size_t k = 0; k <= splits.size(); ++k) {
        const bool last = k == splits.size();
        const std::size_t node1 = last ? row_ids.size() - 1 : splits[k].node;
        const std::size_t place1 = last ? best.size() - 1 : splits[k].place;
        for (std::size_t i = place0; i <= place1; ++i) pts.push_back(surface.positions[best[i]]);
        if (last) pts.push_back(c.points.back());
        const Index outer1 = last ? row_last : new_vertex(best[place1]);
        const std::vector<Index> inner(row_ids.begin() + static_cast<std::ptrdiff_t>(node0),
                                       row_ids.begin() + static_cast<std::ptrdiff_t>(node1 + 1));
        zip(inner, add_nodes(pts, outer0, outer1, best));
        if (!last) counts.knuckle_edges.push_back({row_ids[node1], outer1});
        node0 = node1;
        place0 = place1;
        outer0 = outer1;
        pts.assign(1, surface.positions[best[place1]]);
        ++place0;
      }
      continue;
    }
    // A transom: the strip from the row to the knuckle (with the boundary pieces either side of
    // it), then the transom itself, from the knuckle to the boundary beyond it.
    ++counts.transoms;
    const Index k0 = new_vertex(knuckle.front()), k1 = new_vertex(knuckle.back());
    std::vector<Index> near_side;
    {
      std::vector<Vec3d> pts{c.points.front()};
      for (std::size_t i = 0; i <= p0; ++i) pts.push_back(surface.positions[best[i]]);
      std::vector<Index> a = add_nodes(pts, row_first, k0, best);
      std::vector<Index> k = add_nodes(points_of(knuckle), k0, k1, knuckle, true);
      for (std::size_t i = 0; i + 1 < k.size(); ++i)
        counts.knuckle_edges.push_back({k[i], k[i + 1]});
      pts.assign(1, surface.positions[best[p1]]);
      for (std::size_t i = p1 + 1; i < best.size(); ++i) pts.push_back(surface.positions[best[i]]);
      pts.push_back(c.points.back());
      std::vector<Index> b = add_nodes(pts, k1, row_last, best);
      near_side = a;
      near_side.insert(near_side.end(), k.begin() + 1, k.end());
      near_side.insert(near_side.end(), b.begin() + 1, b.end());
      zip(row_ids, near_side);
      const std::vector<Index> far =
          add_nodes(points_of(std::span<const Index>(best).subspan(p0, p1 - p0 + 1)), k0, k1,
                    std::vector<Index>(best.begin() + static_cast<std::ptrdiff_t>(p0),
                                       best.begin() + static_cast<std::ptrdiff_t>(p1 + 1)));
      zip(k, far);
    }
  }
  return counts;
}

}  // namespace hm::structured
