// The mutable mesh of the coarsening: built from the merged surface and its features, with the
// feature lines as prev / next links and the deviation witnesses as per-face lists.
#include "unstructured/coarsen_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"
#include "kernels/collapse_cost.h"

namespace hm::coarsen_detail {
namespace {

void build_lines(const FeatureSet& features, State& s) {
  auto add = [&](const FeatureLine& l) {
    FineLine fl;
    fl.vertices = l.vertices;
    fl.closed = l.closed;
    fl.arclength.resize(l.vertices.size(), 0.0);
    for (std::size_t i = 1; i < l.vertices.size(); ++i) {
      fl.arclength[i] = fl.arclength[i - 1] +
                        norm(s.fine_positions[l.vertices[i]] - s.fine_positions[l.vertices[i - 1]]);
    }
    s.lines.push_back(std::move(fl));
  };
  for (const FeatureLine& l : features.knuckles) add(l);
  for (const BoundaryRun& b : features.boundaries) add(b);
}

// Squared distance from p to the fine triangles around fine vertex w.
double fan_distance2(const State& s, const Vec3d& p, Index w) {
  double best = std::numeric_limits<double>::infinity();
  for (Index k = s.fine_vf_begin[w]; k < s.fine_vf_begin[w + 1]; ++k) {
    const auto& t = s.fine_faces[s.fine_vf[k]];
    best = std::min(
        best, kernel::point_triangle_distance2(p, s.fine_positions[t[0]], s.fine_positions[t[1]],
                                               s.fine_positions[t[2]]));
  }
  return best;
}

// The witnesses are fine vertices, so they bound the distance from the surface to the panels
// at the fine vertices only. Over a curved hull the panel strays furthest at its centre, between
// witnesses, and the sparser the fine mesh the more it can hide there. So a new panel whose
// witnesses reach kSampleFrom of the bound has its centroid and edge midpoints measured against
// the fine mesh: each sample against the fine triangles around the nearest of the panel's
// witnesses and corners (the two nearest when the first fan is too far). That distance is exact
// or too large, never too small, so the report's samples (the same points, against the NURBS,
// which the fine mesh follows to its chord error) stay inside the bound.
constexpr double kSampleFrom = 0.5;

bool new_panels_near_surface(const State& s, std::span<const Index> from,
                             std::span<const Index> targets,
                             std::span<const std::pair<Index, Index>> moves) {
  const double from2 = kSampleFrom * kSampleFrom * s.bound * s.bound;
  const double bound2 = s.sample_bound * s.sample_bound;
  thread_local std::vector<Index> near;
  for (Index f : targets) {
    if (std::find(from.begin(), from.end(), f) == from.end()) continue;  // unchanged panel
    const auto& t = s.faces[f];
    const Vec3d &a = s.position[t[0]], &b = s.position[t[1]], &c = s.position[t[2]];
    near.clear();
    double worst2 = 0;
    for (const auto& [w, to] : moves) {
      if (to != f) continue;
      near.push_back(w);
      worst2 = std::max(worst2, kernel::point_triangle_distance2(s.fine_positions[w], a, b, c));
    }
    if (worst2 <= from2) continue;
    for (Index v : t) near.push_back(s.source[v]);
    const Vec3d samples[4] = {(a + b + c) / 3.0, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)};
    for (const Vec3d& p : samples) {
      Index n1 = kInvalid, n2 = kInvalid;
      double d1 = std::numeric_limits<double>::infinity(), d2 = d1;
      for (Index w : near) {
        const double d = squared_norm(s.fine_positions[w] - p);
        if (d < d1 || (d == d1 && w < n1)) {
          n2 = n1, d2 = d1;
          n1 = w, d1 = d;
        } else if (d < d2 || (d == d2 && w < n2)) {
          n2 = w, d2 = d;
        }
      }
      if (fan_distance2(s, p, n1) <= bound2) continue;
      if (n2 == kInvalid || n2 == n1 || fan_distance2(s, p, n2) > bound2) return false;
    }
  }
  return true;
}

}  // namespace

