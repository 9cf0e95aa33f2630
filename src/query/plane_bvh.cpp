#include "query/plane_bvh.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <new>

#include "query/embree_device.h"

namespace hm::query {
namespace {

// The builder's nodes live in memory from Embree's thread-local allocator, owned by the RTCBVH
// handle. They are trivially destructible, so releasing the handle frees them.
struct BuildNode {
  bool leaf;
};

constexpr unsigned kWidth = PlaneBvh::kWidth;

struct BuildInner : BuildNode {
  unsigned child_count;
  float lo[kWidth][3];
  float hi[kWidth][3];
  const BuildNode* child[kWidth];
};

// count primitive indices follow the header in the same allocation.
struct BuildLeaf : BuildNode {
  std::uint32_t count;
  const std::uint32_t* ids() const { return reinterpret_cast<const std::uint32_t*>(this + 1); }
  std::uint32_t* ids() { return reinterpret_cast<std::uint32_t*>(this + 1); }
};

// The builder callbacks below do no more than placement-new and copies, so nothing can throw
// out of them into Embree.
void* create_inner(RTCThreadLocalAllocator alloc, unsigned child_count, void*) noexcept {
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(BuildInner), 16);
  if (!mem) return nullptr;
  BuildInner* n = new (mem) BuildInner{};
  n->leaf = false;
  n->child_count = child_count;
  return n;
}

void set_children(void* node, void** children, unsigned count, void*) noexcept {
  BuildInner* n = static_cast<BuildInner*>(node);
  for (unsigned i = 0; i < count && i < kWidth; ++i)
    n->child[i] = static_cast<const BuildNode*>(children[i]);
}

void set_bounds(void* node, const RTCBounds** bounds, unsigned count, void*) noexcept {
  BuildInner* n = static_cast<BuildInner*>(node);
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
  void* mem = rtcThreadLocalAlloc(alloc, sizeof(BuildLeaf) + count * sizeof(std::uint32_t), 16);
  if (!mem) return nullptr;
  BuildLeaf* leaf = new (mem) BuildLeaf{};
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

// Releases the Embree BVH (and with it the builder's nodes) on every path out of build().
struct BvhHandle {
  RTCBVH bvh = nullptr;
  ~BvhHandle() {
    if (bvh) rtcReleaseBVH(bvh);
  }
};

}  // namespace

void PlaneBvh::build(std::span<const Vec3d> positions,
                     std::span<const std::array<Index, 3>> triangles, double slack) {
  nodes_.clear();
  prims_.clear();
  corners_.clear();
  if (triangles.empty()) return;
  std::vector<RTCBuildPrimitive> prims(triangles.size());
  RTCBounds all{};
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
    if (i == 0) {
      all = {b.lower_x, b.lower_y, b.lower_z, 0, b.upper_x, b.upper_y, b.upper_z, 0};
    } else {
      all.lower_x = std::min(all.lower_x, b.lower_x);
      all.lower_y = std::min(all.lower_y, b.lower_y);
      all.lower_z = std::min(all.lower_z, b.lower_z);
      all.upper_x = std::max(all.upper_x, b.upper_x);
      all.upper_y = std::max(all.upper_y, b.upper_y);
      all.upper_z = std::max(all.upper_z, b.upper_z);
    }
  }
  BvhHandle handle;
  handle.bvh = rtcNewBVH(embree_device());
  check_embree("rtcNewBVH");
  RTCBuildArguments args = rtcDefaultBuildArguments();
  // Low quality (Embree's Morton builder): the binned SAH of medium quality took 18 ms on kcs's
  // 41,000-triangle surface against 8 ms, and plane searches ran no faster on it (bench_query:
  // 1,000 sections of 25,600 and 409,600 triangles, 34 / 188 ms against 37 / 191 ms).
  args.buildQuality = RTC_BUILD_QUALITY_LOW;
  args.maxBranchingFactor = kWidth;
  args.maxDepth = 64;
  // Leaves of 8: with the SAH's own choice (1 to 8) leaves held 1.3 triangles on average, and a
  // waterline visited 2,100 nodes for 3,000 triangles; testing a few more triangles costs less
  // than the node loads (measured: the search takes a third of the time).
  args.minLeafSize = 8;
  args.maxLeafSize = 8;
  args.bvh = handle.bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = create_inner;
  args.setNodeChildren = set_children;
  args.setNodeBounds = set_bounds;
  args.createLeaf = create_leaf;
  const BuildNode* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
  check_embree("rtcBuildBVH");

  // Depth-first copy. The root is always a flat node; a root that is a leaf becomes its only
  // child, under the box of all primitives.
  prims_.reserve(triangles.size());
  auto copy_leaf = [&](const BuildLeaf* leaf, unsigned& first, unsigned& count) {
    first = static_cast<unsigned>(prims_.size());
    count = leaf->count;
    prims_.insert(prims_.end(), leaf->ids(), leaf->ids() + leaf->count);
  };
  auto flatten = [&](auto&& self, const BuildInner* inner) -> void {
    const std::size_t at = nodes_.size();
    nodes_.emplace_back();
    nodes_[at].child_count = std::min(inner->child_count, kWidth);
    for (unsigned k = 0; k < nodes_[at].child_count; ++k) {
      for (int a = 0; a < 3; ++a) {
        nodes_[at].lo[k][a] = inner->lo[k][a];
        nodes_[at].hi[k][a] = inner->hi[k][a];
      }
      const BuildNode* child = inner->child[k];
      if (child->leaf) {
        unsigned first = 0, count = 0;
        copy_leaf(static_cast<const BuildLeaf*>(child), first, count);
        nodes_[at].first[k] = first;
        nodes_[at].count[k] = count;
      } else {
        nodes_[at].first[k] = static_cast<unsigned>(nodes_.size());
        nodes_[at].count[k] = 0;
        self(self, static_cast<const BuildInner*>(child));
      }
    }
  };
  if (root->leaf) {
    nodes_.emplace_back();
    nodes_[0].child_count = 1;
    const float lo[3] = {all.lower_x, all.lower_y, all.lower_z};
    const float hi[3] = {all.upper_x, all.upper_y, all.upper_z};
    for (int a = 0; a < 3; ++a) {
      nodes_[0].lo[0][a] = lo[a];
      nodes_[0].hi[0][a] = hi[a];
    }
    copy_leaf(static_cast<const BuildLeaf*>(root), nodes_[0].first[0], nodes_[0].count[0]);
  } else {
    flatten(flatten, static_cast<const BuildInner*>(root));
  }
  corners_.resize(prims_.size());
  for (std::size_t slot = 0; slot < prims_.size(); ++slot) corners_[slot] = triangles[prims_[slot]];
}

void PlaneBvh::query_plane(const Vec3d& n, double c, std::vector<SlotRange>& out) const {
  if (nodes_.empty()) return;
  std::uint32_t stack[64 * kWidth];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    for (unsigned k = 0; k < node.child_count; ++k) {
      if (!box_meets_plane(node.lo[k], node.hi[k], n, c)) continue;
      if (node.count[k] > 0) {
        out.push_back({node.first[k], node.count[k]});
      } else {
        stack[top++] = node.first[k];
      }
    }
  }
}

}  // namespace hm::query
