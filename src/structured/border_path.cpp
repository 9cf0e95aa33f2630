// Paths along the surface's boundary: where a point lies on it, the vertices between two such
// places, and resampling at the panel size.
#include "structured/border_path.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace hm::structured {
namespace {

// A path point turning by more than this (degrees) is kept as a node.
constexpr double kCornerDeg = 40;
// Resampled nodes nearer each other than this (metric units: panels) are one node.
constexpr double kMinNode = 0.25;
// ... except a corner that far or farther off the chord that would replace it, or the last
// corner before the path's end down to kMinCorner from it (see resample).
constexpr double kMinDepth = 0.1;
constexpr double kMinCorner = 0.05;

}  // namespace

LoopSpot nearest_boundary_edge(const SurfaceMesh& s, const EdgeAdjacency& adj, const Vec3d& q) {
  LoopSpot best;
  // Squared distances first: the root (monotone) is taken only for an edge that may be nearer,
  // and an edge is taken only when its rooted distance is, as when every edge was rooted.
  double best_squared = std::numeric_limits<double>::infinity();
  for (std::size_t l = 0; l < adj.boundary_loops.size(); ++l) {
    const std::vector<Index>& v = adj.boundary_loops[l].vertices;
    for (std::size_t e = 0; e < v.size(); ++e) {
      const Vec3d& a = s.positions[v[e]];
      const Vec3d& b = s.positions[v[(e + 1) % v.size()]];
      const Vec3d d = b - a;
      const double dd = squared_norm(d);
      const double f = dd > 0 ? std::clamp(dot(q - a, d) / dd, 0.0, 1.0) : 0.0;
      const double squared = squared_norm(a + d * f - q);
      if (!(squared < best_squared)) continue;
      const double dist = std::sqrt(squared);
      if (dist < best.distance) {
        best = {l, e, dist};
        best_squared = squared;
      }
    }
  }
  return best;
}

namespace {

// Visits the loop vertices strictly between spots a and b, walking forwards or backwards, while
// visit returns true; returns whether every one was visited.
template <class Visit>
bool walk_loop(const std::vector<Index>& v, std::size_t ea, std::size_t eb, bool forward,
               Visit&& visit) {
  const std::size_t n = v.size();
  if (ea == eb) return true;  // both ends on one boundary edge: nothing between them
  if (forward) {
    for (std::size_t k = (ea + 1) % n;; k = (k + 1) % n) {
      if (!visit(v[k])) return false;
      if (k == eb) return true;
    }
  }
  for (std::size_t k = ea;; k = (k + n - 1) % n) {
    if (!visit(v[k])) return false;
    if (k == (eb + 1) % n) return true;
  }
}

}  // namespace

// The loop vertices strictly between spots a and b, walking forwards or backwards.
std::vector<Index> loop_path(const std::vector<Index>& v, std::size_t ea, std::size_t eb,
                             bool forward) {
  std::vector<Index> out;
  walk_loop(v, ea, eb, forward, [&](Index k) {
    out.push_back(k);
    return true;
  });
  return out;
}