void build_state(std::span<const Patch> patches, const SurfaceMesh& fine,
                 const EdgeAdjacency& adjacency, const FeatureSet& features, State& s) {
  const std::size_t nv = fine.vertex_count(), nf = fine.face_count();
  if (fine.vertex_patch.size() != nv || fine.vertex_uv.size() != nv ||
      fine.face_patch.size() != nf || features.edge_knuckle.size() != adjacency.edges.size() ||
      features.vertex_feature.size() != nv) {
    throw GeometryError("coarsen: the merged surface's arrays and its features disagree in size");
  }
  if (!adjacency.nonmanifold_edges.empty()) {
    throw GeometryError("coarsen: the merged surface has " +
                        std::to_string(adjacency.nonmanifold_edges.size()) +
                        " non-manifold edges; merge it first");
  }
  s.patches = patches;
  s.patch_net.resize(patches.size());
  parallel_for(0, patches.size(),
               [&](std::size_t p) { s.patch_net[p] = net_size(patches[p].surface); });
  s.fine_positions = fine.positions;
  s.fine_vertex_patch = fine.vertex_patch;
  s.fine_uv = fine.vertex_uv;
  s.position = fine.positions;
  s.uv = fine.vertex_uv;
  s.vpatch = fine.vertex_patch;
  s.source.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) s.source[v] = static_cast<Index>(v);
  s.alive.assign(nv, 1);
  s.faces.resize(nf);
  s.face_patch = fine.face_patch;
  s.face_alive.assign(nf, 1);
  s.live_faces = nf;
  s.face_witness.assign(nf, kInvalid);
  s.witness_next.assign(nv, kInvalid);
  s.is_witness.assign(nv, 0);

  // Faces around each vertex (in face order), and the rest normal of each vertex.
  std::vector<Index> count(nv, 0);
  for (std::size_t f = 0; f < nf; ++f) {
    const Face& fc = fine.faces[f];
    if (!is_triangle(fc)) throw GeometryError("coarsen: the merged surface must be triangles");
    for (int c = 0; c < 3; ++c) {
      if (fc[c] >= nv)
        throw GeometryError("coarsen: face " + std::to_string(f) + " names a missing vertex");
      ++count[fc[c]];
    }
    s.faces[f] = {fc[0], fc[1], fc[2]};
  }
  s.vertex_faces.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) s.vertex_faces[v].reserve(count[v] + 2);
  for (std::size_t f = 0; f < nf; ++f) {
    for (int c = 0; c < 3; ++c) s.vertex_faces[s.faces[f][c]].push_back(static_cast<Index>(f));
  }
  // The fine mesh stays as it is for the samples' distances: count -> scan -> scatter.
  s.fine_faces = fine.faces;
  s.fine_vf_begin.assign(nv + 1, 0);
  for (std::size_t v = 0; v < nv; ++v) s.fine_vf_begin[v + 1] = s.fine_vf_begin[v] + count[v];
  s.fine_vf.resize(s.fine_vf_begin[nv]);
  {
    std::vector<Index> next(s.fine_vf_begin.begin(), s.fine_vf_begin.end() - 1);
    for (std::size_t f = 0; f < nf; ++f) {
      for (int c = 0; c < 3; ++c) s.fine_vf[next[s.faces[f][c]]++] = static_cast<Index>(f);
    }
  }
  s.rest_normal.assign(nv, Vec3d{});
  parallel_for(0, nv, [&](std::size_t v) {
    Vec3d n;
    for (Index f : s.vertex_faces[v]) {
      const auto& t = s.faces[f];
      n += cross(s.position[t[1]] - s.position[t[0]], s.position[t[2]] - s.position[t[0]]);
    }
    s.rest_normal[v] = normalized(n);
  });

  // Feature degree per vertex: knuckle and boundary edges.
  std::vector<std::uint8_t> degree(nv, 0);
  std::vector<std::array<Index, 2>> feature_edges;
  for (std::size_t e = 0; e < adjacency.edges.size(); ++e) {
    const MeshEdge& me = adjacency.edges[e];
    if (me.uses == 1 || features.edge_knuckle[e]) {
      degree[me.v0] = static_cast<std::uint8_t>(std::min(degree[me.v0] + 1, 255));
      degree[me.v1] = static_cast<std::uint8_t>(std::min(degree[me.v1] + 1, 255));
      feature_edges.push_back({me.v0, me.v1});
    }
  }
  s.kind.assign(nv, Kind::kSmooth);
  for (std::size_t v = 0; v < nv; ++v) {
    if (count[v] == 0) {
      s.alive[v] = 0;  // not used by any face: not part of the surface
    } else if (features.vertex_feature[v] == VertexFeature::kCorner ||
               (degree[v] != 0 && degree[v] != 2)) {
      s.kind[v] = Kind::kCorner;
    } else if (degree[v] == 2) {
      s.kind[v] = Kind::kOnLine;
    }
  }
  // Lines: the prev / next links of on-line vertices, in each fine line's order.
  build_lines(features, s);
  s.line_nbr.assign(nv, {kInvalid, kInvalid});
  s.spot.assign(nv, LineSpot{});
  for (std::size_t li = 0; li < s.lines.size(); ++li) {
    const FineLine& l = s.lines[li];
    const std::size_t n = l.vertices.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Index v = l.vertices[i];
      if (s.kind[v] != Kind::kOnLine) continue;
      const bool has_prev = i > 0 || l.closed, has_next = i + 1 < n || l.closed;
      if (!has_prev || !has_next) {
        s.kind[v] = Kind::kCorner;  // a line end the features did not call a corner
        continue;
      }
      s.line_nbr[v] = {l.vertices[(i + n - 1) % n], l.vertices[(i + 1) % n]};
      s.spot[v] = {static_cast<Index>(li), static_cast<Index>(i)};
    }
  }
  // An on-line vertex no line lists (the features disagree with the edges) is held fixed.
  for (std::size_t v = 0; v < nv; ++v) {
    if (s.kind[v] == Kind::kOnLine && s.line_nbr[v][0] == kInvalid) s.kind[v] = Kind::kCorner;
  }
  for (const auto& e : feature_edges) {
    if (s.kind[e[0]] == Kind::kCorner && s.kind[e[1]] == Kind::kCorner) {
      s.corner_edges.push_back({std::min(e[0], e[1]), std::max(e[0], e[1])});
    }
  }
  std::sort(s.corner_edges.begin(), s.corner_edges.end());
}

