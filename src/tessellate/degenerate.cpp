#include "tessellate/degenerate.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include "tessellate/initial_grid.h"

namespace hm {
namespace {

constexpr int kClosureSamples = 9;

Index find_root(std::vector<Index>& parent, Index v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

// Rewrites triangle corners through new_id, drops triangles with a repeated corner.
void remap_tris(PatchMesh& m, const std::vector<Index>& new_id) {
  std::size_t out = 0;
  for (std::size_t t = 0; t < m.tris.size(); ++t) {
    Tri r{new_id[m.tris[t][0]], new_id[m.tris[t][1]], new_id[m.tris[t][2]]};
    if (r[0] == r[1] || r[1] == r[2] || r[2] == r[0]) continue;
    m.tris[out] = r;
    m.tri_uv[out] = m.tri_uv[t];
    ++out;
  }
  m.tris.resize(out);
  m.tri_uv.resize(out);
}

}  // namespace

Closure detect_closure(const NurbsSurface& s, double tol) {
  Closure c;
  c.closed_u = c.closed_v = true;
  for (int i = 0; i < kClosureSamples; ++i) {
    const double f = double(i) / (kClosureSamples - 1);
    const double v = s.v0 + f * (s.v1 - s.v0), u = s.u0 + f * (s.u1 - s.u0);
    if (norm(evaluate(s, s.u0, v) - evaluate(s, s.u1, v)) > tol) c.closed_u = false;
    if (norm(evaluate(s, u, s.v0) - evaluate(s, u, s.v1)) > tol) c.closed_v = false;
  }
  return c;
}

CollapsedSides detect_collapsed(const NurbsSurface& s, double tol) {
  CollapsedSides c;
  c.su0 = s.u0, c.su1 = s.u1, c.sv0 = s.v0, c.sv1 = s.v1;
  c.u0 = iso_line_length(s, false, s.u0, s.v0, s.v1, kClosureSamples) <= tol;
  c.u1 = iso_line_length(s, false, s.u1, s.v0, s.v1, kClosureSamples) <= tol;
  c.v0 = iso_line_length(s, true, s.v0, s.u0, s.u1, kClosureSamples) <= tol;
  c.v1 = iso_line_length(s, true, s.v1, s.u0, s.u1, kClosureSamples) <= tol;
  return c;
}

void join_seams(PatchMesh& m, std::size_t nu, std::size_t nv, const Closure& c) {
  if (!c.closed_u && !c.closed_v) return;
  std::vector<Index> new_id(m.vertex_count());
  std::iota(new_id.begin(), new_id.end(), Index{0});
  for (std::size_t j = 0; j < nv; ++j) {
    for (std::size_t i = 0; i < nu; ++i) {
      std::size_t ti = (c.closed_u && i + 1 == nu) ? 0 : i;
      std::size_t tj = (c.closed_v && j + 1 == nv) ? 0 : j;
      new_id[i + nu * j] = Index(ti + nu * tj);
    }
  }
  remap_tris(m, new_id);
}

void join_collapsed(PatchMesh& m, std::size_t nu, std::size_t nv, const CollapsedSides& c) {
  if (!c.any()) return;
  std::vector<Index> new_id(m.vertex_count());
  std::iota(new_id.begin(), new_id.end(), Index{0});
  auto join = [&](std::size_t first, std::size_t step, std::size_t count) {
    for (std::size_t k = 1; k < count; ++k) new_id[first + k * step] = new_id[first];
  };
  // Two collapsed sides that meet share a corner: process in a fixed order, resolving chains.
  if (c.v0) join(0, 1, nu);
  if (c.v1) join(nu * (nv - 1), 1, nu);
  if (c.u0) join(0, nu, nv);
  if (c.u1) join(nu - 1, nu, nv);
  for (Index v = 0; v < new_id.size(); ++v)
    while (new_id[new_id[v]] != new_id[v]) new_id[v] = new_id[new_id[v]];
  remap_tris(m, new_id);
}

void merge_coincident(PatchMesh& m, double tol) {
  // Every vertex is a candidate: next to an apex, the midpoints of two edges that become one
  // edge after the merge coincide too, and they are interior vertices.
  std::vector<Index> cand(m.vertex_count());
  std::iota(cand.begin(), cand.end(), Index{0});
  std::sort(cand.begin(), cand.end(), [&](Index a, Index b) {
    return m.xyz[a].x < m.xyz[b].x || (m.xyz[a].x == m.xyz[b].x && a < b);
  });
  std::vector<Index> parent(m.vertex_count());
  std::iota(parent.begin(), parent.end(), Index{0});
  bool any = false;
  const double tol2 = tol * tol;
  for (std::size_t i = 0; i < cand.size(); ++i) {
    for (std::size_t k = i + 1; k < cand.size(); ++k) {
      if (m.xyz[cand[k]].x - m.xyz[cand[i]].x > tol) break;
      if (squared_norm(m.xyz[cand[k]] - m.xyz[cand[i]]) > tol2) continue;
      Index a = find_root(parent, cand[i]), b = find_root(parent, cand[k]);
      if (a == b) continue;
      parent[std::max(a, b)] = std::min(a, b);  // the lowest index represents the group
      any = true;
    }
  }
  if (!any) return;
  std::vector<Index> new_id(m.vertex_count());
  for (Index v = 0; v < m.vertex_count(); ++v) new_id[v] = find_root(parent, v);
  remap_tris(m, new_id);
  compact_vertices(m);
}

namespace {

constexpr int kZeroAreaPasses = 4;

double tri_area(const PatchMesh& m, const Tri& t) {
  return 0.5 * norm(cross(m.xyz[t[1]] - m.xyz[t[0]], m.xyz[t[2]] - m.xyz[t[0]]));
}

bool is_zero(const PatchMesh& m, const Tri& t, double f) {
  double longest = 0;
  for (int i = 0; i < 3; ++i)
    longest = std::max(longest, squared_norm(m.xyz[t[(i + 1) % 3]] - m.xyz[t[i]]));
  return tri_area(m, t) <= f * longest;
}

Vec2d corner_of(const PatchMesh& m, std::size_t t, Index v) {
  for (int i = 0; i < 3; ++i)
    if (m.tris[t][i] == v) return m.tri_uv[t][i];
  return m.uv[v];
}

}  // namespace

void remove_zero_area(PatchMesh& m, double f) {
  bool any_removed = false;
  for (int pass = 0; pass < kZeroAreaPasses; ++pass) {
    // Directed edge (a, b) -> triangle, sorted for lookup.
    std::vector<std::pair<std::uint64_t, Index>> edges;
    edges.reserve(3 * m.tri_count());
    for (std::size_t t = 0; t < m.tri_count(); ++t)
      for (int i = 0; i < 3; ++i)
        edges.push_back({(std::uint64_t{m.tris[t][i]} << 32) | m.tris[t][(i + 1) % 3], Index(t)});
    std::sort(edges.begin(), edges.end());
    auto find = [&](Index a, Index b) {
      const std::uint64_t k = (std::uint64_t{a} << 32) | b;
      auto it = std::lower_bound(edges.begin(), edges.end(), std::pair{k, Index{0}});
      return it != edges.end() && it->first == k ? it->second : kInvalid;
    };
    std::vector<std::uint8_t> touched(m.tri_count(), 0), dead(m.tri_count(), 0);
    bool changed = false;
    for (std::size_t t = 0; t < m.tri_count(); ++t) {
      if (touched[t] || !is_zero(m, m.tris[t], f)) continue;
      int k = 0;  // longest edge (v[k], v[k + 1])
      double best = -1;
      for (int i = 0; i < 3; ++i) {
        const double l = squared_norm(m.xyz[m.tris[t][(i + 1) % 3]] - m.xyz[m.tris[t][i]]);
        if (l > best) best = l, k = i;
      }
      const Index a = m.tris[t][k], b = m.tris[t][(k + 1) % 3], c = m.tris[t][(k + 2) % 3];
      const Index nb = find(b, a);
      // On the boundary, c lies on the boundary edge (a, b); next to another zero triangle, the
      // parametrisation folds a region onto a curve and there is no surface to cover.
      if (nb == kInvalid || is_zero(m, m.tris[nb], f)) {
        dead[t] = touched[t] = 1;
        changed = any_removed = true;
        continue;
      }
      if (touched[nb] || dead[nb]) continue;
      Index d = kInvalid;
      for (Index v : m.tris[nb])
        if (v != a && v != b) d = v;
      const Tri t1{a, d, c}, t2{d, b, c};
      if (d == kInvalid || d == c || is_zero(m, t1, f) || is_zero(m, t2, f)) {
        dead[t] = touched[t] = 1;
        changed = any_removed = true;
        continue;
      }
      const TriUv w1{corner_of(m, t, a), corner_of(m, nb, d), corner_of(m, t, c)};
      const TriUv w2{corner_of(m, nb, d), corner_of(m, t, b), corner_of(m, t, c)};
      m.tris[t] = t1, m.tri_uv[t] = w1;
      m.tris[nb] = t2, m.tri_uv[nb] = w2;
      touched[t] = touched[nb] = 1;
      changed = true;
    }
    if (any_removed) {
      std::size_t out = 0;
      for (std::size_t t = 0; t < m.tri_count(); ++t) {
        if (dead[t]) continue;
        m.tris[out] = m.tris[t];
        m.tri_uv[out++] = m.tri_uv[t];
      }
      m.tris.resize(out);
      m.tri_uv.resize(out);
    }
    if (!changed) break;
  }
  if (any_removed) compact_vertices(m);
}

void compact_vertices(PatchMesh& m) {
  std::vector<Index> new_id(m.vertex_count(), kInvalid);
  for (const Tri& t : m.tris)
    for (Index v : t) new_id[v] = 0;
  Index n = 0;
  for (Index v = 0; v < m.vertex_count(); ++v) {
    if (new_id[v] == kInvalid) continue;
    new_id[v] = n;
    m.xyz[n] = m.xyz[v];
    m.uv[n] = m.uv[v];
    m.flags[n] = m.flags[v];
    ++n;
  }
  m.xyz.resize(n);
  m.uv.resize(n);
  m.flags.resize(n);
  for (Tri& t : m.tris)
    for (Index& v : t) v = new_id[v];
}

}  // namespace hm
