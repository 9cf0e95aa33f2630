// A BVH over the hull triangles for plane queries, built with Embree's builder (rtcBuildBVH)
// into our own node type.
//
// Why this and not the other Embree routes: rtcPointQuery prunes with a query sphere, and a plane
// is not a sphere (a sphere around the plane's bounded part would take in most of the hull);
// rtcCollide needs a second scene of user geometry and reports triangle pairs, so a plane would
// have to be faked as a huge thin box whose float bounds lose the plane's precision. Our own
// 4-wide nodes let the traversal test each child box against the plane exactly, in double:
// |n.(c - p)| <= |n|.h (box centre c, half extent h), which is all a section needs.
//
// Embree's nodes are scattered over its allocator's blocks, and a query is bound by the cache
// misses of loading them; so after the build the tree is copied into one array in depth-first
// order (a subtree is contiguous), leaves become ranges of one primitive array held by their
// parent, and Embree's copy is released.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm::query {

class PlaneBvh {
 public:
  static constexpr unsigned kWidth = 4;  // children per node: fewer levels to descend

  // triangles[i] are vertex indices into positions (local frame, metres); primitive i is
  // reported as index i. slack (metres) widens every box, covering float rounding.
  void build(std::span<const Vec3d> positions, std::span<const std::array<Index, 3>> triangles,
             double slack);

  // Appends to out the slots [first, first + count) of every leaf whose box meets the plane
  // n.x = c (n unit, local frame). Slots number the triangles in the tree's leaf order, so that
  // neighbouring slots are neighbouring triangles in space and memory; prim(slot) is the
  // primitive index given to build.
  struct SlotRange {
    Index first, count;
  };
  void query_plane(const Vec3d& n, double c, std::vector<SlotRange>& out) const;

  Index prim(Index slot) const { return prims_[slot]; }
  const std::array<Index, 3>& corners(Index slot) const { return corners_[slot]; }

 private:
  // Child boxes (local frame, float, widened by the slack) stored in the parent. A child with
  // count 0 is the node at index first; otherwise it is the leaf prims_[first, first + count).
  struct Node {
    float lo[kWidth][3];
    float hi[kWidth][3];
    std::uint32_t first[kWidth];
    std::uint32_t count[kWidth];
    unsigned child_count = 0;
  };
  std::vector<Node> nodes_;   // nodes_[0] is the root; empty when there are no triangles
  std::vector<Index> prims_;  // per slot
  std::vector<std::array<Index, 3>> corners_;  // per slot: the triangle's vertex indices
};

}  // namespace hm::query