bool is_feature_edge(const State& s, Index a, Index b) {
  if (s.kind[a] == Kind::kOnLine) return s.line_nbr[a][0] == b || s.line_nbr[a][1] == b;
  if (s.kind[b] == Kind::kOnLine) return s.line_nbr[b][0] == a || s.line_nbr[b][1] == a;
  if (s.kind[a] == Kind::kCorner && s.kind[b] == Kind::kCorner) {
    const std::array<Index, 2> key{std::min(a, b), std::max(a, b)};
    return std::binary_search(s.corner_edges.begin(), s.corner_edges.end(), key);
  }
  return false;
}

bool reassign_witnesses(State& s, std::span<const Index> from, Index extra,
                        std::span<const Index> targets, double& deviation) {
  // Gather (witness, chosen target) first; commit only when every witness is within the bound.
  thread_local std::vector<std::pair<Index, Index>> moves;
  // Per target: the centroid and the radius of the ball around it that holds the triangle, so
  // that a target that cannot be nearest is passed over without the exact distance.
  thread_local std::vector<Vec3d> centre;
  thread_local std::vector<double> radius;
  moves.clear();
  centre.resize(targets.size());
  radius.resize(targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const auto& t = s.faces[targets[i]];
    const Vec3d &a = s.position[t[0]], &b = s.position[t[1]], &c = s.position[t[2]];
    centre[i] = (a + b + c) / 3.0;
    radius[i] = std::sqrt(std::max(
        {squared_norm(a - centre[i]), squared_norm(b - centre[i]), squared_norm(c - centre[i])}));
  }
  const double bound2 = s.bound * s.bound;
  double worst2 = 0;
  // The nearest target, the first in `targets` among equals (as a scan in order finds it).
  // `first` is tried first: the witness's own face when it is a target, usually the nearest.
  auto place = [&](Index w, std::size_t first) {
    const Vec3d& p = s.fine_positions[w];
    double best = std::numeric_limits<double>::infinity(), best_root = best;
    std::size_t best_i = targets.size();
    auto consider = [&](std::size_t i) {
      const auto& t = s.faces[targets[i]];
      const double d2 =
          kernel::point_triangle_distance2(p, s.position[t[0]], s.position[t[1]], s.position[t[2]]);
      if (d2 < best || (d2 == best && i < best_i)) {
        best = d2;
        best_root = std::sqrt(d2);
        best_i = i;
      }
    };
    if (first < targets.size()) consider(first);
    for (std::size_t i = 0; i < targets.size(); ++i) {
      if (i == first) continue;
      // |p - centre| - radius is a lower bound on the distance; the margin covers its rounding.
      const double dc = norm(p - centre[i]);
      if (dc - radius[i] > best_root * (1 + 1e-9) + 1e-12 * (dc + radius[i])) continue;
      consider(i);
    }
    worst2 = std::max(worst2, best);
    moves.emplace_back(w, best_i < targets.size() ? targets[best_i] : kInvalid);
    return best <= bound2;
  };
  if (extra != kInvalid && !s.is_witness[extra] && !place(extra, targets.size())) return false;
  for (Index f : from) {
    const auto own = std::find(targets.begin(), targets.end(), f);
    const std::size_t first = static_cast<std::size_t>(own - targets.begin());
    for (Index w = s.face_witness[f]; w != kInvalid; w = s.witness_next[w]) {
      if (!place(w, first)) return false;
    }
  }
  if (!new_panels_near_surface(s, from, targets, moves)) return false;
  for (Index f : from) s.face_witness[f] = kInvalid;
  // Pushing to the list heads in gathering order: the lists come out in a fixed order.
  for (const auto& [w, f] : moves) {
    s.witness_next[w] = s.face_witness[f];
    s.face_witness[f] = w;
    s.is_witness[w] = 1;
  }
  deviation = std::sqrt(worst2);
  return true;
}

