// The batched NURBS surface kernel: plain functions over arrays, depending on core alone.
// Single-point and batched evaluation share one code path (the same basis routines and the same
// summation order), so a point evaluated in a batch is bit-identical to the point evaluated alone.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "core/vec.h"
#include "kernels/bspline_basis.h"

namespace hm::kernel {

// A rational B-spline surface as raw arrays. Control point (i, j) is points[i + count_u * j]
// (u fastest), with weight weights[i + count_u * j]; knots_x has count_x + degree_x + 1 values.
// [u0, u1] x [v0, v1] is the parameter domain (used by the degenerate-normal fallback).
struct SurfaceArrays {
  int degree_u = 0;
  int degree_v = 0;
  int count_u = 0;
  int count_v = 0;
  std::span<const double> knots_u;
  std::span<const double> knots_v;
  std::span<const Vec3d> points;
  std::span<const double> weights;
  double u0 = 0, u1 = 1, v0 = 0, v1 = 1;
};

// Position and partial derivatives at (u, v): out[0] = S, and for order >= 1 out[1] = Su,
// out[2] = Sv, for order 2 out[3] = Suu, out[4] = Suv, out[5] = Svv (1, 3 or 6 entries).
// Parameters outside the knot range are clamped into it. Rational derivatives by the quotient
// rule on the homogeneous derivatives (Piegl & Tiller A3.6 + A4.4).
void surface_derivs(const SurfaceArrays& s, double u, double v, int order, Vec3d* out);
Vec3d surface_point(const SurfaceArrays& s, double u, double v);

// True when Su x Sv is too small to define a normal: its area element is below `ratio` (1e-12 by
// default) times the square of the local edge lengths |Su| du + |Sv| dv (du, dv: domain widths).
// Scale-free; true for NaN. Collapsed edges and zero-length control rows land here.
inline constexpr double kDegenerateRatio = 1e-12;
bool normal_degenerate(const Vec3d& su, const Vec3d& sv, double du, double dv,
                       double ratio = kDegenerateRatio);

// Moves (u, v) to the first parameter of the sequence (u, v), then points a fraction 1e-6, 1e-5,
// ..., 0.1, 0.5, 1 of the way towards the domain centre, that is not normal_degenerate with
// `ratio`. False (and (u, v) left clamped to the domain) when there is none: the whole patch is a
// point or a curve.
bool regular_param(const SurfaceArrays& s, double& u, double& v, double ratio = kDegenerateRatio);

// Unit normal Su x Sv at (u, v), taken at regular_param when degenerate there. The zero vector
// only when the whole patch is degenerate; never NaN for finite input.
Vec3d surface_normal(const SurfaceArrays& s, double u, double v);

// Basis functions of one direction at a list of parameters, computed once for a whole grid.
// spans[i] is the span of params[i]; values holds (order + 1) x (degree + 1) numbers per
// parameter, laid out as ders_basis_funs writes them.
struct BasisTable {
  int degree = 0;
  int order = 0;
  std::vector<int> spans;
  std::vector<double> values;
};
void basis_table(int degree, int count, std::span<const double> knots,
                 std::span<const double> params, int order, BasisTable& out);

// Grid rows j in [row_begin, row_end) of the grid us x vs: positions[i + us.size() * j] and,
// when normals is not empty, the unit normals likewise. bu and bv are basis_table(us) and
// basis_table(vs) of order 1 when normals are wanted, order 0 otherwise.
void surface_grid_rows(const SurfaceArrays& s, std::span<const double> us,
                       std::span<const double> vs, const BasisTable& bu, const BasisTable& bv,
                       std::size_t row_begin, std::size_t row_end, std::span<Vec3d> positions,
                       std::span<Vec3d> normals);

// Position and derivatives (as surface_derivs, order 0..2, bit for bit) on the whole grid of two
// basis tables of at least that order: out[(i + nu * j) * m + d] with m = 1, 3 or 6 entries per
// point. Each u parameter is contracted with a v span's rows of the net once for all the v
// parameters in that span, in their order (sorted parameters: once per span), about 2.4 times
// fewer operations on a Gauss grid of 7 x 7.
void surface_grid_derivs(const SurfaceArrays& s, const BasisTable& bu, const BasisTable& bv,
                         int order, std::span<Vec3d> out);

// Items [begin, end) of a list of (u, v) pairs: positions[k] and, when normals is not empty,
// normals[k].
void surface_points(const SurfaceArrays& s, std::span<const Vec2d> uv, std::size_t begin,
                    std::size_t end, std::span<Vec3d> positions, std::span<Vec3d> normals);

// Rational B-spline curve at t (clamped into the knot range): out[0] = C and, for order 1,
// out[1] = C'. points and weights have count entries, knots count + degree + 1.
void curve_derivs(int degree, std::span<const double> knots, std::span<const Vec3d> points,
                  std::span<const double> weights, double t, int order, Vec3d* out);

}  // namespace hm::kernel
