// A BVH over the hull triangles for plane queries, built with Embree's builder (rtcBuildBVH)
// into our own node type.
//
// Why this and not the other Embree routes: rtcPointQuery prunes with a query sphere, and a plane
// is not a sphere (a sphere around the plane's bounded part would take in most of the hull);
// rtcCollide needs a second scene of user geometry and reports triangle pairs, so a plane would
// have to be faked as a huge thin box whose float bounds lose the plane's precision. Our own
// 4-wide nodes let the traversal test each child box against the plane exactly, in double:
// |n.(c - p)| <= |n|.h (box centre c, half extent h), which is all a section needs.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"

namespace hm::query {

class PlaneBvh {
 public:
  PlaneBvh() = default;
  PlaneBvh(const PlaneBvh&) = delete;
  PlaneBvh& operator=(const PlaneBvh&) = delete;
  ~PlaneBvh();

  // triangles[i] are vertex indices into positions (local frame, metres); primitive i is
  // reported as index i. slack (metres) widens every box, covering float rounding.
  void build(std::span<const Vec3d> positions, std::span<const std::array<Index, 3>> triangles,
             double slack);

  // Appends to out every triangle whose box meets the plane n.x = c (n unit, local frame).
  void query_plane(const Vec3d& n, double c, std::vector<Index>& out) const;

 private:
  RTCBVH bvh_ = nullptr;
  const void* root_ = nullptr;
};

}  // namespace hm::query
