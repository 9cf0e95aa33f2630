// flip_edges_3d: collect the neighbours across every edge -> for each interior edge, score the
// flip (smallest 3D angle before and after) -> apply it when it is better and valid in the chart
// and in 3D -> repeat until a pass flips nothing.
#include "tessellate/flip_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace hm {
namespace {

// A flip must raise the smallest angle by this much (radians): ties do not flip back and forth.
constexpr double kMinGain = 1e-9;
// A chart triangle is kept counter-clockwise with this margin, relative to its squared longest
// edge: a near-flat quad is not flipped into a triangle of zero parameter area.
constexpr double kUvMargin = 1e-12;

double corner_angle(const Vec3d& p, const Vec3d& q, const Vec3d& r) {
  const Vec3d a = q - p, b = r - p;
  return std::atan2(norm(cross(a, b)), dot(a, b));
}

double smallest_angle(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)});
}

bool ccw_2d(const Vec2d& a, const Vec2d& b, const Vec2d& c) {
  const Vec2d ab = b - a, ac = c - a, bc = c - b;
  const double longest = std::max({dot(ab, ab), dot(ac, ac), dot(bc, bc)});
  return cross(ab, ac) > kUvMargin * longest;
}

// nbr[t][i]: the triangle across edge (tris[t][i], tris[t][i + 1]), or kInvalid on the boundary
// (or at an edge with more than two triangles, which never flips).
std::vector<std::array<Index, 3>> neighbours(const PatchMesh& m) {
  EdgeTable table;
  table.build(m.tris);
  std::vector<std::array<Index, 3>> nbr(m.tri_count(), {kInvalid, kInvalid, kInvalid});
  for (std::size_t e = 0; e < table.count(); ++e) {
    if (table.size(Index(e)) != 2) continue;
    const Index x = table.he[table.first[e]].corner, y = table.he[table.first[e] + 1].corner;
    nbr[x / 3][x % 3] = y / 3;
    nbr[y / 3][y % 3] = x / 3;
  }
  return nbr;
}

int edge_index(const Tri& t, Index a, Index b) {
  for (int i = 0; i < 3; ++i)
    if (t[i] == a && t[(i + 1) % 3] == b) return i;
  return -1;
}

void repoint(std::array<Index, 3>& n, Index from, Index to) {
  for (Index& x : n)
    if (x == from) x = to;
}

}  // namespace

std::size_t flip_edges_3d(PatchMesh& m, std::span<const Vec2d> plane, int max_passes) {
  std::vector<std::array<Index, 3>> nbr = neighbours(m);
  std::size_t flips = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    std::size_t this_pass = 0;
    for (Index t = 0; t < m.tri_count(); ++t) {
      for (int i = 0; i < 3; ++i) {
        const Index u = nbr[t][i];
        if (u == kInvalid || u < t) continue;  // each interior edge once, from its lower triangle
        const Index a = m.tris[t][i], b = m.tris[t][(i + 1) % 3], c = m.tris[t][(i + 2) % 3];
        const int j = edge_index(m.tris[u], b, a);
        if (j < 0) continue;  // wound against t: not a flippable pair
        const Index d = m.tris[u][(j + 2) % 3];
        if (d == c) continue;
        // Score: the quad a, d, b, c (counter-clockwise) split along c-d instead of a-b.
        const Vec3d &pa = m.xyz[a], &pb = m.xyz[b], &pc = m.xyz[c], &pd = m.xyz[d];
        const double before = std::min(smallest_angle(pa, pb, pc), smallest_angle(pb, pa, pd));
        const double after = std::min(smallest_angle(pc, pa, pd), smallest_angle(pd, pb, pc));
        if (!(after > before + kMinGain)) continue;
        if (!ccw_2d(plane[c], plane[a], plane[d]) || !ccw_2d(plane[d], plane[b], plane[c]))
          continue;
        const Vec3d n_old = cross(pb - pa, pc - pa) + cross(pa - pb, pd - pb);
        if (!(dot(cross(pa - pc, pd - pc), n_old) > 0) ||
            !(dot(cross(pb - pd, pc - pd), n_old) > 0))
          continue;
        // Apply: t = (c, a, d), u = (d, b, c); the outer neighbours across a-d and b-c swap owner.
        const Index n_bc = nbr[t][(i + 1) % 3], n_ca = nbr[t][(i + 2) % 3];
        const Index n_ad = nbr[u][(j + 1) % 3], n_db = nbr[u][(j + 2) % 3];
        m.tris[t] = {c, a, d};
        m.tris[u] = {d, b, c};
        m.tri_uv[t] = {m.uv[c], m.uv[a], m.uv[d]};
        m.tri_uv[u] = {m.uv[d], m.uv[b], m.uv[c]};
        nbr[t] = {n_ca, n_ad, u};
        nbr[u] = {n_db, n_bc, t};
        if (n_ad != kInvalid) repoint(nbr[n_ad], u, t);
        if (n_bc != kInvalid) repoint(nbr[n_bc], t, u);
        ++this_pass;
        break;  // t's edges changed: its other edges are met again in the next pass
      }
    }
    flips += this_pass;
    if (this_pass == 0) break;
  }
  return flips;
}

}  // namespace hm
