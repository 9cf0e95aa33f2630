#include "nurbs/evaluate_grid.h"

#include <algorithm>

#include "core/parallel.h"
#include "nurbs/basis.h"

namespace hm {
namespace {

// Items per parallel task for the list form (rows of the grid are the tasks of the grid form).
constexpr std::size_t kPointsPerTask = 512;
// Grids smaller than this run on the calling thread.
constexpr std::size_t kSerialGridPoints = 4096;

}  // namespace

SurfaceSamples evaluate_grid(const NurbsSurface& s, std::span<const double> us,
                             std::span<const double> vs, bool with_normals) {
  const kernel::SurfaceArrays a = surface_arrays(s);
  const int order = with_normals ? 1 : 0;
  kernel::BasisTable bu, bv;
  kernel::basis_table(s.degree_u, s.count_u, s.knots_u, us, order, bu);
  kernel::basis_table(s.degree_v, s.count_v, s.knots_v, vs, order, bv);
  SurfaceSamples out;
  out.positions.resize(us.size() * vs.size());
  if (with_normals) out.normals.resize(out.positions.size());
  auto row = [&](std::size_t j) {
    kernel::surface_grid_rows(a, us, vs, bu, bv, j, j + 1, out.positions, out.normals);
  };
  if (out.positions.size() < kSerialGridPoints) {
    for (std::size_t j = 0; j < vs.size(); ++j) row(j);
  } else {
    parallel_for_each_item(vs.size(), row);
  }
  return out;
}

SurfaceSamples evaluate_grid(const NurbsSurface& s, int n_u, int n_v, bool with_normals) {
  const std::vector<double> us = uniform_params(s.u0, s.u1, n_u);
  const std::vector<double> vs = uniform_params(s.v0, s.v1, n_v);
  return evaluate_grid(s, us, vs, with_normals);
}

SurfaceSamples evaluate_uv(const NurbsSurface& s, std::span<const Vec2d> uv, bool with_normals) {
  const kernel::SurfaceArrays a = surface_arrays(s);
  SurfaceSamples out;
  out.positions.resize(uv.size());
  if (with_normals) out.normals.resize(uv.size());
  const std::size_t tasks = (uv.size() + kPointsPerTask - 1) / kPointsPerTask;
  parallel_for_each_item(tasks, [&](std::size_t t) {
    const std::size_t begin = t * kPointsPerTask;
    const std::size_t end = std::min(uv.size(), begin + kPointsPerTask);
    kernel::surface_points(a, uv, begin, end, out.positions, out.normals);
  });
  return out;
}

std::vector<double> uniform_params(double a, double b, int n) {
  n = std::max(n, 2);
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = a + (b - a) * i / (n - 1);
  t.back() = b;
  return t;
}

}  // namespace hm
