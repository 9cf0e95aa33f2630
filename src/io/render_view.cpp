#include "io/render_view.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.h"
#include "core/parallel.h"
#include "mesh/adjacency.h"

namespace hm {
namespace {

// The sequential map's control points at t = 0, 1/8, ..., 1: lightness rises steadily from a
// dark violet through blue and green to a light yellow, readable in grey and by most colour-blind
// viewers (the idea of viridis; our own points, interpolated linearly in sRGB).
constexpr std::array<std::array<double, 3>, 9> kSequential{{
    {70, 6, 90},
    {72, 44, 124},
    {60, 80, 140},
    {44, 112, 142},
    {33, 142, 140},
    {40, 170, 126},
    {92, 198, 98},
    {168, 220, 56},
    {250, 232, 40},
}};

std::uint8_t to_byte(double v) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

Rgb8 hsv(double h, double s, double v) {
  h = (h - std::floor(h)) * 6;
  const int i = static_cast<int>(h) % 6;
  const double f = h - std::floor(h);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (i) {
    case 1:
      r = q, g = v, b = p;
      break;
    case 2:
      r = p, g = v, b = t;
      break;
    case 3:
      r = p, g = q, b = v;
      break;
    case 4:
      r = t, g = p, b = v;
      break;
    case 5:
      r = v, g = p, b = q;
      break;
    default:
      break;
  }
  return {to_byte(255 * r), to_byte(255 * g), to_byte(255 * b)};
}

// Faces at least this many pixels across (as seen) get full-strength edge lines.
constexpr double kFullLineWidth = 5;

bool has_value(double v) { return std::isfinite(v) && std::abs(v) < kNoValueMagnitude; }

Rgb8 scale(Rgb8 c, double k) { return {to_byte(c.r * k), to_byte(c.g * k), to_byte(c.b * k)}; }

// Distance from p to the segment a-b after removing every component along the unit vector d
// (the distance a viewer looking along d sees).
double picture_distance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& d) {
  Vec3d q = p - a, e = b - a;
  q -= dot(q, d) * d;
  e -= dot(e, d) * d;
  const double ee = dot(e, e);
  const double t = ee > 0 ? std::clamp(dot(q, e) / ee, 0.0, 1.0) : 0.0;
  return norm(q - t * e);
}

// The colour of one pixel (column x, row-major slot).
struct PixelShader {
  const SurfaceMesh& mesh;
  const PixelHits& hits;
  std::span<const Rgb8> face_colour;
  std::span<const std::array<EdgeKind, 4>> edge_kind;
  const ShadeOptions& options;
  std::span<const Vec3d> normal;  // per face, unit
  std::span<const double> area;   // per face, m^2
  std::span<const Vec3d> light;   // per column, unit, towards the light

  Rgb8 operator()(std::uint32_t x, std::size_t slot) const {
    const Index f = hits.face[slot];
    if (f == kInvalid || f >= mesh.faces.size()) return kBackground;
    const Vec3d& d = hits.column_dir[x];
    const double facing = std::min(1.0, std::abs(dot(normal[f], d)));
    const double diffuse = std::min(1.0, std::abs(dot(normal[f], light[x])));
    const Rgb8 lit = scale(face_colour[f], options.ambient + (1 - options.ambient) * diffuse);

    // Nearest plain and nearest feature edge of the face, as the viewer sees them.
    const Face& face = mesh.faces[f];
    const int corners = corner_count(face);
    double plain = std::numeric_limits<double>::infinity(), feature = plain;
    double perimeter = 0;  // of the face as seen, metres
    EdgeKind feature_kind = EdgeKind::kPlain;
    for (int k = 0; k < corners; ++k) {
      const Vec3d& a = mesh.positions[face[k]];
      const Vec3d& b = mesh.positions[face[(k + 1) % corners]];
      const Vec3d e = b - a;
      perimeter += norm(e - dot(e, d) * d);
      const double dist = picture_distance(hits.point[slot], a, b, d);
      const EdgeKind kind = edge_kind.empty() ? EdgeKind::kPlain : edge_kind[f][k];
      if (kind == EdgeKind::kPlain) {
        plain = std::min(plain, dist);
      } else if (dist < feature) {
        feature = dist;
        feature_kind = kind;
      }
    }
    const double px = hits.pixel_size;
    if (feature < options.feature_width_px * px) {
      return feature_kind == EdgeKind::kKnuckle ? kKnuckleLine : kBoundaryLine;
    }
    if (std::min(plain, feature) >= options.edge_width_px * px) return lit;
    // A face seen nearly edge-on is a few pixels across and its own edges would paint it dark:
    // its lines fade as its visible width (twice the projected area over the projected
    // perimeter, in pixels) falls from kFullLineWidth pixels to one.
    const double width_px = perimeter > 0 ? 2 * area[f] * facing / perimeter / px : 0.0;
    const double strength = std::clamp((width_px - 1) / (kFullLineWidth - 1), 0.0, 1.0);
    return scale(lit, 1 - (1 - options.edge_darkening) * strength);
  }
};

}  // namespace

Rgb8 sequential_colour(double t) {
  if (!(t >= 0)) t = 0;  // NaN too
  t = std::min(t, 1.0) * (kSequential.size() - 1);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(t), kSequential.size() - 2);
  const double f = t - i;
  const auto& a = kSequential[i];
  const auto& b = kSequential[i + 1];
  return {to_byte(a[0] + f * (b[0] - a[0])), to_byte(a[1] + f * (b[1] - a[1])),
          to_byte(a[2] + f * (b[2] - a[2]))};
}

