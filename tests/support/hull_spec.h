// A generated hull's proportions in one call, for tests that replay a property-test case.
// Header only: the test must link hm_nurbs.
#pragma once

#include "nurbs/generate_hull.h"

namespace hm::test {

// Length, beam, draft and depth in metres; `patches` over the half (or, with full, both sides).
inline HullSpec hull_spec(HullKind kind, double length, double beam, double draft, double depth,
                          int patches, bool full = false) {
  HullSpec spec;
  spec.kind = kind;
  spec.length = length;
  spec.beam = beam;
  spec.draft = draft;
  spec.depth = depth;
  spec.patches = patches;
  spec.full_hull = full;
  return spec;
}

}  // namespace hm::test
