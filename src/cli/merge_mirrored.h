// A heeled half hull made whole for meshing: its half merged alone, then the merged surface
// mirrored about the centre plane. Merging the patches and their images together made the merge
// weld two copies of every strip along the keel, and where a file's half holds a thin double
// layer there (kcs.iges's 2.6 mm flat keel strip under the skeg's patch, x = -3.49 to -3.31 m)
// the two copies crossed: 43-92 pairs of faces through each other in every heeled kcs, and 4
// pairs of panels. The mirror of a merged half shares its centre-plane vertices exactly.
#pragma once

#include <span>

#include "core/progress.h"
#include "nurbs/patch.h"
#include "quality/hydrostatics.h"
#include "tessellate/tessellate.h"
#include "unstructured/merge.h"

namespace hm::cli {

// whole: the file's patches (file frame) with their mirror images after them, as
// add_mirror_image makes them (image of patch p is p + n, u reversed). half_tessellation: the n
// first patches tessellated in the file frame. Returns the whole hull's merged surface in the
// frame `to_placed` maps to: the half's faces, then their images on patches p + n with
// (u, v) -> (u0 + u1 - u, v); the open boundary within kPlaneTolerance of the hull's length of
// y = 0 put on it and shared. The report is
// the half's merge, its topology taken again on the whole and the flipped patches' images
// added; the maps lead to half_tessellation.
MergedSurface merge_mirrored_half(std::span<const Patch> whole,
                                  const Tessellation& half_tessellation,
                                  const MergeOptions& options, const FloatingTransform& to_placed,
                                  Progress& progress);

}  // namespace hm::cli
