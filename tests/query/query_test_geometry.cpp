#include "query_test_geometry.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hm::test {

NurbsSurface quarter_cylinder(double r, double h) {
  NurbsSurface s;
  s.degree_u = 2;
  s.degree_v = 1;
  s.count_u = 3;
  s.count_v = 2;
  s.knots_u = {0, 0, 0, 1, 1, 1};
  s.knots_v = {0, 0, 1, 1};
  const double w = std::sqrt(0.5);
  for (double z : {0.0, h}) {
    s.points.insert(s.points.end(), {{r, 0, z}, {r, r, z}, {0, r, z}});
    s.weights.insert(s.weights.end(), {1, w, 1});
  }
  return s;
}

NurbsSurface full_cylinder(double r, double h) {
  NurbsSurface s;
  s.degree_u = 2;
  s.degree_v = 1;
  s.count_u = 9;
  s.count_v = 2;
  s.knots_u = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  s.knots_v = {0, 0, 1, 1};
  const double w = std::sqrt(0.5);
  const double xy[9][2] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                           {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  for (double z : {0.0, h}) {
    for (int i = 0; i < 9; ++i) {
      s.points.push_back({r * xy[i][0], r * xy[i][1], z});
      s.weights.push_back(i % 2 == 0 ? 1 : w);
    }
  }
  return s;
}

NurbsSurface plate_x(double x0, double half) {
  NurbsSurface s;
  s.degree_u = s.degree_v = 1;
  s.count_u = s.count_v = 2;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.points = {{x0, -half, -half}, {x0, half, -half}, {x0, -half, half}, {x0, half, half}};
  s.weights.assign(4, 1.0);
  return s;
}

NurbsSurface wigley(double l, double b, double t) {
  // Bernstein coefficients: 1 - (2x/L)^2 = 4u(1 - u) -> (0, 2, 0); 1 - v^2 -> (1, 1, 0).
  const double fx[3] = {0, 2, 0}, gz[3] = {1, 1, 0};
  const double xs[3] = {-l / 2, 0, l / 2}, zs[3] = {0, -t / 2, -t};
  NurbsSurface s;
  s.degree_u = s.degree_v = 2;
  s.count_u = s.count_v = 3;
  s.knots_u = s.knots_v = {0, 0, 0, 1, 1, 1};
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) s.points.push_back({xs[i], b / 2 * fx[i] * gz[j], zs[j]});
  }
  s.weights.assign(9, 1.0);
  return s;
}

double wigley_y(double l, double b, double t, double x, double z) {
  const double a = 2 * x / l, c = z / t;
  return b / 2 * (1 - a * a) * (1 - c * c);
}

std::pair<NurbsSurface, NurbsSurface> split_bezier_u(const NurbsSurface& s) {
  NurbsSurface left = s, right = s;
  const int n = s.count_u;
  for (int j = 0; j < s.count_v; ++j) {
    // Homogeneous de Casteljau at 1/2 on row j.
    std::vector<Vec3d> p(n);
    std::vector<double> w(n);
    for (int i = 0; i < n; ++i) {
      w[i] = s.weight(i, j);
      p[i] = s.point(i, j) * w[i];
    }
    for (int k = 0; k < n; ++k) {
      left.points[k + n * j] = p[0] / w[0];
      left.weights[k + n * j] = w[0];
      right.points[n - 1 - k + n * j] = p[n - 1 - k] / w[n - 1 - k];
      right.weights[n - 1 - k + n * j] = w[n - 1 - k];
      for (int i = 0; i + 1 < n - k; ++i) {
        p[i] = 0.5 * (p[i] + p[i + 1]);
        w[i] = 0.5 * (w[i] + w[i + 1]);
      }
    }
  }
  return {left, right};
}

Patch make_patch(NurbsSurface s, bool reversed) {
  Patch p;
  p.surface = std::move(s);
  p.reversed = reversed;
  p.wrapping = Wrapping::kGenerated;
  return p;
}

void add_grid(SurfaceMesh& mesh, const Patch& patch, PatchId p, int nu, int nv) {
  const NurbsSurface& s = patch.surface;
  const Index base = static_cast<Index>(mesh.positions.size());
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const double u = s.u0 + (s.u1 - s.u0) * i / nu;
      const double v = s.v0 + (s.v1 - s.v0) * j / nv;
      mesh.positions.push_back(evaluate(s, u, v));
      mesh.vertex_uv.push_back({u, v});
      mesh.vertex_patch.push_back(p);
    }
  }
  auto id = [&](int i, int j) { return base + static_cast<Index>(i + (nu + 1) * j); };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), kInvalid});
      mesh.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1), kInvalid});
      mesh.face_patch.insert(mesh.face_patch.end(), 2, p);
    }
  }
}

void weld(SurfaceMesh& mesh, double tol) {
  const std::size_t n = mesh.positions.size();
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), Index{0});
  std::sort(order.begin(), order.end(), [&](Index a, Index b) {
    return std::make_pair(mesh.positions[a].x, a) < std::make_pair(mesh.positions[b].x, b);
  });
  // Union-find; every class is represented by its lowest vertex.
  std::vector<Index> target(n);
  std::iota(target.begin(), target.end(), Index{0});
  auto find = [&](Index v) {
    while (target[v] != v) v = target[v] = target[target[v]];
    return v;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Index a = order[i];
    for (std::size_t k = i + 1; k < n; ++k) {
      const Index b = order[k];
      if (mesh.positions[b].x - mesh.positions[a].x > tol) break;
      if (norm(mesh.positions[a] - mesh.positions[b]) > tol) continue;
      const Index ra = find(a), rb = find(b);
      target[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  for (Index v = 0; v < n; ++v) target[v] = find(v);
  std::vector<Index> new_index(n, kInvalid);
  SurfaceMesh out;
  for (Index v = 0; v < n; ++v) {
    if (target[v] != v) continue;
    new_index[v] = static_cast<Index>(out.positions.size());
    out.positions.push_back(mesh.positions[v]);
    out.vertex_uv.push_back(mesh.vertex_uv[v]);
    out.vertex_patch.push_back(mesh.vertex_patch[v]);
  }
  for (Index v = 0; v < n; ++v) new_index[v] = new_index[target[v]];
  out.faces = mesh.faces;
  for (Face& f : out.faces) {
    for (int k = 0; k < 3; ++k) f[k] = new_index[f[k]];
  }
  out.face_patch = mesh.face_patch;
  mesh = std::move(out);
}

}  // namespace hm::test
