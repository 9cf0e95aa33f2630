// The working triangulation of one patch while it is being built and refined.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm {

using Tri = std::array<Index, 3>;
using TriUv = std::array<Vec2d, 3>;

// Vertex flags.
inline constexpr std::uint8_t kOnDomainSide = 1;  // on u = u0/u1 or v = v0/v1
inline constexpr std::uint8_t kOnTrimLoop = 2;    // on a sampled trim loop
// A midpoint on a domain side: its (u, v) seen from a triangle keeps that triangle's fixed
// coordinate (u1 rather than u0 across a seam).
inline constexpr std::uint8_t kSideMidpoint = 4;

// Triangles are counter-clockwise in (u, v). A vertex has one 3D position and one canonical (u, v)
// with evaluate(surface, uv) == xyz; each triangle also keeps the (u, v) of its own corners, which
// differ from the canonical ones only across a seam of a closed patch (u0 on one side, u1 on the
// other). Interpolating inside a triangle always uses the corner values.
struct PatchMesh {
  std::vector<Vec3d> xyz;
  std::vector<Vec2d> uv;
  std::vector<std::uint8_t> flags;
  std::vector<Tri> tris;
  std::vector<TriUv> tri_uv;

  Index add_vertex(const Vec3d& p, const Vec2d& w, std::uint8_t f) {
    xyz.push_back(p);
    uv.push_back(w);
    flags.push_back(f);
    return static_cast<Index>(xyz.size() - 1);
  }
  void add_tri(const Tri& t, const TriUv& w) {
    tris.push_back(t);
    tri_uv.push_back(w);
  }
  std::size_t vertex_count() const { return xyz.size(); }
  std::size_t tri_count() const { return tris.size(); }
};

// Domain sides that the surface collapses to a point (a bow or stern apex). Any parameter along
// such a side names the same point, so chord samples next to it use the parameter of the other
// corner(s): an edge into the apex follows the iso-line of its other end.
struct CollapsedSides {
  bool u0 = false, u1 = false, v0 = false, v1 = false;
  double su0 = 0, su1 = 0, sv0 = 0, sv1 = 0;  // the side parameters

  // 1 when w lies on a collapsed u side (its v is free), 2 on a collapsed v side, 0 otherwise.
  int on(const Vec2d& w) const {
    if ((u0 && w.x == su0) || (u1 && w.x == su1)) return 1;
    if ((v0 && w.y == sv0) || (v1 && w.y == sv1)) return 2;
    return 0;
  }
  bool any() const { return u0 || u1 || v0 || v1; }
  // The ends of edge (a, b) as chord sampling sees them: an end on a collapsed side takes the free
  // parameter of the other end.
  void edge_ends(Vec2d& a, Vec2d& b) const {
    if (!any()) return;
    const int ka = on(a), kb = on(b);
    if (ka && !kb) (ka == 1 ? a.y : a.x) = (ka == 1 ? b.y : b.x);
    if (kb && !ka) (kb == 1 ? b.y : b.x) = (kb == 1 ? a.y : a.x);
  }
  // The middle of edge (a, b) in (u, v) for chord sampling.
  Vec2d edge_middle(Vec2d a, Vec2d b) const {
    edge_ends(a, b);
    return 0.5 * (a + b);
  }
  // The centroid of a triangle in (u, v) for chord sampling.
  Vec2d centroid(std::array<Vec2d, 3> w) const {
    if (any()) {
      int k[3] = {on(w[0]), on(w[1]), on(w[2])};
      double free_sum[3] = {0, 0, 0};
      int free_n = 0;
      for (int i = 0; i < 3; ++i)
        if (!k[i]) free_sum[1] += w[i].y, free_sum[2] += w[i].x, ++free_n;
      if (free_n > 0 && free_n < 3) {
        for (int i = 0; i < 3; ++i)
          if (k[i]) (k[i] == 1 ? w[i].y : w[i].x) = free_sum[k[i]] / free_n;
      }
    }
    return (w[0] + w[1] + w[2]) * (1.0 / 3);
  }
};

// Key of an undirected edge (a, b), the same for (b, a).
inline std::uint64_t edge_key(Index a, Index b) {
  return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

// Undirected edges of a triangle list, found by sorting half-edges (key, then corner: the same
// for any thread count).
struct HalfEdge {
  std::uint64_t key;
  Index corner;  // 3t + i: edge (v[i], v[i + 1]) of triangle t
  bool operator<(const HalfEdge& o) const {
    return key < o.key || (key == o.key && corner < o.corner);
  }
};

struct EdgeTable {
  std::vector<HalfEdge> he;
  std::vector<Index> first;           // unique edge e: he[first[e], first[e + 1])
  std::vector<Index> edge_of_corner;  // 3t + i -> unique edge

  // he sorted by (key, corner), by a counting sort on the edges' lower vertex
  // (build_edge_table.cpp).
  void build(const std::vector<Tri>& tris);
  std::size_t count() const { return first.size() - 1; }
  Index size(Index e) const { return first[e + 1] - first[e]; }
  // Unique edge with this key, or kInvalid.
  Index find(std::uint64_t key) const {
    auto it = std::lower_bound(he.begin(), he.end(), HalfEdge{key, 0});
    if (it == he.end() || it->key != key) return kInvalid;
    return edge_of_corner[it->corner];
  }
};

}  // namespace hm
