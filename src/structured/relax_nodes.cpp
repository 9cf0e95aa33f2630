// Point relocation (the paper's planned last step): Laplacian smoothing constrained to the rows.
// A free node moves along its own row curve, so it stays on its station plane and on the hull,
// towards the point of the curve nearest the mean of its mesh neighbours, and never past the
// nodes beside it on the row. Jacobi sweeps: every node reads the last sweep's positions and
// writes its own slot, so the result does not depend on the thread count.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// Share of the gap to a row neighbour that a node keeps clear of.
constexpr double kKeepClear = 0.15;

// The arc length of the point of c nearest q, searched over [lo, hi]: the segments that meet
// [lo, hi] are a run of the ascending arc lengths, found by bisection.
double nearest_on_curve(const RowCurve& c, const Vec3d& q, double lo, double hi) {
  double best_s = lo, best_d = std::numeric_limits<double>::infinity();
  if (c.points.size() < 2) return best_s;
  const std::size_t first =
      static_cast<std::size_t>(std::lower_bound(c.s.begin() + 1, c.s.end(), lo) - c.s.begin()) - 1;
  for (std::size_t k = first; k + 1 < c.points.size() && c.s[k] <= hi; ++k) {
    const Vec3d d = c.points[k + 1] - c.points[k];
    const double dd = squared_norm(d);
    double f = dd > 0 ? std::clamp(dot(q - c.points[k], d) / dd, 0.0, 1.0) : 0.0;
    double s = c.s[k] + f * (c.s[k + 1] - c.s[k]);
    s = std::clamp(s, lo, hi);
    const double dist = squared_norm(c.at(s) - q);
    if (dist < best_d) {
      best_d = dist;
      best_s = s;
    }
  }
  return best_s;
}

}  // namespace

void relax_nodes(std::span<const Row> rows, std::span<NodeSlot> slots, std::span<const Face> faces,
                 std::vector<Vec3d>& positions, int passes) {
  const std::size_t nv = positions.size();
  // Vertex neighbours along face sides (CSR, sorted, unique).
  std::vector<std::uint32_t> count(nv + 1, 0);
  for (const Face& f : faces) {
    const int m = corner_count(f);
    for (int c = 0; c < m; ++c) {
      ++count[f[c] + 1];
      ++count[f[(c + 1) % m] + 1];
    }
  }
  for (std::size_t v = 0; v < nv; ++v) count[v + 1] += count[v];
  std::vector<Index> nbr(count[nv]);
  {
    std::vector<std::uint32_t> fill(count.begin(), count.end() - 1);
    for (const Face& f : faces) {
      const int m = corner_count(f);
      for (int c = 0; c < m; ++c) {
        const Index a = f[c], b = f[(c + 1) % m];
        nbr[fill[a]++] = b;
        nbr[fill[b]++] = a;
      }
    }
  }
  // Each list sorted and made unique once, for all the passes (each side is listed by both of
  // its faces): the unique entries are moved to the front of their range, and ends[v] marks
  // where they stop.
  std::vector<std::uint32_t> ends(nv);
  parallel_for(0, nv, [&](std::size_t v) {
    const auto first = nbr.begin() + count[v], last = nbr.begin() + count[v + 1];
    std::sort(first, last);
    ends[v] = static_cast<std::uint32_t>(std::unique(first, last) - nbr.begin());
  });
  // The row neighbours of each free node: its predecessor and successor on the same curve.
  std::vector<Index> prev(nv, kInvalid), next(nv, kInvalid);
  for (std::size_t v = 0; v + 1 < nv; ++v) {
    const NodeSlot& a = slots[v];
    const NodeSlot& b = slots[v + 1];
    if (a.row != kInvalid && a.row == b.row && a.curve == b.curve && b.s > a.s) {
      next[v] = static_cast<Index>(v + 1);
      prev[v + 1] = static_cast<Index>(v);
    }
  }
  std::vector<double> new_s(nv);
  for (int pass = 0; pass < passes; ++pass) {
    parallel_for(0, nv, [&](std::size_t v) {
      const NodeSlot& n = slots[v];
      new_s[v] = n.s;
      if (n.fixed || prev[v] == kInvalid || next[v] == kInvalid) return;
      const std::span<const Index> around(nbr.data() + count[v], nbr.data() + ends[v]);
      if (around.empty()) return;
      Vec3d mean{0, 0, 0};
      for (Index u : around) mean += positions[u];
      mean = mean * (1.0 / static_cast<double>(around.size()));
      const double lo = slots[prev[v]].s, hi = slots[next[v]].s;
      const double margin = kKeepClear * (hi - lo) * 0.5;
      const RowCurve& c = rows[n.row].curves[n.curve];
      new_s[v] = nearest_on_curve(c, mean, lo + margin, hi - margin);
    });
    for (std::size_t v = 0; v < nv; ++v) {
      if (new_s[v] == slots[v].s) continue;
      slots[v].s = new_s[v];
      positions[v] = rows[slots[v].row].curves[slots[v].curve].at(new_s[v]);
    }
  }
}

double side_ratio(std::span<const Vec3d> p, const Face& f) {
  const int n = corner_count(f);
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (int c = 0; c < n; ++c) {
    const double l = norm(p[f[(c + 1) % n]] - p[f[c]]);
    lo = std::min(lo, l);
    hi = std::max(hi, l);
  }
  return lo > 0 ? hi / lo : std::numeric_limits<double>::infinity();
}

bool flat_face(std::span<const Vec3d> p, const Face& f) {
  const int n = corner_count(f);
  double longest = 0;
  for (int c = 0; c < n; ++c)
    longest = std::max(longest, squared_norm(p[f[(c + 1) % n]] - p[f[c]]));
  return !(face_area(p, f) > kFlatArea * longest);
}

}  // namespace hm::structured
