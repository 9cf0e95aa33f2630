// Faces of a structured panel mesh under small local edits (renaming corners, adding and removing
// faces, moving nodes), with the panel rules each edit is scored by. Private to src/structured:
// the border-panel repairs and the wedge collapse share it.
#pragma once

#include <array>
#include <cstdint>
#include <set>
#include <span>
#include <utility>
#include <vector>

#include "core/types.h"
#include "core/vec.h"
#include "mesh/surface_mesh.h"
#include "structured/structured_steps.h"

namespace hm::structured {

// A panel is distorted past these (the rules themselves; the scores use kSideTarget and
// kAreaTarget, a little inside them).
inline constexpr double kSideLimit = 4, kAreaLimit = 2;

// The mesh as the repairs change it: faces (kInvalid in slot 0: removed), vertex -> faces, and
// positions. Small local edits; queries read it as it stands.
class EditableFaces {
 public:
  EditableFaces(std::vector<Face>& faces, std::vector<Vec3d>& positions);

  const Face& face(Index f) const { return faces_[f]; }
  bool removed(Index f) const { return faces_[f][0] == kInvalid; }
  const std::set<Index>& around(Index v) const { return around_[v]; }
  const Vec3d& position(Index v) const { return positions_[v]; }
  std::span<const Vec3d> positions() const { return positions_; }

  // The face other than f that has the side a-b; kInvalid when none (a free side).
  Index across(Index f, Index a, Index b) const;

  // The worst rule value, over its yardstick, of the faces in `core` and their neighbours' area
  // ratios.
  double worst(const std::set<Index>& core) const;

  // A candidate's score: the panels failing a rule among `core` and the faces beside them (the
  // rule shares are what panel codes are judged by), then the worst rule value over `core`.
  struct Score {
    std::size_t fails = 0;
    double worst = 0;
    bool better_than(const Score& o) const {
      return fails != o.fails ? fails < o.fails : worst < o.worst - 1e-9;
    }
  };
  Score score(const std::set<Index>& core) const;
  // The same with the failing panels counted over `judged`, a set fixed before the edits it
  // compares (the faces beside `core` change as corners merge).
  Score score(const std::set<Index>& core, const std::set<Index>& judged) const;

  // The quad side ratio (1 for a triangle) and the largest area ratio to a neighbour of face f.
  void rules(Index f, double& side, double& area) const;

  // No face in `core` repeats a corner, every side of them has at most two faces, and no two
  // faces have the same corners.
  bool manifold(const std::set<Index>& core) const;

  // Some face in `core` has next to no area (under kFlatArea of its longest side squared): a
  // merge along a straight boundary can leave three corners on one line.
  bool flat(const std::set<Index>& core) const;

  // The faces in `core` and every face that shares a corner with one of them: where an edit of
  // `core` is checked for crossings.
  std::set<Index> ring(const std::set<Index>& core) const;

  // The pairs of a face in `core` and another in `near` that pass through each other
  // (query/find_self_intersections.h; tol in m): an edit may merge a node so that panels it
  // drags along cover others that share no corner with them.
  std::size_t crossings(const std::set<Index>& core, const std::set<Index>& near, double tol) const;

  Index add_face(const Face& h) {
    faces_.push_back(h);
    const Index f = static_cast<Index>(faces_.size() - 1);
    for (int c = 0; c < corner_count(h); ++c) around_[h[c]].insert(f);
    return f;
  }
  void pop_face() {
    const Index f = static_cast<Index>(faces_.size() - 1);
    set_face(f, {kInvalid, kInvalid, kInvalid, kInvalid});
    faces_.pop_back();
  }

  void set_face(Index f, const Face& h);
  // Every face around `from` with that corner renamed `to` (renamed(); undo by setting the faces
  // back as they were).
  void merge_node(Index from, Index to);
  void set_position(Index v, const Vec3d& p) { positions_[v] = p; }

 private:
  std::vector<Face>& faces_;
  std::vector<Vec3d>& positions_;
  std::vector<std::set<Index>> around_;
};

// Face h with vertex `from` renamed `to`, and a repeated corner dropped (a quad that loses a side
// becomes a triangle; one that loses two, or a triangle that loses one, is removed).
Face renamed(const Face& h, Index from, Index to);

// What a repair may do with each node of the panel mesh.
struct NodeFreedom {
  std::vector<std::uint8_t> movable;     // free row nodes off every boundary and knuckle
  std::vector<std::uint8_t> on_knuckle;  // on a knuckle edge
  std::vector<std::uint8_t> straight;    // on the boundary, which runs on straight through it
  std::set<std::pair<Index, Index>> boundary_edges;  // (lower, higher) vertex

  // Whether node i may merge into its neighbour b: a movable node may; so may a row's end node
  // on the hull's boundary where the side i-b is a boundary edge and the boundary runs straight
  // through i (the boundary loses a node and keeps its line: the keel, the waterline). Never a
  // node on a knuckle.
  bool may_merge(Index i, Index b, std::span<const NodeSlot> slots) const;
};
NodeFreedom node_freedom(std::span<const NodeSlot> slots,
                         std::span<const std::array<Index, 2>> knuckle_edges,
                         const SurfaceMesh& mesh);

// Drops the faces a repair removed (kInvalid in slot 0), with their blocks, keeping the order.
void drop_removed_faces(SurfaceMesh& mesh);

}  // namespace hm::structured
