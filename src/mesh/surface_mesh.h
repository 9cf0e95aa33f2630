// The surface mesh every stage passes along: arrays per attribute, 32-bit indices.
// Positions in metres, in the model frame of the imported file.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm {

// A face has three or four corners; a triangle's fourth index is kInvalid.
using Face = std::array<Index, 4>;

inline bool is_triangle(const Face& f) { return f[3] == kInvalid; }
inline int corner_count(const Face& f) { return is_triangle(f) ? 3 : 4; }

struct SurfaceMesh {
  // Per vertex.
  std::vector<Vec3d> positions;
  // Per vertex, optional (empty or one per vertex): the patch a vertex lies on and its (u, v)
  // there. Vertices shared by patches name one of them.
  std::vector<PatchId> vertex_patch;
  std::vector<Vec2d> vertex_uv;

  // Per face. face_patch is the provenance: the index of the source patch in the imported model.
  std::vector<Face> faces;
  std::vector<PatchId> face_patch;
  // Per face, optional: structured block id (kInvalid when not from a block).
  std::vector<Index> face_block;

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t face_count() const { return faces.size(); }
};

// Named scalar per face, written as cell data (for example "chord_error").
struct FaceField {
  const char* name;
  std::span<const double> values;
};

// Two panel centres nearer than this share of the smaller panel's size (the square root of its
// area) are "very close": panel codes refuse such pairs (the quality report's rule, and what the
// meshers avoid where a hull's halves are tangent or meet at a fine stem).
inline constexpr double kCloseCentreFraction = 0.05;

// Area of a triangle or of a quad (as two triangles split along 0-2), in m^2.
double face_area(std::span<const Vec3d> positions, const Face& f);
// Unit normal by the right-hand rule over the corners (Newell's method for quads).
Vec3d face_normal(std::span<const Vec3d> positions, const Face& f);
Vec3d face_centroid(std::span<const Vec3d> positions, const Face& f);

// Keeps the faces with keep[f] != 0, in order, and every per-face array in step with them.
// Returns how many went. Vertices stay.
std::size_t keep_faces(SurfaceMesh& mesh, std::span<const std::uint8_t> keep);

}  // namespace hm
