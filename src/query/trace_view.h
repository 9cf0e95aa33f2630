// Pictures of a panel mesh: orthographic cameras fitted to the mesh and one ray per pixel.
//
// Frames: positions, ray origins and hit points are in metres in the model frame of the mesh
// (x forward, y to port, z up). Pixels are numbered row-major from the top-left corner; pixel
// (i, j) is column i, row j, and its ray starts at the centre of the pixel.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/surface_mesh.h"

namespace hm {

enum class ViewKind : std::uint8_t {
  kProfile,   // looking along +y at the side: x to the right, z up
  kPlan,      // looking up from below (+z), drawn with x to the right and y up
  kBodyPlan,  // fore body (x >= midship) from ahead on the right half, aft body from astern on
              // the left half; both halves show one side of the centre plane, mirrored about it
  kIso,       // the bow quarter from below (35 deg forward of the beam, 25 deg down)
};

// One orthographic camera over the picture columns [first_column, first_column + columns).
struct OrthoPane {
  std::uint32_t first_column = 0, columns = 0;
  Vec3d origin;      // ray start of the centre of pixel (first_column, 0), metres
  Vec3d step_right;  // offset of one pixel to the right, metres
  Vec3d step_down;   // offset of one pixel down, metres
  Vec3d dir;         // unit ray direction
  double tmax = 0;   // ray length, metres (a body plan's pane stops at the midship plane)
};

struct ViewCamera {
  std::uint32_t width = 0, height = 0;  // pixels
  double pixel_size = 0;                // metres per pixel (square pixels)
  std::vector<OrthoPane> panes;         // cover every column once, left to right
  // The picture column (in pixels, from the left edge) of the centre plane in a body plan;
  // negative for the other views.
  double centre_line_x = -1;
};

// Fits the camera of `kind` to the mesh's vertices: the projected extent plus `margin` (a
// fraction of the larger projected extent) on every side fills `width` pixels; the height
// follows the view's aspect. Throws GeometryError when the mesh has no faces or zero extent in
// the picture plane, UsageError when the height would exceed max_height.
ViewCamera fit_view_camera(const SurfaceMesh& mesh, ViewKind kind, std::uint32_t width,
                           double margin = 0.03, std::uint32_t max_height = 16384);

// What each pixel's ray hits first, row-major (width x height entries each).
struct ViewHits {
  std::uint32_t width = 0, height = 0;
  std::vector<Index> face;   // the mesh face hit, kInvalid for the background
  std::vector<Vec3d> point;  // hit point, model frame, metres; zero for the background
  // The ray direction of each column (unit, model frame): what a head light shines along.
  std::vector<Vec3d> column_dir;
};

// Casts one ray per pixel at the mesh (faces with 3 or 4 corners; quads as two triangles split
// along 0-2). Embree finds the face in float in a local frame centred on the mesh's bounding
// box; the hit point is then recomputed in double on that face's triangle. Rows run in parallel;
// each pixel writes its own slot, so the result does not depend on the thread count. Throws
// GeometryError for a mesh without faces, with a vertex index out of range or a non-finite
// position, or when Embree fails.
ViewHits trace_view(const SurfaceMesh& mesh, const ViewCamera& camera);

}  // namespace hm
