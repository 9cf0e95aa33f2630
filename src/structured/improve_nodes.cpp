// Relocation with quality as the objective, after the Laplacian (relax_nodes.cpp): each free node
// in turn tries a few moves along its row curve and keeps the one that leaves the fewest rule
// values over their targets around it, then the mildest worst one; then the panels left passing
// through each other get wider moves that part them.
//
// Why the count comes first: scored by the worst value alone, a node beside a panel that cannot
// be mended (a short one fixed on a border row) moves to soften that panel's ratio and hands a
// failure to the panel beside it; the next node does the same, and a strip grades down towards
// the fixed panel. DTMB 5415's keel aft of the sonar dome lost 16 panels to the area rule that
// way. A move changes the areas of the panels around its node only, and every pair of those with
// their neighbours is counted, so the count is exact for the move.
//
// Gauss-Seidel in vertex order, serial: deterministic.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/bbox.h"
#include "mesh/adjacency.h"
#include "query/find_self_intersections.h"
#include "structured/editable_faces.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// Share of a node's gap to its row neighbours that one trial move spans.
constexpr double kTrialSteps[] = {-0.3, -0.15, 0.15, 0.3};
// The wider moves a node of a crossing panel tries, and how many crossing pairs are looked at.
constexpr double kUntangleSteps[] = {-0.6, -0.45, -0.3, -0.15, 0.15, 0.3, 0.45, 0.6};
constexpr std::size_t kUntangleListed = 64;
// A node whose worst rule value around it is under this share of its target is left alone.
constexpr double kWellInside = 0.5;

// Rule values over their targets around a node, then the worst (each over its target): the
// border-panel repairs' score.
using Score = EditableFaces::Score;

BBox3d face_box(std::span<const Vec3d> p, const Face& f) {
  BBox3d b;
  for (int c = 0; c < corner_count(f); ++c) b.add(p[f[c]]);
  return b;
}

// The faces around every node, their areas, and moves of one node along its row curve.
class NodeStars {
 public:
  NodeStars(std::span<const Row> rows, std::span<NodeSlot> slots, std::span<const Face> faces,
            std::vector<Vec3d>& positions)
      : rows_(rows),
        slots_(slots),
        faces_(faces),
        positions_(positions),
        adj_(build_edge_adjacency(faces, positions.size())),
        start_(positions.size() + 1, 0),
        area_(faces.size()),
        seen_(faces.size(), 0),
        tol_(crossing_tolerance(positions)) {
    const std::size_t nv = positions.size();
    for (const Face& f : faces)
      for (int c = 0; c < corner_count(f); ++c) ++start_[f[c] + 1];
    for (std::size_t v = 0; v < nv; ++v) start_[v + 1] += start_[v];
    around_.resize(start_[nv]);
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (int c = 0; c < corner_count(faces[f]); ++c)
        around_[fill[faces[f][c]]++] = static_cast<Index>(f);
    for (std::size_t f = 0; f < faces.size(); ++f) area_[f] = face_area(positions, faces[f]);
  }

  std::span<const Index> around(std::size_t v) const {
    return {around_.data() + start_[v], around_.data() + start_[v + 1]};
  }

  // A free node: not fixed, on a row, its row neighbours the vertices beside it (rows are
  // numbered node by node).
  bool free(std::size_t v) const {
    const NodeSlot& n = slots_[v];
    if (n.fixed || n.row == kInvalid || v == 0 || v + 1 >= slots_.size()) return false;
    const NodeSlot& a = slots_[v - 1];
    const NodeSlot& b = slots_[v + 1];
    return a.row == n.row && a.curve == n.curve && b.row == n.row && b.curve == n.curve;
  }

  // The arc length a trial share t of the gap from s0 (v's place before its trials) towards its
  // row neighbour moves v to; NaN when that is not strictly between the neighbours.
  double trial(std::size_t v, double s0, double t) const {
    const double lo = slots_[v - 1].s, hi = slots_[v + 1].s;
    const double s = s0 + t * (t < 0 ? s0 - lo : hi - s0);
    return s > lo && s < hi ? s : std::numeric_limits<double>::quiet_NaN();
  }

  void set(std::size_t v, double s) {
    slots_[v].s = s;
    positions_[v] = rows_[slots_[v].row].curves[slots_[v].curve].at(s);
    for (Index f : around(v)) area_[f] = face_area(positions_, faces_[f]);
  }

  // Quad side ratios over kSideTarget and neighbour area ratios over kAreaTarget, of the faces
  // around v and their neighbours across each side.
  Score score(std::size_t v) const {
    Score sc;
    auto add = [&](double q) {
      sc.worst = std::max(sc.worst, q);
      sc.fails += q > 1;
    };
    for (Index f : around(v)) {
      if (!is_triangle(faces_[f])) add(side_ratio(positions_, faces_[f]) / kSideTarget);
      for (int c = 0; c < corner_count(faces_[f]); ++c) {
        const Index g = adj_.opposite_face[4 * f + c];
        if (g == kInvalid) continue;
        const double a = area_[f], b = area_[g];
        add(std::min(a, b) > 0 ? std::max(a, b) / std::min(a, b) / kAreaTarget
                               : std::numeric_limits<double>::infinity());
      }
    }
    return sc;
  }