Rgb8 category_colour(Index id) {
  // The golden angle between consecutive ids; saturation and value alternate with the id's
  // bits so that ids whose hues come close still differ in brightness.
  constexpr double kGolden = 0.3819660112501051;  // 1 - 1 / phi, of a full turn
  const double hue = std::fmod(0.02 + kGolden * id, 1.0);
  const double sat = (id / 3) % 2 == 0 ? 0.62 : 0.42;
  const double val = (id / 6) % 2 == 0 ? 0.95 : 0.78;
  return hsv(hue, sat, val);
}

ScalarRange value_range(std::span<const double> values) {
  ScalarRange r;
  for (double v : values) {
    if (!has_value(v)) continue;
    if (!r.valid) {
      r.lo = r.hi = v;
      r.valid = true;
    }
    r.lo = std::min(r.lo, v);
    r.hi = std::max(r.hi, v);
  }
  return r;
}

std::vector<Rgb8> scalar_face_colours(std::span<const double> values, const ScalarRange& range) {
  std::vector<Rgb8> out(values.size(), kNoValue);
  const double span = range.hi - range.lo;
  for (std::size_t f = 0; f < values.size(); ++f) {
    if (!has_value(values[f])) continue;
    out[f] = sequential_colour(span > 0 ? (values[f] - range.lo) / span : 0.5);
  }
  return out;
}

std::vector<Rgb8> category_face_colours(std::span<const Index> ids) {
  std::vector<Rgb8> out(ids.size(), kNoValue);
  for (std::size_t f = 0; f < ids.size(); ++f) {
    if (ids[f] != kInvalid) out[f] = category_colour(ids[f]);
  }
  return out;
}

std::vector<std::array<EdgeKind, 4>> classify_face_edges(const SurfaceMesh& mesh,
                                                         double knuckle_angle_deg) {
  const EdgeAdjacency adj = build_edge_adjacency(mesh.faces, mesh.positions.size());
  std::vector<Vec3d> normal(mesh.faces.size());
  for (std::size_t f = 0; f < normal.size(); ++f)
    normal[f] = face_normal(mesh.positions, mesh.faces[f]);
  const double cos_limit = std::cos(knuckle_angle_deg * std::numbers::pi / 180);
  std::vector<std::array<EdgeKind, 4>> kind(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int c = 0; c < 4; ++c) {
      kind[f][c] = EdgeKind::kPlain;
      const Index e = adj.slot_edge[4 * f + c];
      if (e == kInvalid) continue;
      const MeshEdge& edge = adj.edges[e];
      if (edge.uses == 1) {
        kind[f][c] = EdgeKind::kBoundary;
      } else if (edge.uses > 2) {
        kind[f][c] = EdgeKind::kKnuckle;
      } else {
        const Index g = adj.opposite_face[4 * f + c];
        if (g == kInvalid) continue;
        // Faces traversing the edge the same way disagree in orientation: compare n with -n.
        const double cosine = dot(normal[f], normal[g]) * (edge.same_direction ? -1.0 : 1.0);
        if (cosine < cos_limit) kind[f][c] = EdgeKind::kKnuckle;
      }
    }
  }
  return kind;
}

RgbImage shade_view(const SurfaceMesh& mesh, const PixelHits& hits,
                    std::span<const Rgb8> face_colour,
                    std::span<const std::array<EdgeKind, 4>> edge_kind,
                    const ShadeOptions& options) {
  const std::size_t n = std::size_t{hits.width} * hits.height;
  if (hits.face.size() != n || hits.point.size() != n || hits.column_dir.size() != hits.width ||
      face_colour.size() != mesh.faces.size() ||
      (!edge_kind.empty() && edge_kind.size() != mesh.faces.size()) || !(hits.pixel_size > 0)) {
    throw InternalError("render: the pixel, face and colour arrays do not match");
  }
  std::vector<Vec3d> normal(mesh.faces.size());
  std::vector<double> area(mesh.faces.size());
  parallel_for(0, normal.size(), [&](std::size_t f) {
    normal[f] = face_normal(mesh.positions, mesh.faces[f]);
    area[f] = face_area(mesh.positions, mesh.faces[f]);
  });

  RgbImage img;
  img.width = hits.width;
  img.height = hits.height;
  img.rgb.resize(n * 3);
  // The head light sits a little above and to the side of the eye, so that surfaces seen
  // edge-on (most of a body plan) still differ in brightness; "above" is +z as seen, or +y when
  // looking along z.
  std::vector<Vec3d> light(hits.width);
  for (std::uint32_t x = 0; x < hits.width; ++x) {
    const Vec3d& d = hits.column_dir[x];
    Vec3d up = Vec3d{0, 0, 1} - d.z * d;
    if (squared_norm(up) < 1e-6) up = Vec3d{0, 1, 0} - d.y * d;
    up = normalized(up);
    light[x] = normalized(-d + options.light_above * up + options.light_aside * cross(up, d));
  }
  const PixelShader shader{mesh, hits, face_colour, edge_kind, options, normal, area, light};
  parallel_for(
      0, hits.height,
      [&](std::size_t y) {
        for (std::uint32_t x = 0; x < hits.width; ++x) {
          img.set(x, static_cast<std::uint32_t>(y), shader(x, y * hits.width + x));
        }
      },
      1, 2);

  // The centre line of a body plan: a thin grey rule on the background.
  if (hits.centre_line_x >= 0 && hits.centre_line_x < hits.width) {
    const auto x = static_cast<std::uint32_t>(hits.centre_line_x);
    for (std::uint32_t y = 0; y < hits.height; ++y) {
      if (img.at(x, y) == kBackground) img.set(x, y, Rgb8{120, 120, 120});
    }
  }
  return img;
}

}  // namespace hm