// Resamples the polyline pts at about one panel per metric unit, keeping its corners; returns
// the interior points (the two ends excluded).
std::vector<Vec3d> resample(const std::vector<Vec3d>& pts, const Metric& metric) {
  if (pts.size() < 2) return {};
  std::vector<std::size_t> keep{0};
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    const Vec3d a = pts[i] - pts[i - 1], b = pts[i + 1] - pts[i];
    const double na = norm(a), nb = norm(b);
    if (na == 0 || nb == 0) continue;
    if (dot(a, b) / (na * nb) < std::cos(kCornerDeg * M_PI / 180)) keep.push_back(i);
  }
  keep.push_back(pts.size() - 1);
  std::vector<Vec3d> out;
  std::vector<std::uint8_t> corner;  // per out point: a kept corner of pts
  for (std::size_t k = 0; k + 1 < keep.size(); ++k) {
    std::vector<double> s{0};
    for (std::size_t i = keep[k] + 1; i <= keep[k + 1]; ++i)
      s.push_back(s.back() + metric.length(pts[i - 1], pts[i]));
    const int n = std::max(1, static_cast<int>(std::lround(s.back())));
    for (int j = 1; j < n; ++j) {
      const double t = s.back() * j / n;
      std::size_t i = 0;
      while (i + 2 < s.size() && s[i + 1] < t) ++i;
      const double len = s[i + 1] - s[i];
      const double f = len > 0 ? (t - s[i]) / len : 0;
      out.push_back(pts[keep[k] + i] * (1 - f) + pts[keep[k] + i + 1] * f);
      corner.push_back(0);
    }
    if (k + 2 < keep.size()) {
      out.push_back(pts[keep[k + 1]]);
      corner.push_back(1);
    }
  }
  // Nodes nearer than kMinNode to the node before are dropped, and the last when it is that near
  // the path's end. Corners that close come of a boundary that doubles back on itself (npl's
  // 3 mm keel bar meets its 1.5 mm waterline step at the stern: a spike of 0.3 mm, whose
  // copies of one point made panels with no area) or of a step far below the panel size; a
  // panel edge that short breaks the side-ratio rule wherever it is. A corner stays, though,
  // when the chord that would replace it passes kMinDepth or more from it (the surface beyond
  // the chord would be left uncovered: a transom's immersed corner a fifth of a panel deep, the
  // property test's seed 1102), and so does the last node when it is a corner farther than
  // kMinCorner from the end (the stem meeting the waterline a seventh of a panel from the last
  // station's upper end, seeds 1091 and 1134). Both left free edges below the waterline. A
  // short edge breaks a share rule; a hole breaks a hard one.
  std::vector<Vec3d> kept;
  bool last_is_corner = false;  // the last node kept is a corner of pts
  Vec3d last = pts.front();
  // How far out[i] lies from the chord that would replace it, from the last node kept to the
  // next point (metric units).
  const auto off_chord = [&](std::size_t i) {
    const Vec3d& q = i + 1 < out.size() ? out[i + 1] : pts.back();
    const Vec3d d = q - last;
    const double dd = squared_norm(d);
    const double t = dd > 0 ? std::clamp(dot(out[i] - last, d) / dd, 0.0, 1.0) : 0.0;
    return metric.length(out[i], last + t * d);
  };
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Vec3d& p = out[i];
    if (metric.length(last, p) < kMinNode && !(corner[i] && off_chord(i) >= kMinDepth)) continue;
    kept.push_back(p);
    last_is_corner = corner[i] != 0;
    last = p;
  }
  if (!kept.empty() && metric.length(kept.back(), pts.back()) < kMinNode &&
      !(last_is_corner && metric.length(kept.back(), pts.back()) >= kMinCorner)) {
    kept.pop_back();
  }
  return kept;
}

std::vector<Vec3d> shortest_border_path(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                                        const Vec3d& a, const Vec3d& b, const Metric& metric,
                                        double tol, double x_lo, double x_hi) {
  const LoopSpot sa = nearest_boundary_edge(surface, adj, a);
  const LoopSpot sb = nearest_boundary_edge(surface, adj, b);
  if (sa.loop != sb.loop || sa.distance > tol || sb.distance > tol) return {};
  const std::vector<Index>& loop = adj.boundary_loops[sa.loop].vertices;
  std::vector<Vec3d> best;
  double best_len = std::numeric_limits<double>::infinity();
  std::vector<Vec3d> pts;
  for (const bool forward : {true, false}) {
    // Walked point by point, and dropped as soon as it leaves the slab or grows as long as the
    // way already found (its length only grows): the long way round a hull's whole outline was
    // walked for every short path asked.
    pts.assign(1, a);
    double len = 0;
    const bool kept = walk_loop(loop, sa.edge, sb.edge, forward, [&](Index v) {
      const Vec3d& p = surface.positions[v];
      if (!(p.x >= x_lo && p.x <= x_hi)) return false;
      len += metric.length(pts.back(), p);
      if (!(len < best_len)) return false;
      pts.push_back(p);
      return true;
    });
    if (!kept) continue;
    len += metric.length(pts.back(), b);
    pts.push_back(b);
    if (len < best_len) {
      best_len = len;
      best = pts;
    }
  }
  return best;
}

std::vector<double> chain_fractions(std::span<const Index> ids, const SurfaceMesh& mesh,
                                    const Metric& metric) {
  std::vector<double> f{0};
  for (std::size_t i = 1; i < ids.size(); ++i)
    f.push_back(f.back() + metric.length(mesh.positions[ids[i - 1]], mesh.positions[ids[i]]));
  const double total = std::max(f.back(), 1e-300);
  for (double& x : f) x /= total;
  return f;
}

}  // namespace hm::structured