bool back_to_back(const State& s, const std::array<Index, 3>& a, const std::array<Index, 3>& b) {
  auto twice_area_normal = [&](const std::array<Index, 3>& t) {
    return cross(s.position[t[1]] - s.position[t[0]], s.position[t[2]] - s.position[t[0]]);
  };
  const Vec3d na = twice_area_normal(a), nb = twice_area_normal(b);
  if (dot(na, nb) >= 0) return false;
  const Vec3d ca = (s.position[a[0]] + s.position[a[1]] + s.position[a[2]]) / 3.0;
  const Vec3d cb = (s.position[b[0]] + s.position[b[1]] + s.position[b[2]]) / 3.0;
  // |ca - cb| < k sqrt(area), squared, with area = |n| / 2.
  return squared_norm(ca - cb) <
         kCloseCentreFraction * kCloseCentreFraction * 0.5 * std::min(norm(na), norm(nb));
}

bool back_to_back_across(const State& s, const std::array<Index, 3>& corners,
                         std::span<const Index> skip) {
  for (int e = 0; e < 3; ++e) {
    const Index p = corners[e], q = corners[(e + 1) % 3];
    for (Index g : s.vertex_faces[p]) {
      if (std::find(skip.begin(), skip.end(), g) != skip.end()) continue;
      const auto& tg = s.faces[g];
      if (has_corner(tg, q) && back_to_back(s, corners, tg)) return true;
    }
  }
  return false;
}

Index line_index(const State& s, Index v, Index w, bool before) {
  const LineSpot sp = s.spot[v];
  if (s.kind[w] == Kind::kOnLine) return s.spot[w].line == sp.line ? s.spot[w].k : kInvalid;
  const FineLine& l = s.lines[sp.line];
  const std::size_t n = l.vertices.size();
  const std::size_t steps = l.closed ? n - 1 : (before ? sp.k : n - 1 - sp.k);
  for (std::size_t i = 1; i <= steps; ++i) {
    const std::size_t k = before ? (sp.k + n - i) % n : (sp.k + i) % n;
    if (l.vertices[k] == w) return static_cast<Index>(k);
  }
  return kInvalid;
}

bool line_chord_ok(const State& s, Index line, Index ka, Index kb, const Vec3d& pa,
                   const Vec3d& pb) {
  const FineLine& l = s.lines[line];
  const std::size_t n = l.vertices.size();
  const Vec3d ab = pb - pa;
  const double len2 = dot(ab, ab);
  const double bound2 = s.bound * s.bound;
  for (std::size_t k = (ka + 1) % n; k != kb; k = (k + 1) % n) {
    const Vec3d& p = s.fine_positions[l.vertices[k]];
    const double t = len2 > 0 ? std::clamp(dot(p - pa, ab) / len2, 0.0, 1.0) : 0.0;
    if (squared_norm(p - (pa + t * ab)) > bound2) return false;
    if (!l.closed && k + 1 >= n) return false;  // ran off an open line: indices out of order
  }
  return true;
}

double face_index(const State& s, Index f) {
  const auto& t = s.faces[f];
  const Vec3d &a = s.position[t[0]], &b = s.position[t[1]], &c = s.position[t[2]];
  const double area = 0.5 * norm(cross(b - a, c - a));
  kernel::CollapseQualities q;
  q.shape = kernel::triangle_shape(a, b, c);
  // Area ratio against the faces across its edges.
  double lo = 1;
  for (int e = 0; e < 3; ++e) {
    const Index u = t[e], w = t[(e + 1) % 3];
    for (Index g : s.vertex_faces[u]) {
      if (g == f) continue;
      const auto& tg = s.faces[g];
      if (tg[0] != w && tg[1] != w && tg[2] != w) continue;
      const double ag = 0.5 * norm(cross(s.position[tg[1]] - s.position[tg[0]],
                                         s.position[tg[2]] - s.position[tg[0]]));
      const double hi = std::max(area, ag);
      lo = std::min(lo, hi > 0 ? std::min(area, ag) / hi : 0.0);
    }
  }
  q.area_ratio = lo;
  const double cf = std::min({s.cfactor[t[0]], s.cfactor[t[1]], s.cfactor[t[2]]});
  const double l = kernel::equilateral_edge(area);
  q.curvature = kernel::size_quality(l / (s.field.h0 * cf));
  q.sources = kernel::size_quality(l / (s.field.h0 * s.field.source_factor((a + b + c) / 3.0)));
  return kernel::weighted_index(q, s.weights);
}

}  // namespace hm::coarsen_detail
