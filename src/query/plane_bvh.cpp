#include "query/plane_bvh.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <new>

#include "query/embree_device.h"

namespace hm::query {
namespace {

// Nodes live in memory from Embree's thread-local allocator, owned by the RTCBVH handle. They
// are trivially destructible, so releasing the handle frees them.
struct Node {
  bool leaf;
};

// Child boxes are stored in the parent (local frame, float, already widened by the slack).
constexpr unsigned kWidth = 4;  // children per inner node: fewer levels to descend

struct Inner : Node {
  unsigned child_count;
  float lo[kWidth][3];
  float hi[kWidth][3];
  const Node* child[kWidth];
};

// count primitive indices follow the header in the same allocation.
struct Leaf : Node {
  std::uint32_t count;
  const std::uint32_t* ids() const { return reinterpret_cast<const std::uint32_t*>(this + 1); }
  std::uint32_t* ids() { return reinterpret_cast<std::uint32_t*>(this + 1); }
};

// The builder callbacks below do no more than placement-new and copies, so nothing can throw
// out of them into Embree.
void* create_inner(RTCThreadLocalAllocator alloc, unsigned child_count, void*) noexcept {
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(Inner), 16);
  if (!mem) return nullptr;
  Inner* n = new (mem) Inner{};
  n->leaf = false;
  n->child_count = child_count;
  return n;
}

void set_children(void* node, void** children, unsigned count, void*) noexcept {
  Inner* n = static_cast<Inner*>(node);
  for (unsigned i = 0; i < count && i < kWidth; ++i)
    n->child[i] = static_cast<const Node*>(children[i]);
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned count, void*) noexcept {
  Inner* n = static_cast<Inner*>(node);
  for (unsigned i = 0; i < count && i < kWidth; ++i) {
    n->lo[i][0] = bounds[i]->lower_x;
    n->lo[i][1] = bounds[i]->lower_y;
    n->lo[i][2] = bounds[i]->lower_z;
    n->hi[i][0] = bounds[i]->upper_x;
    n->hi[i][1] = bounds[i]->upper_y;
    n->hi[i][2] = bounds[i]->upper_z;
  }
}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count,
                  void*) noexcept {
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(Leaf) + count * sizeof(std::uint32_t), 16);
  if (!mem) return nullptr;
  Leaf* leaf = new (mem) Leaf{};
  leaf->leaf = true;
  leaf->count = static_cast<std::uint32_t>(count);
  for (size_t i = 0; i < count; ++i) leaf->ids()[i] = prims[i].primID;
  return leaf;
}

float round_down(double x) {
  return std::nextafter(static_cast<float>(x), -std::numeric_limits<float>::infinity());
}
float round_up(double x) {
  return std::nextafter(static_cast<float>(x), std::numeric_limits<float>::infinity());
}

// Box [lo, hi] (float, local frame) meets the plane n.x = c when the centre's distance to the
// plane is at most the box's half extent projected on n.
bool box_meets_plane(const float* lo, const float* hi, const Vec3d& n, double c) {
  double centre_dist = -c, radius = 0;
  for (int k = 0; k < 3; ++k) {
    const double mid = 0.5 * (double{lo[k]} + double{hi[k]});
    const double half = 0.5 * (double{hi[k]} - double{lo[k]});
    centre_dist += n[k] * mid;
    radius += std::abs(n[k]) * half;
  }
  return std::abs(centre_dist) <= radius;
}

}  // namespace

PlaneBvh::~PlaneBvh() {
  if (bvh_) rtcReleaseBVH(bvh_);
}

void PlaneBvh::build(std::span<const Vec3d> positions,
                     std::span<const std::array<Index, 3>> triangles, double slack) {
  std::vector<RTCBuildPrimitive> prims(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    Vec3d lo = positions[triangles[i][0]], hi = lo;
    for (int k = 1; k < 3; ++k) {
      const Vec3d& p = positions[triangles[i][k]];
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    }
    RTCBuildPrimitive& b = prims[i];
    b.lower_x = round_down(lo.x - slack);
    b.lower_y = round_down(lo.y - slack);
    b.lower_z = round_down(lo.z - slack);
    b.upper_x = round_up(hi.x + slack);
    b.upper_y = round_up(hi.y + slack);
    b.upper_z = round_up(hi.z + slack);
    b.geomID = 0;
    b.primID = static_cast<unsigned>(i);
  }
  if (bvh_) rtcReleaseBVH(bvh_);
  bvh_ = rtcNewBVH(embree_device());
  check_embree("rtcNewBVH");
  RTCBuildArguments args = rtcDefaultBuildArguments();
  // Medium quality: binned SAH without spatial splits (which would need splitPrimitive and a
  // larger primitive array); plane queries are cheap enough that the extra quality would not pay.
  args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
  args.maxBranchingFactor = kWidth;
  args.maxDepth = 64;
  args.minLeafSize = 1;
  args.maxLeafSize = 8;
  args.bvh = bvh_;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = create_inner;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  root_ = prims.empty() ? nullptr : rtcBuildBVH(&args);
  check_embree("rtcBuildBVH");
}

void PlaneBvh::query_plane(const Vec3d& n, double c, std::vector<Index>& out) const {
  if (!root_) return;
  const Node* stack[64 * kWidth];
  int top = 0;
  stack[top++] = static_cast<const Node*>(root_);
  while (top > 0) {
    const Node* node = stack[--top];
    if (node->leaf) {
      const Leaf* leaf = static_cast<const Leaf*>(node);
      out.insert(out.end(), leaf->ids(), leaf->ids() + leaf->count);
      continue;
    }
    const Inner* inner = static_cast<const Inner*>(node);
    for (unsigned k = 0; k < inner->child_count && k < kWidth; ++k) {
      if (box_meets_plane(inner->lo[k], inner->hi[k], n, c)) stack[top++] = inner->child[k];
    }
  }
}

}  // namespace hm::query
