// A hull patch: one NURBS surface, the loops that trim it, and where it came from.
#pragma once

#include <string>
#include <vector>

#include "core/bbox.h"
#include "core/types.h"
#include "nurbs/nurbs_curve.h"
#include "nurbs/nurbs_surface.h"

namespace hm {

// How the surface was wrapped in the file (reported by `hullmesh info`).
enum class Wrapping {
  kPlain,      // a bare surface entity (128, 118, 120, 122, 114, 108, 190)
  kBounded,    // 143 bounded surface
  kTrimmed,    // 144 trimmed surface
  kFace,       // 510 face of a B-rep (508 loops)
  kGenerated,  // made by `hullmesh generate`
};
const char* to_string(Wrapping w);

// A closed loop in the (u, v) domain of the patch, made of curves with z = 0 chained head to tail.
struct TrimLoop {
  std::vector<NurbsCurve> curves_uv;
  bool outer = true;
};

struct Patch {
  NurbsSurface surface;
  // Empty: the whole parameter domain. Otherwise the outer loop comes first (outer = true) and the
  // holes follow. A loop that is the natural boundary of the domain is dropped on import.
  std::vector<TrimLoop> loops;
  // True when the face uses the surface reversed (normal -su x sv), from a 510/514 orientation
  // flag or an injected flip.
  bool reversed = false;
  Wrapping wrapping = Wrapping::kPlain;
  int source_type = 128;  // IGES type of the surface entity
  int de = 0;             // DE number of the surface entity; 0 when generated
  int wrapper_de = 0;     // DE number of the 143/144/510 that wrapped it; 0 when none
  std::string name;       // from 406 form 15 or the DE label; may be empty
};

// A 2D polygon of each loop of the patch, within tol in parameter units. Empty when untrimmed.
std::vector<std::vector<Vec2d>> sample_loops_uv(const Patch& p, double tol_uv);

// Area of the patch's surface (m^2), inside its loops, by Gauss-Legendre quadrature over the knot
// spans (adaptively split where a trim loop crosses a cell). A cell is accepted when rules of two
// orders agree to rel_tol of its value (or of its share of the patch): kAreaExactTol, the
// default, for areas that are reported or compared; kAreaEstimateTol for sizes derived from the
// area, at about half the cost. rel_tol outside (0, 1) is an InternalError.
inline constexpr double kAreaExactTol = 1e-11;
inline constexpr double kAreaEstimateTol = 1e-5;
double patch_area(const Patch& p, double rel_tol = kAreaExactTol);

// Bounding box of the surface over its whole parameter domain (trims ignored), from a grid of
// 4 samples per knot span and direction: tight to the surface, unlike the control net's box,
// which a curved patch overshoots (a Wigley's net reaches twice its beam). From the same samples,
// the area of the untrimmed surface as the sum of the sample grid's triangles (m^2): a cheap
// lower estimate, zero when the surface collapses to a line or a point, whatever its
// parametrisation.
struct PatchExtent {
  BBox3d box;
  double grid_area = 0;
};
PatchExtent patch_extent(const Patch& p);

}  // namespace hm
