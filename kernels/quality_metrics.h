// Per-face quality metrics of a panel mesh: plain loops over arrays, depending on core alone.
//
// Shapes: positions is #V points (metres); faces is #F rows of four vertex indices, a triangle's
// fourth index being kInvalid. A quad with two equal consecutive indices is measured as the
// triangle it collapses to. Indices must be valid (< #V): callers validate them first.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm::kernel {

// One value per face. Angles in degrees, lengths in metres, areas in m^2.
struct FaceMetricArrays {
  std::vector<double> area;
  std::vector<Vec3d> normal;    // unit, Newell's method; zero vector for a zero-area face
  std::vector<Vec3d> centroid;  // mean of the corners
  std::vector<double> min_angle_deg;
  std::vector<double> max_angle_deg;
  // Triangles: 4 sqrt(3) A / (l1^2 + l2^2 + l3^2), 1 for an equilateral triangle, 0 when
  // degenerate. Quads: -1 (not defined).
  std::vector<double> equilateral;
  // Longest side / shortest side (1 for a square or equilateral triangle).
  std::vector<double> side_ratio;
  // Quads: max distance of a corner from the mean plane (centroid, Newell normal) divided by the
  // mean diagonal length; triangles: 0.
  std::vector<double> warp;
  // Quads: the larger, over the two diagonal splits, of the angle between the two triangles'
  // normals; triangles: 0.
  std::vector<double> warp_angle_deg;
  // Triangles: l_max (l1 + l2 + l3) / (4 sqrt(3) A) = l_max / (2 sqrt(3) r_in), 1 when
  // equilateral. Quads: longer / shorter of the two mid-lines (joining midpoints of opposite
  // sides), 1 for a square or rhombus.
  std::vector<double> aspect_ratio;
  // Quads: both diagonals split the quad (the four corner triangles turn the same way as the
  // Newell normal). Triangles: 1. Zero-area faces: 0.
  std::vector<std::uint8_t> convex;
  // Area <= zero_area_rel * (longest side)^2, or every side of zero length.
  std::vector<std::uint8_t> zero_area;
  std::vector<std::uint8_t> is_quad;  // four distinct corners

  void resize(std::size_t n);
};

// Fills out (resized to faces.size()) in parallel over faces; each face writes its own slots, so
// the result is identical for any thread count.
void face_metrics(std::span<const Vec3d> positions, std::span<const std::array<Index, 4>> faces,
                  double zero_area_rel, FaceMetricArrays& out);

}  // namespace hm::kernel
