// Patches whose surface collapses to a point or to a line. They have no area to mesh, and
// nothing downstream can size itself on them (a hull made of one such patch has no length), so
// the importer reports each by its entity and leaves it out.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "nurbs/patch.h"

namespace hm::iges {

// Per patch, why its surface collapses ("" when it does not). extents[i] is patch_extent of
// patch i, in metres. A point: the patch's box diagonal is at most 1e-9 of the whole model's
// (or 1 nm). A line: the sampled area is at most 1e-10 of the squared diagonal, the quality
// report's zero-area rule.
std::vector<std::string> find_collapsed(std::span<const PatchExtent> extents);

}  // namespace hm::iges
