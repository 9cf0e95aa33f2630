// Hand-made patches with known geometry and mesh property checks for the tessellation tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include "mesh/surface_mesh.h"
#include "nurbs/nurbs_curve.h"
#include "nurbs/patch.h"

namespace hm::test {

// Bilinear square [0, side]^2 in the plane z = 0, (u, v) in [0, 1]^2.
inline Patch flat_square(double side) {
  Patch p;
  NurbsSurface& s = p.surface;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.points = {{0, 0, 0}, {side, 0, 0}, {0, side, 0}, {side, side, 0}};
  s.weights = {1, 1, 1, 1};
  p.wrapping = Wrapping::kGenerated;
  return p;
}

// Quarter cylinder of radius r and length len: exact rational quadratic in u (the arc from +x to
// +y), linear in v along z.
inline Patch quarter_cylinder(double r, double len) {
  Patch p;
  NurbsSurface& s = p.surface;
  s.degree_u = 2;
  s.degree_v = 1;
  s.count_u = 3;
  s.count_v = 2;
  s.knots_u = {0, 0, 0, 1, 1, 1};
  s.knots_v = {0, 0, 1, 1};
  const double w = std::sqrt(0.5);
  for (double z : {0.0, len}) {
    s.points.push_back({r, 0, z});
    s.points.push_back({r, r, z});
    s.points.push_back({0, r, z});
    s.weights.insert(s.weights.end(), {1.0, w, 1.0});
  }
  p.wrapping = Wrapping::kGenerated;
  return p;
}

// A curved patch whose edge v = 1 is collapsed to the apex (0, 0, h): quadratic in u (a bulging
// base curve), quadratic in v, every control point of the last row at the apex.
inline Patch apex_patch() {
  Patch p;
  NurbsSurface& s = p.surface;
  s.degree_u = s.degree_v = 2;
  s.count_u = s.count_v = 3;
  s.knots_u = s.knots_v = {0, 0, 0, 1, 1, 1};
  s.points = {{-1, 0, 0},    {0, 1.2, 0},   {1, 0, 0},     {-0.5, 0, 0.6}, {0, 0.7, 0.7},
              {0.5, 0, 0.6}, {0, 0.2, 1.0}, {0, 0.2, 1.0}, {0, 0.2, 1.0}};
  s.weights.assign(9, 1.0);
  p.wrapping = Wrapping::kGenerated;
  return p;
}

// A full cylinder closed in u (seam at u = 0 / 1): four rational quadratic quarter arcs.
inline Patch closed_cylinder(double r, double len) {
  Patch p;
  NurbsSurface& s = p.surface;
  s.degree_u = 2;
  s.degree_v = 1;
  s.count_u = 9;
  s.count_v = 2;
  s.knots_u = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  s.knots_v = {0, 0, 1, 1};
  const double w = std::sqrt(0.5);
  const double xy[9][2] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                           {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  for (double z : {0.0, len}) {
    for (int i = 0; i < 9; ++i) {
      s.points.push_back({r * xy[i][0], r * xy[i][1], z});
      s.weights.push_back(i % 2 ? w : 1.0);
    }
  }
  p.wrapping = Wrapping::kGenerated;
  return p;
}

// A circle of radius r around c in the (u, v) plane as two counter-clockwise half arcs.
inline TrimLoop circle_loop(Vec2d c, double r, bool outer) {
  TrimLoop l;
  l.outer = outer;
  const Vec3d cc{c.x, c.y, 0};
  l.curves_uv.push_back(make_circular_arc(cc, cc + Vec3d{r, 0, 0}, cc + Vec3d{-r, 0, 0}));
  l.curves_uv.push_back(make_circular_arc(cc, cc + Vec3d{-r, 0, 0}, cc + Vec3d{r, 0, 0}));
  return l;
}

inline TrimLoop square_loop(double lo, double hi) {
  TrimLoop l;
  l.outer = true;
  const Vec3d a{lo, lo, 0}, b{hi, lo, 0}, c{hi, hi, 0}, d{lo, hi, 0};
  for (auto [p, q] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, d}, std::pair{d, a}})
    l.curves_uv.push_back(make_line(p, q));
  return l;
}

// Topology of the triangles of one patch.
struct Topology {
  bool manifold = true;  // every edge has one or two triangles
  bool oriented = true;  // every directed edge appears once
  int boundary_loops = 0;
  long long euler = 0;  // V - E + F over the vertices the triangles use
  std::size_t triangles = 0;
};

inline Topology patch_topology(const SurfaceMesh& m, PatchId patch) {
  Topology t;
  std::map<std::pair<Index, Index>, int> directed;
  std::map<Index, int> used;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    if (m.face_patch[f] != patch) continue;
    ++t.triangles;
    for (int i = 0; i < 3; ++i) {
      const Index a = m.faces[f][i], b = m.faces[f][(i + 1) % 3];
      if (++directed[{a, b}] > 1) t.oriented = false;
      used[a] = 1;
    }
  }
  std::map<std::pair<Index, Index>, int> undirected;
  std::map<Index, std::vector<Index>> next;  // boundary: directed edges without a twin
  for (const auto& [e, n] : directed) {
    ++undirected[{std::min(e.first, e.second), std::max(e.first, e.second)}];
    if (!directed.count({e.second, e.first})) next[e.first].push_back(e.second);
  }
  for (const auto& [e, n] : undirected)
    if (n > 2) t.manifold = false;
  for (const auto& [v, outs] : next)
    if (outs.size() != 1) t.manifold = false;  // a boundary vertex touched twice (pinched)
  std::map<Index, bool> seen;
  for (const auto& [v, outs] : next) {
    if (seen[v]) continue;
    ++t.boundary_loops;
    for (Index c = v; !seen[c];) {
      seen[c] = true;
      if (!next.count(c)) break;
      c = next[c].front();
    }
  }
  t.euler = static_cast<long long>(used.size()) - static_cast<long long>(undirected.size()) +
            static_cast<long long>(t.triangles);
  return t;
}

inline double triangle_area(const SurfaceMesh& m, std::size_t f) {
  return face_area(m.positions, m.faces[f]);
}

// Smallest interior angle of a triangle, degrees.
inline double min_angle_deg(const SurfaceMesh& m, std::size_t f) {
  double best = 180;
  for (int i = 0; i < 3; ++i) {
    const Vec3d& a = m.positions[m.faces[f][i]];
    const Vec3d e1 = m.positions[m.faces[f][(i + 1) % 3]] - a;
    const Vec3d e2 = m.positions[m.faces[f][(i + 2) % 3]] - a;
    const double c = dot(e1, e2) / (norm(e1) * norm(e2));
    best = std::min(best, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / std::numbers::pi);
  }
  return best;
}

}  // namespace hm::test
