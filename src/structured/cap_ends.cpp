// End caps. Beyond the first station (the stern, or a transom) and the last (the stem) the hull
// is a small region bounded by the end row and by the surface's boundary (keel and centre plane,
// the waterline, a transom edge). Its boundary path is resampled at the panel size, keeping its
// corners, and zipped against the row.
#include "structured/cap_ends.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "mesh/adjacency.h"
#include "structured/border_path.h"

namespace hm::structured {
namespace {}  // namespace

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
  std::map<Index, std::vector<Index>> next;
  for (const FeatureLine& l : features.knuckles) {
    const std::size_t n = l.vertices.size();
    for (std::size_t i = 0; i + 1 < n + (l.closed ? 1 : 0); ++i) {
      const Index a = l.vertices[i], b = l.vertices[(i + 1) % n];
      if (!beyond(a) || !beyond(b)) continue;
      next[a].push_back(b);
      next[b].push_back(a);
    }
  }
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
      ++counts.unmatched;
      continue;
    }
    const RowCurve& c = row.curves[0];
    const LoopSpot sa = nearest_boundary_edge(surface, adj, c.points.front());
    const LoopSpot sb = nearest_boundary_edge(surface, adj, c.points.back());
    if (sa.loop != sb.loop || sa.distance > tol || sb.distance > tol) {
      ++counts.unmatched;
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
      ++counts.unmatched;
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
      std::vector<Vec3d> pts{c.points.front()};
      for (const Vec3d& p : points_of(best)) pts.push_back(p);
      pts.push_back(c.points.back());
      zip(row_ids, add_nodes(pts, row_first, row_last, best));
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
