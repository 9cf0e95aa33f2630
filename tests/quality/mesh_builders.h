// Small meshes built in the tests themselves (no other stage involved). Normals out of the body.
#pragma once

#include <cmath>
#include <functional>
#include <numbers>

#include "mesh/surface_mesh.h"

namespace hm::test {

// Quads of a parametric grid (nu x nv cells) of f(s, t), s, t in [0, 1]; the quad corner order
// follows +s then +t, so its normal is f_s x f_t.
inline SurfaceMesh grid_mesh(int nu, int nv, const std::function<Vec3d(double, double)>& f) {
  SurfaceMesh m;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i)
      m.positions.push_back(f(static_cast<double>(i) / nu, static_cast<double>(j) / nv));
  auto id = [nu](int i, int j) { return static_cast<Index>(i + (nu + 1) * j); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i)
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  m.face_patch.assign(m.faces.size(), 0);
  return m;
}

// Appends b to a (vertices not merged).
inline void append(SurfaceMesh& a, const SurfaceMesh& b) {
  const Index off = static_cast<Index>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (Face f : b.faces) {
    for (Index& v : f)
      if (v != kInvalid) v += off;
    a.faces.push_back(f);
    a.face_patch.push_back(0);
  }
}

// Merges vertices closer than tol (quadratic; test sizes only). Face indices are remapped.
inline void merge_vertices(SurfaceMesh& m, double tol = 1e-12) {
  std::vector<Index> map(m.positions.size());
  std::vector<Vec3d> kept;
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    map[i] = static_cast<Index>(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k)
      if (norm(kept[k] - m.positions[i]) <= tol) {
        map[i] = static_cast<Index>(k);
        break;
      }
    if (map[i] == kept.size()) kept.push_back(m.positions[i]);
  }
  for (Face& f : m.faces)
    for (Index& v : f)
      if (v != kInvalid) v = map[v];
  m.positions = std::move(kept);
}

// Box [lo, hi] with n x n quads on each side, outward normals, vertices merged.
inline SurfaceMesh box_mesh(const Vec3d& lo, const Vec3d& hi, int n) {
  SurfaceMesh m;
  const Vec3d d = hi - lo;
  // For each axis a, the side at lo (normal -a) and at hi (normal +a). The two in-plane axes
  // b = a + 1, c = a + 2 (cyclic): e_b x e_c = e_a.
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      append(m, grid_mesh(n, n, [&](double s, double t) {
               Vec3d p = lo;
               p[a] += side * d[a];
               // +side: (s along b, t along c) gives e_b x e_c = +e_a; -side: swap.
               p[b] += (side ? s : t) * d[b];
               p[c] += (side ? t : s) * d[c];
               return p;
             }));
    }
  }
  merge_vertices(m);
  return m;
}

// UV sphere of radius r centred at c: nu around, nv from pole to pole (poles merged).
inline SurfaceMesh sphere_mesh(double r, const Vec3d& c, int nu, int nv) {
  SurfaceMesh m = grid_mesh(nu, nv, [&](double s, double t) {
    const double phi = 2 * std::numbers::pi * s,
                 th = std::numbers::pi * (1 - t);  // t: south->north
    return c + r * Vec3d{std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th)};
  });
  merge_vertices(m, 1e-12 * r);
  // Quads at the poles collapse to triangles: drop the repeated corner.
  for (Face& f : m.faces) {
    Face g{kInvalid, kInvalid, kInvalid, kInvalid};
    int n = 0;
    for (int i = 0; i < 4; ++i)
      if (f[i] != f[(i + 3) % 4]) g[n++] = f[i];
    f = g;
  }
  return m;
}

}  // namespace hm::test
