// The border of a working merge mesh (every edge that one face uses), and a grid to find the
// border edges near a point. Internal to src/unstructured.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/adjacency.h"
#include "mesh/surface_mesh.h"

namespace hm::merge {

struct BorderEdge {
  Index v0 = kInvalid, v1 = kInvalid;  // as the face traverses it
  Index face = kInvalid;
  PatchId patch = kInvalid;
};

struct Border {
  std::vector<BorderEdge> edges;    // by ascending undirected edge key
  std::vector<Index> vertices;      // border vertices, ascending
  std::vector<double> edge_length;  // per border vertex (same order): mean of its border edges, m
};

// Border edges from the faces' edge adjacency (edges used twice or more are not border).
Border collect_border(const SurfaceMesh& mesh);
Border collect_border(const SurfaceMesh& mesh, const EdgeAdjacency& adj);

// Border edges binned in a uniform grid of cubic cells about the median edge length; an edge is
// listed in every cell its bounding box meets, so a query looks only at the cells its own ball
// meets (a fixed search radius sized for the longest edge would scan far too many).
class SegmentGrid {
 public:
  // Cells are `median_edges` median edge lengths wide, and at least `min_cell` (for zero-length
  // "edges": points). A query whose ball is about one median edge wide meets 8 cells of 2 median
  // edges, against 27 of one: a border is a curve, so the wider cells hold only twice the edges.
  SegmentGrid(std::span<const Vec3d> positions, std::span<const BorderEdge> edges,
              double min_cell = 0, double median_edges = 1);
  // Calls f(edge index) for every edge that may lie within `radius` of p (a superset; an edge
  // may come more than once).
  template <class F>
  void for_each_near(const Vec3d& p, double radius, F&& f) const {
    for_each_entry(p, radius, [&](std::size_t i) { f(order_[i]); });
  }

  // The same, less those whose bounding ball lies beyond the radius: what a nearest-edge search
  // needs. The test reads the entries in cell order, so most of what the cells give is dropped
  // before any edge is loaded.
  template <class F>
  void for_each_within(const Vec3d& p, double radius, F&& f) const {
    for_each_entry(p, radius, [&](std::size_t i) {
      const Vec3d q = p - entry_centre_[i];
      const double r = radius + entry_radius_[i];
      if (!(dot(q, q) > r * r)) f(order_[i]);
    });
  }

  // False when edge e certainly lies farther than d from p: its bounding ball, grown by a margin
  // far above the rounding of closest_on_segment, does. A nearest-edge search asks this before
  // the exact distance, whose division and root (latency, not work) were a third of the merge.
  bool may_be_within(Index e, const Vec3d& p, double d) const {
    const Vec3d q = p - ball_centre_[e];
    const double r = d + ball_radius_[e];
    return !(dot(q, q) > r * r);
  }

 private:
  // Calls g(entry) for the entries of every cell the box of the ball meets.
  template <class G>
  void for_each_entry(const Vec3d& p, double radius, G&& g) const {
    if (order_.empty()) return;
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max<std::int64_t>(cell(p[a] - radius, a), 0);
      hi[a] = std::min<std::int64_t>(cell(p[a] + radius, a), dims_[a] - 1);
      if (lo[a] > hi[a]) return;
    }
    // A ball much wider than the cells: every entry is cheaper than every cell.
    const double cells =
        double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
    if (cells > double(order_.size())) {
      for (std::size_t i = 0; i < order_.size(); ++i) g(i);
      return;
    }
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
          const std::uint64_t k = key(x, y, z);
          for (std::size_t i = first(k); i < order_.size() && keys_[i] == k; ++i) g(i);
        }
      }
    }
  }
  std::int64_t cell(double v, int axis) const;
  std::uint64_t key(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return std::uint64_t(x) + std::uint64_t(dims_[0]) *
                                  (std::uint64_t(y) + std::uint64_t(dims_[1]) * std::uint64_t(z));
  }
  // Index of the first entry of cell k, or order_.size() when the cell is empty.
  std::size_t first(std::uint64_t k) const;
  std::size_t slot_of(std::uint64_t k) const;

  Vec3d lo_;
  double size_ = 1;
  std::int64_t dims_[3] = {0, 0, 0};
  std::vector<std::uint64_t> keys_;  // sorted
  std::vector<Index> order_;         // edge index per sorted key
  std::vector<Vec3d> ball_centre_;   // per edge: its midpoint
  std::vector<double> ball_radius_;  // per edge: half its length, plus the margin, m
  std::vector<Vec3d> entry_centre_;  // the same per entry, in cell order
  std::vector<double> entry_radius_;
  // Occupied cells: key and first entry, open addressing (a power-of-two table).
  static constexpr std::uint64_t kEmptySlot = ~std::uint64_t{0};
  std::vector<std::uint64_t> slot_key_;
  std::vector<std::size_t> slot_first_;
};

// Unit direction into the face across border edge e, perpendicular to the edge (zero when the
// face is degenerate).
Vec3d edge_inward(const SurfaceMesh& m, const BorderEdge& e);
// The corner of the edge's face off the edge.
Index edge_apex(const SurfaceMesh& m, const BorderEdge& e);

// Per border vertex (b.vertices order): the mean inward direction of its border edges (unit, or
// zero). local maps a mesh vertex to its border index.
std::vector<Vec3d> vertex_inward(const SurfaceMesh& m, const Border& b,
                                 std::span<const Index> local);

// Closest point of segment [a, b] to p: parameter t in [0, 1] from a, and the distance.
struct SegmentPoint {
  double t = 0;
  double distance = 0;
};
SegmentPoint closest_on_segment(const Vec3d& p, const Vec3d& a, const Vec3d& b);

}  // namespace hm::merge
