#include "tessellate/butterfly.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/parallel.h"

namespace hm {
namespace {

// Position of value x in the ring, or -1.
int find_in(std::span<const Index> r, Index x) {
  for (std::size_t i = 0; i < r.size(); ++i)
    if (r[i] == x) return static_cast<int>(i);
  return -1;
}

Index at(std::span<const Index> r, int i) {
  const int k = static_cast<int>(r.size());
  return r[((i % k) + k) % k];
}

// The stencil centred on an extraordinary (or any closed-ring) vertex a for edge (a, b).
bool centred_stencil(const VertexRings& rings, std::span<const Vec3d> p, Index a, Index b,
                     Vec3d& out) {
  if (rings.kind[a] != RingKind::kClosed) return false;
  const std::span<const Index> r = rings.of(a);
  const int j0 = find_in(r, b);
  const int k = static_cast<int>(r.size());
  if (j0 < 0 || k < 3) return false;
  out = 0.75 * p[a];
  for (int j = 0; j < k; ++j) out += extraordinary_weight(k, j) * p[at(r, j0 + j)];
  return true;
}

bool regular_stencil(const VertexRings& rings, std::span<const Vec3d> p, Index a, Index b, double w,
                     Vec3d& out) {
  if (rings.kind[a] != RingKind::kClosed || rings.kind[b] != RingKind::kClosed) return false;
  const std::span<const Index> ra = rings.of(a), rb = rings.of(b);
  if (ra.size() != 6 || rb.size() != 6) return false;
  const int j = find_in(ra, b), k = find_in(rb, a);
  if (j < 0 || k < 0) return false;
  out = (0.5 - w) * (p[a] + p[b]) + (0.125 + 2 * w) * (p[at(ra, j + 1)] + p[at(ra, j - 1)]) -
        (0.0625 + w) * (p[at(ra, j + 2)] + p[at(ra, j - 2)] + p[at(rb, k + 2)] + p[at(rb, k - 2)]) +
        w * (p[at(ra, j + 3)] + p[at(rb, k + 3)]);
  return true;
}

// The boundary neighbour of boundary vertex v other than `other`, or kInvalid.
Index boundary_neighbour(const VertexRings& rings, Index v, Index other) {
  if (rings.kind[v] != RingKind::kOpen) return kInvalid;
  const std::span<const Index> r = rings.of(v);
  if (r.front() == other) return r.back();
  if (r.back() == other) return r.front();
  return kInvalid;
}

}  // namespace

VertexRings build_rings(std::span<const Tri> tris, std::size_t n) {
  VertexRings rg;
  std::vector<Index> count(n + 1, 0);
  for (const Tri& t : tris)
    for (Index v : t) ++count[v + 1];
  // Incident corners in CSR form: corner 3t + i.
  std::vector<Index> start(n + 1, 0);
  for (std::size_t v = 0; v < n; ++v) start[v + 1] = start[v] + count[v + 1];
  std::vector<Index> corners(start[n]);
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int i = 0; i < 3; ++i) corners[fill[tris[t][i]]++] = Index(3 * t + i);
  rg.offset.resize(n);
  rg.size.assign(n, 0);
  rg.kind.assign(n, RingKind::kNone);
  for (std::size_t v = 0; v < n; ++v) rg.offset[v] = Index(start[v] + v);  // room for one more
  rg.ring.assign(start[n] + n, kInvalid);
  parallel_for(0, n, [&](std::size_t v) {
    const Index b = start[v], e = start[v + 1];
    const Index m = e - b;
    if (m == 0) return;
    // Link edges x -> y of the fan (counter-clockwise around v).
    auto from = [&](Index c) { return tris[corners[c] / 3][(corners[c] % 3 + 1) % 3]; };
    auto to = [&](Index c) { return tris[corners[c] / 3][(corners[c] % 3 + 2) % 3]; };
    Index first = b;
    int open_starts = 0;
    for (Index c = b; c < e; ++c) {
      bool has_in = false;
      for (Index d = b; d < e && !has_in; ++d) has_in = to(d) == from(c);
      if (!has_in) {
        ++open_starts;
        first = c;
      }
    }
    if (open_starts > 1) return;
    Index* out = rg.ring.data() + rg.offset[v];
    Index len = 0, used = 0;
    Index cur = first;
    out[len++] = from(cur);
    while (true) {
      ++used;
      const Index y = to(cur);
      if (open_starts == 0 && y == out[0]) break;
      if (len == m + 1) return;  // a fan that does not close: not a disk
      out[len++] = y;
      Index next = kInvalid;
      for (Index d = b; d < e; ++d)
        if (from(d) == y) next = d;
      if (next == kInvalid || used > m) break;
      cur = next;
    }
    if (used != m) return;  // more than one fan: not a disk
    rg.size[v] = len;
    rg.kind[v] = open_starts == 0 ? RingKind::kClosed : RingKind::kOpen;
  });
  return rg;
}

double extraordinary_weight(int k, int j) {
  if (k == 3) return j == 0 ? 5.0 / 12 : -1.0 / 12;
  if (k == 4) return j == 0 ? 3.0 / 8 : (j == 2 ? -1.0 / 8 : 0.0);
  const double t = 2 * std::numbers::pi * j / k;
  return (0.25 + std::cos(t) + 0.5 * std::cos(2 * t)) / k;
}

Vec3d butterfly_midpoint(const VertexRings& rings, std::span<const Vec3d> p,
                         std::span<const std::uint8_t> is_boundary, Index a, Index b,
                         bool boundary_edge, double w) {
  const Vec3d mid = 0.5 * (p[a] + p[b]);
  if (boundary_edge) {
    if (!is_boundary[a] || !is_boundary[b]) return mid;
    const Index pa = boundary_neighbour(rings, a, b), pb = boundary_neighbour(rings, b, a);
    if (pa == kInvalid || pb == kInvalid) return mid;
    return (9.0 / 16) * (p[a] + p[b]) - (1.0 / 16) * (p[pa] + p[pb]);
  }
  Vec3d q;
  if (regular_stencil(rings, p, a, b, w, q)) return q;
  const bool ca = rings.kind[a] == RingKind::kClosed, cb = rings.kind[b] == RingKind::kClosed;
  const bool ea = ca && rings.size[a] != 6, eb = cb && rings.size[b] != 6;
  Vec3d qa, qb;
  const bool ha = centred_stencil(rings, p, a, b, qa), hb = centred_stencil(rings, p, b, a, qb);
  // Both ends extraordinary (or the only closed rings available): the average of their stencils.
  if (ha && hb && (ea == eb)) return 0.5 * (qa + qb);
  if (ha && (ea || !hb)) return qa;
  if (hb) return qb;
  return mid;
}

}  // namespace hm
