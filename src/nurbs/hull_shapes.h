// The defining shapes of the generated hulls, as exact B-spline part surfaces of the port half
// (y >= 0), plus their facts from closed forms or fine quadrature of the defining shape.
// Ship frame: x forward from the aft perpendicular, y to port, z up from the keel; metres.
//
// Every part surface runs u aft to fore (or, for a transom, from the centreline outward) and
// v from the deck down to the keel, so that su x sv points out of the hull.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "nurbs/generate_hull.h"
#include "nurbs/nurbs_surface.h"

namespace hm {

// What lies beyond one side of a part surface.
enum class SideKind {
  kFree,        // open edge (deck line)
  kShared,      // another part of the same half hull (a knuckle line)
  kCentre,      // on the centreplane y = 0: shared with the starboard half of a full hull
  kDegenerate,  // collapsed to a point
};

struct HullPart {
  std::string name;
  NurbsSurface surface;
  std::array<SideKind, 4> sides{};  // u0, u1, v0, v1
};

// A knuckle as a parameter line of a part: u = value (fixed_u) or v = value, over the whole
// range of the other parameter.
struct KnuckleLine {
  int part = 0;
  bool fixed_u = true;
  double value = 0;
};

struct HullShape {
  std::vector<HullPart> parts;  // separate part surfaces; knuckles lie on their borders
  // All parts in one surface, with knots of full multiplicity at the knuckles; used when fewer
  // patches than parts are asked for.
  HullPart merged;
  std::vector<KnuckleLine> knuckles;  // on `parts`
  double displacement_volume = 0;     // m^3, both sides, below z = draft
  double wetted_area = 0;  // m^2, both sides, below z = draft (immersed transom included)
};

// Throws UsageError when the spec's sizes do not make the kind's shape (for example a Wigley
// depth of twice the draft or more, or a draft not below the depth).
HullShape make_hull_shape(const HullSpec& spec);

}  // namespace hm
