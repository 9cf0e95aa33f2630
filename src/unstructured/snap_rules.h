// The snap's rules that its two steps share: snap_borders (the driver: nearest edges, splits,
// and applying welds and splits) and pair_welds (which border vertices weld). Internal to
// src/unstructured.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "kernels/weld.h"
#include "mesh/surface_mesh.h"
#include "unstructured/merge_border.h"

namespace hm::merge {

// A vertex this close to an edge end (as a fraction of the edge) joins that end rather than
// splitting the edge: the split would leave a sliver.
constexpr double kEndFraction = 0.3;

struct Split {
  Index edge = kInvalid;  // border edge index
  double t = 0;           // along v0 -> v1
  double distance = 0;
};

// Two borders may be stitched only where their patches lie on different sides: continuing each
// other (inward directions opposite) or meeting at a knuckle (about perpendicular). Inward
// directions within 60 degrees mean the patches fold onto each other (a sliver of one patch
// whose two border runs lie close together, a patch lying on another), and stitching there
// would make an edge with three faces.
constexpr double kFoldCos = 0.5;
// ... except where the two halves of a full hull meet in the centre plane (y = 0) at a fine
// stem, forefoot or bulb nose, well inside 60 degrees of each other: the vertex lies within its
// tolerance of the plane, the two patches leave it to either side (inward directions of
// opposite y) at least kWedgeMin apart, its own border runs along the other border edge (each
// of its own border edges within about 25 degrees of it: kAlongCos in snap_borders.cpp), and
// it lies on that edge, within
// kOnEdgeShare of the edge's length (its chord error: the halves' borders sampled at different
// points of one curve), or across the wedge from it (the way from the edge to the vertex within
// about 45 degrees of the inward directions' difference: the halves mirrored a gap apart).
// Elsewhere a fold is no wedge: a remnant of an overlap the cut left, one patch's border lying
// along another's 12 degrees apart on the same side (the generated 100-patch chine hull with
// gaps and overlaps, at a chine), must not be stitched.
constexpr double kOnEdgeShare = 0.05;
constexpr double kWedgeMin = 0.087;  // |difference of two unit vectors 5 degrees apart|
constexpr double kAcrossCos = 0.7;

// What the snap knows of each border vertex (by border index) when it pairs them.
struct BorderView {
  std::span<const double> tol;           // gap tolerance, m, cut to half its patch's width
  std::span<const Split> near;           // nearest other patch's border edge within tol
  std::span<const Vec3d> inward;         // unit, along its patch away from the border
  std::span<const Vec3d> points;         // position before the snap
  std::span<const std::uint32_t> group;  // its patch
  std::span<const Index> local;          // mesh vertex -> border index (kInvalid off the border)
};

// Score welds: the pairs of border vertices that may weld (a < b, sorted by (a, b), each once).
// A vertex near an end of its nearest other-patch edge joins that end; close pairs from the weld
// kernel catch vertices that meet at a patch corner where no edge is nearest, under the rules in
// pair_welds.cpp (tolerances, folds and wedges, a third patch between, a thin hull).
std::vector<ClosePair> weld_pairs(const SurfaceMesh& m, const Border& b, const BorderView& v,
                                  double length);

}  // namespace hm::merge
