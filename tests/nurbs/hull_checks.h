// Geometric checks on sets of patches shared by the generator tests: distances from points to the
// boundary edges of other patches, found by sampling and golden-section refinement on the exact
// surfaces (no tolerance from tessellation).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "nurbs/generate_hull.h"
#include "nurbs/nurbs_surface.h"

namespace hm::test {

// Every generated hull kind, and a spec with the generator's defaults otherwise.
inline constexpr HullKind kKinds[] = {HullKind::kWigley, HullKind::kRoundBilge, HullKind::kChine};

inline HullSpec spec_of(HullKind kind, int patches, bool full = false) {
  HullSpec s;
  s.kind = kind;
  s.patches = patches;
  s.full_hull = full;
  return s;
}

// Side k of a patch: 0: u = u0, 1: u = u1, 2: v = v0, 3: v = v1.
inline Vec3d edge_point(const NurbsSurface& s, int side, double t) {
  const double u = side == 0 ? s.u0 : (side == 1 ? s.u1 : s.u0 + t * (s.u1 - s.u0));
  const double v = side == 2 ? s.v0 : (side == 3 ? s.v1 : s.v0 + t * (s.v1 - s.v0));
  return evaluate(s, u, v);
}

struct Box {
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  void add(const Vec3d& p) {
    for (int c = 0; c < 3; ++c) {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  }
  bool contains(const Vec3d& p, double margin) const {
    for (int c = 0; c < 3; ++c) {
      if (p[c] < lo[c] - margin || p[c] > hi[c] + margin) return false;
    }
    return true;
  }
};

// Distance from q to the parameter line u = value (fixed_u) or v = value of s: Gauss-Newton on
// the line parameter, clamped to the domain, from each of the two best of 17 samples (one start
// can sit where the line is collapsed to a point and has no derivative).
inline double line_distance(const NurbsSurface& s, bool fixed_u, double value, const Vec3d& q) {
  const double lo = fixed_u ? s.v0 : s.u0, hi = fixed_u ? s.v1 : s.u1;
  const auto at = [&](double t) {
    return fixed_u ? evaluate_derivs(s, value, t, 1) : evaluate_derivs(s, t, value, 1);
  };
  constexpr int kSamples = 16;
  std::array<double, 2> start = {lo, lo};
  std::array<double, 2> near = {std::numeric_limits<double>::infinity(),
                                std::numeric_limits<double>::infinity()};
  for (int k = 0; k <= kSamples; ++k) {
    const double tk = lo + (hi - lo) * k / kSamples;
    const double dk = norm(at(tk).p - q);
    if (dk < near[0]) {
      near = {dk, near[0]}, start = {tk, start[0]};
    } else if (dk < near[1]) {
      near[1] = dk, start[1] = tk;
    }
  }
  double best = near[0];
  for (double t : start) {
    for (int it = 0; it < 30; ++it) {
      const SurfaceDerivs d = at(t);
      const Vec3d& dp = fixed_u ? d.sv : d.su;
      const double dd = dot(dp, dp);
      best = std::min(best, norm(d.p - q));
      if (dd <= 0) break;
      const double next = std::clamp(t - dot(d.p - q, dp) / dd, lo, hi);
      if (std::abs(next - t) < 1e-15 * (hi - lo)) break;
      t = next;
    }
    best = std::min(best, norm(at(t).p - q));
  }
  return best;
}

// Boxes of the four boundary curves of every patch, from their control rows (clamped knots: a
// boundary curve's control points are the first or last row or column of the net).
class EdgeIndex {
 public:
  explicit EdgeIndex(const std::vector<Patch>& patches) : patches_(patches) {
    for (const Patch& p : patches) {
      const NurbsSurface& s = p.surface;
      std::array<Box, 4> boxes;
      for (int j = 0; j < s.count_v; ++j) {
        boxes[0].add(s.point(0, j));
        boxes[1].add(s.point(s.count_u - 1, j));
      }
      for (int i = 0; i < s.count_u; ++i) {
        boxes[2].add(s.point(i, 0));
        boxes[3].add(s.point(i, s.count_v - 1));
      }
      boxes_.push_back(boxes);
    }
  }

  // Distance from q to the nearest boundary curve of any patch except `skip`, looking only at
  // curves whose box lies within `reach` of q (infinity when none does).
  double distance(const Vec3d& q, std::size_t skip, double reach) const {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < patches_.size(); ++k) {
      if (k == skip) continue;
      for (int side = 0; side < 4; ++side) {
        if (!boxes_[k][side].contains(q, reach)) continue;
        best = std::min(best, edge_distance(patches_[k].surface, side, q));
      }
    }
    return best;
  }

  static double edge_distance(const NurbsSurface& s, int side, const Vec3d& q) {
    return side < 2 ? line_distance(s, true, side == 0 ? s.u0 : s.u1, q)
                    : line_distance(s, false, side == 2 ? s.v0 : s.v1, q);
  }

 private:
  const std::vector<Patch>& patches_;
  std::vector<std::array<Box, 4>> boxes_;
};

// True when the point lies on an edge of the hull that has no neighbour: the deck line
// (z = depth) or, for a half hull, the centreplane.
inline bool on_free_edge(const Vec3d& p, const HullSpec& spec, double tol) {
  const double deck =
      spec.kind == HullKind::kWigley ? std::max(spec.depth, spec.draft) : spec.depth;
  return std::abs(p.z - deck) < tol || (!spec.full_hull && std::abs(p.y) < tol);
}

// Length of a patch side, by a polyline of 16 chords.
inline double edge_length(const NurbsSurface& s, int side) {
  double len = 0;
  for (int k = 0; k < 16; ++k)
    len += norm(edge_point(s, side, (k + 1) / 16.0) - edge_point(s, side, k / 16.0));
  return len;
}

}  // namespace hm::test