  // Pairs of a face around v and a face within two rings of it that pass through each other.
  // (Two faces around v share v, so they never count.)
  std::size_t crossings(std::size_t v) {
    const std::uint32_t own = ++epoch_, ring = ++epoch_;
    for (Index f : around(v)) seen_[f] = own;
    near_.clear();
    for (Index f : around(v)) {
      for (int c = 0; c < corner_count(faces_[f]); ++c) {
        for (Index g : around(faces_[f][c])) {
          if (seen_[g] == own || seen_[g] == ring) continue;
          seen_[g] = ring;
          near_.push_back(g);
        }
      }
    }
    std::size_t n = 0;
    for (Index f : around(v)) {
      const BBox3d bf = face_box(positions_, faces_[f]);
      for (Index g : near_) {
        n += bf.meets(face_box(positions_, faces_[g])) &&
             faces_cross(positions_, faces_[f], faces_[g], tol_);
      }
    }
    return n;
  }

  std::span<const Face> faces() const { return faces_; }
  std::span<const Vec3d> positions() const { return positions_; }
  double tol() const { return tol_; }

 private:
  std::span<const Row> rows_;
  std::span<NodeSlot> slots_;
  std::span<const Face> faces_;
  std::vector<Vec3d>& positions_;
  EdgeAdjacency adj_;
  std::vector<std::uint32_t> start_;
  std::vector<Index> around_;
  std::vector<double> area_;
  std::vector<Index> near_;
  std::vector<std::uint32_t> seen_;  // per face: the epoch of the crossings call that met it
  std::uint32_t epoch_ = 0;
  double tol_;
};

// One node: the trial move with the best score, kept when it beats staying and makes no more
// crossings around the node than it had. Returns whether the node moved.
bool improve_node(NodeStars& m, std::size_t v, std::span<const NodeSlot> slots) {
  const double s0 = slots[v].s;
  Score best = m.score(v);
  if (best.worst <= kWellInside) return false;
  double best_s = s0;
  for (double t : kTrialSteps) {
    const double s = m.trial(v, s0, t);
    if (std::isnan(s)) continue;
    m.set(v, s);
    const Score q = m.score(v);
    if (q.better_than(best)) {
      best = q;
      best_s = s;
    }
  }
  if (best_s != s0) {
    m.set(v, best_s);
    const std::size_t after = m.crossings(v);
    if (after > 0) {
      m.set(v, s0);
      if (after > m.crossings(v)) best_s = s0;
    }
  }
  m.set(v, best_s);
  return best_s != s0;
}

// The free corners of crossing pairs (the Laplacian moved every node at once, unchecked): each
// tries the wider moves and keeps the one with the fewest crossings around it, then the best
// score, when that is fewer crossings than it had. Returns the moves kept.
std::size_t untangle(NodeStars& m, std::span<const NodeSlot> slots) {
  SurfaceMesh view;
  view.positions.assign(m.positions().begin(), m.positions().end());
  view.faces.assign(m.faces().begin(), m.faces().end());
  const SelfIntersections tangles = find_self_intersections(view, m.tol(), kUntangleListed);
  std::size_t moves = 0;
  for (const FaceCrossing& x : tangles.first) {
    for (Index f : {x.face_a, x.face_b}) {
      const Face corners = m.faces()[f];
      for (int c = 0; c < corner_count(corners); ++c) {
        const Index v = corners[c];
        if (!m.free(v)) continue;
        const double s0 = slots[v].s;
        const std::size_t crossed = m.crossings(v);
        if (crossed == 0) continue;
        std::size_t best_crossed = crossed;
        Score best = m.score(v);
        double best_s = s0;
        for (double t : kUntangleSteps) {
          const double s = m.trial(v, s0, t);
          if (std::isnan(s)) continue;
          m.set(v, s);
          const std::size_t k = m.crossings(v);
          const Score q = m.score(v);
          if (k < best_crossed || (k == best_crossed && q.better_than(best))) {
            best_crossed = k;
            best = q;
            best_s = s;
          }
        }
        m.set(v, best_crossed < crossed ? best_s : s0);
        moves += best_crossed < crossed;
      }
    }
  }
  return moves;
}

}  // namespace

std::size_t improve_nodes(std::span<const Row> rows, std::span<NodeSlot> slots,
                          std::span<const Face> faces, std::vector<Vec3d>& positions, int passes) {
  NodeStars m(rows, slots, faces, positions);
  const std::size_t nv = positions.size();
  // A node is tried again only after something its trials read has moved: the corners of its
  // faces and of their edge neighbours, and its row neighbours (the bounds of its steps). Trying
  // it again before would give the same answer (it stays), so the passes are the same as trying
  // every node every time.
  std::vector<std::uint8_t> stale(nv, 1);
  auto touch = [&](std::size_t u) {
    stale[u - 1] = stale[u + 1] = 1;
    for (Index f : m.around(u)) {
      for (int c = 0; c < corner_count(faces[f]); ++c)
        for (Index g : m.around(faces[f][c]))
          for (int k = 0; k < corner_count(faces[g]); ++k) stale[faces[g][k]] = 1;
    }
  };
  std::size_t moves = 0;
  for (int pass = 0; pass < passes; ++pass) {
    std::size_t moved = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      if (!stale[v] || !m.free(v)) continue;
      stale[v] = 0;
      if (improve_node(m, v, slots)) {
        ++moved;
        touch(v);
      }
    }
    moves += moved;
    if (moved == 0) break;
  }
  if (passes > 0) moves += untangle(m, slots);
  return moves;
}

}  // namespace hm::structured
