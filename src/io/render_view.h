// Pictures of a panel mesh from what each pixel's ray hit: face colours, Lambert shading with a
// head light, panel edges and feature lines, then legends (io/render_legend.h).
//
// Plain functions over arrays. Pixels are row-major from the top-left, 3 bytes (R, G, B) each;
// positions and hit points are in metres in the mesh's model frame.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/surface_mesh.h"

namespace hm {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  friend constexpr bool operator==(const Rgb8&, const Rgb8&) = default;
};

struct RgbImage {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3

  Rgb8 at(std::uint32_t x, std::uint32_t y) const {
    const std::size_t i = (std::size_t{y} * width + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
  void set(std::uint32_t x, std::uint32_t y, Rgb8 c) {
    const std::size_t i = (std::size_t{y} * width + x) * 3;
    rgb[i] = c.r;
    rgb[i + 1] = c.g;
    rgb[i + 2] = c.b;
  }
};

inline constexpr Rgb8 kBackground{255, 255, 255};
inline constexpr Rgb8 kPlainPanel{188, 198, 214};
inline constexpr Rgb8 kNoValue{150, 150, 150};    // a face whose measure is not finite
inline constexpr Rgb8 kKnuckleLine{214, 32, 39};  // features: knuckle edges
inline constexpr Rgb8 kBoundaryLine{31, 100, 230};

// The perceptual sequential map (dark violet -> blue -> green -> yellow, lightness rising), t in
// [0, 1], clamped.
Rgb8 sequential_colour(double t);
// A categorical colour for an id (patch, block): hues spaced by the golden angle, so that
// neighbouring ids differ strongly.
Rgb8 category_colour(Index id);

struct ScalarRange {
  double lo = 0, hi = 1;
  bool valid = false;  // false: no finite value
};
// Values at or beyond this magnitude (quality's 1e30 for degenerate panels) carry no value.
inline constexpr double kNoValueMagnitude = 1e29;
// The range of the finite values under kNoValueMagnitude.
ScalarRange value_range(std::span<const double> values);
// Per face: sequential_colour((v - lo) / (hi - lo)), clamped; kNoValue for a value without one.
// A range with hi == lo maps every value to the middle of the map.
std::vector<Rgb8> scalar_face_colours(std::span<const double> values, const ScalarRange& range);
// Per face: category_colour(id), kNoValue for kInvalid (a face from no block).
std::vector<Rgb8> category_face_colours(std::span<const Index> ids);

// What a face's edge (corner c to c + 1) is drawn as.
enum class EdgeKind : std::uint8_t { kPlain, kKnuckle, kBoundary };
// Per face, per corner edge: kBoundary when one face uses the edge, kKnuckle when the normals of
// its two faces differ by more than knuckle_angle_deg, else kPlain (a triangle's fourth slot is
// kPlain). Non-manifold edges count as knuckles.
std::vector<std::array<EdgeKind, 4>> classify_face_edges(const SurfaceMesh& mesh,
                                                         double knuckle_angle_deg);

// The rays' answers, as trace_view returns them (query/trace_view.h), in plain arrays.
struct PixelHits {
  std::uint32_t width = 0, height = 0;
  std::span<const Index> face;        // per pixel, kInvalid = background
  std::span<const Vec3d> point;       // per pixel hit point
  std::span<const Vec3d> column_dir;  // per column, unit ray direction
  double pixel_size = 1;              // metres per pixel
  double centre_line_x = -1;          // a vertical rule at this column (body plan); < 0: none
};

struct ShadeOptions {
  double ambient = 0.3;           // light where the surface turns away from the light
  double light_above = 0.5;       // the head light's offset above the eye, per unit view distance
  double light_aside = 0.35;      // and to the side
  double edge_width_px = 0.7;     // a hit this close to its face's edge (pixels) is an edge
  double feature_width_px = 1.6;  // the same for knuckle and boundary lines
  double edge_darkening = 0.25;   // an edge pixel keeps this share of its shaded colour
};

// The picture: background where no face was hit, else the face's colour times
// (ambient + (1 - ambient) |n . l|) with n the face normal and l the direction to a head light
// just above and beside the eye (both sides lit), darkened on panel edges and replaced by the
// feature colours on knuckle and boundary edges (edge_kind empty: every edge plain). The distance
// to an edge is measured in the picture plane, so lines keep their width on faces seen at a slant.
// Rows run in parallel; the bytes do not depend on the thread count. Throws InternalError when the
// arrays do not match.
RgbImage shade_view(const SurfaceMesh& mesh, const PixelHits& hits,
                    std::span<const Rgb8> face_colour,
                    std::span<const std::array<EdgeKind, 4>> edge_kind,
                    const ShadeOptions& options = {});

}  // namespace hm
