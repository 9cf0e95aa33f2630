// Growing rows: border rows first (even spacing between breakpoints), then each column grows from
// its aft border row, row by row, as the paper grows panels from a starting row. A node of row r
// finds its successor by cutting the hull with the plane normal to row r at the node (the plane
// through the node whose normal is the row's tangent there) and walking along that section to
// the next station: where it meets row r + 1.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// A marched node closer than this (panels) to a breakpoint gives way to it.
constexpr double kBreakClearance = 0.25;
// Weight of even spacing against the marched position when a grown row is finished.
constexpr double kEvenWeight = 0.5;
// A grown row keeps its node count while its length is within this many panels of it.
constexpr double kKeepCount = 0.8;

int segment_count(double length) { return std::max(1, static_cast<int>(std::lround(length))); }

std::vector<double> even_nodes(const RowCurve& c) {
  std::vector<double> s;
  for (std::size_t b = 0; b + 1 < c.breaks.size(); ++b) {
    const double s0 = c.breaks[b].s, s1 = c.breaks[b + 1].s;
    const int n = segment_count(s1 - s0);
    for (int i = 0; i < n; ++i) s.push_back(s0 + (s1 - s0) * i / n);
  }
  s.push_back(c.breaks.back().s);
  return s;
}

// The tangent of a node chain at node i (central difference, one-sided at the ends).
Vec3d chain_tangent(const RowCurve& c, std::span<const double> s, std::size_t i) {
  const std::size_t a = i == 0 ? 0 : i - 1;
  const std::size_t b = std::min(i + 1, s.size() - 1);
  return c.at(s[b]) - c.at(s[a]);
}

// Brings the marched nodes inside (s0, s1) to the count the segment needs: merges the closest
// pair's node away, or splits the widest gap, one at a time (each change makes one triangle in
// the strip), then blends towards even spacing.
std::vector<double> fit_segment(std::vector<double> inner, double s0, double s1) {
  // Hysteresis: the grown count stays while it is within kKeepCount of the length, so a row
  // whose length hovers near k + 1/2 does not flip between k and k + 1 panels (each flip is a
  // triangle).
  int n = segment_count(s1 - s0);
  const double grown = static_cast<double>(inner.size() + 1);
  if (!inner.empty() && std::abs((s1 - s0) - grown) < kKeepCount) n = static_cast<int>(grown);
  const std::size_t want = static_cast<std::size_t>(n - 1);
  auto gap = [&](std::size_t i, bool left) {
    const double lo = i == 0 ? s0 : inner[i - 1];
    const double hi = i + 1 == inner.size() ? s1 : inner[i + 1];
    return left ? inner[i] - lo : hi - inner[i];
  };
  while (inner.size() > want) {
    std::size_t worst = 0;
    double worst_gap = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < inner.size(); ++i) {
      const double g = std::min(gap(i, true), gap(i, false));
      if (g < worst_gap) {
        worst_gap = g;
        worst = i;
      }
    }
    inner.erase(inner.begin() + static_cast<std::ptrdiff_t>(worst));
  }
  while (inner.size() < want) {
    // Gaps between s0, inner..., s1; split the widest.
    std::size_t widest = 0;
    double widest_gap = -1;
    for (std::size_t i = 0; i <= inner.size(); ++i) {
      const double lo = i == 0 ? s0 : inner[i - 1];
      const double hi = i == inner.size() ? s1 : inner[i];
      if (hi - lo > widest_gap) {
        widest_gap = hi - lo;
        widest = i;
      }
    }
    const double lo = widest == 0 ? s0 : inner[widest - 1];
    inner.insert(inner.begin() + static_cast<std::ptrdiff_t>(widest), lo + 0.5 * widest_gap);
  }
  for (std::size_t i = 0; i < inner.size(); ++i) {
    const double even = s0 + (s1 - s0) * static_cast<double>(i + 1) / n;
    inner[i] = (1 - kEvenWeight) * inner[i] + kEvenWeight * even;
  }
  return inner;
}

// Row `next` grown from row `prev` and its nodes.
RowNodes grow_one(const Row& prev, const RowNodes& prev_nodes, const Row& next) {
  RowNodes out;
  out.s.resize(next.curves.size());
  const bool paired = prev.curves.size() == next.curves.size();
  for (std::size_t c = 0; c < next.curves.size(); ++c) {
    const RowCurve& to = next.curves[c];
    if (!paired) {
      out.s[c] = even_nodes(to);
      continue;
    }
    const RowCurve& from = prev.curves[c];
    const std::vector<double>& ps = prev_nodes.s[c];
    const double scale = to.length() / std::max(from.length(), 1e-300);
    std::vector<double> marched;
    marched.reserve(ps.size());
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const Vec3d p = from.at(ps[i]);
      const Vec3d t = chain_tangent(from, ps, i);
      double s = squared_norm(t) > 0 ? to.crossing(p, t, ps[i] * scale)
                                     : std::numeric_limits<double>::quiet_NaN();
      if (!std::isfinite(s)) s = ps[i] * scale;  // no crossing: keep the girth fraction
      marched.push_back(s);
    }
    // Walks that crossed each other are dropped (the row keeps its order).
    std::vector<double> kept;
    for (double s : marched)
      if (kept.empty() || s > kept.back()) kept.push_back(s);
    std::vector<double>& nodes = out.s[c];
    for (std::size_t b = 0; b + 1 < to.breaks.size(); ++b) {
      const double s0 = to.breaks[b].s, s1 = to.breaks[b + 1].s;
      std::vector<double> inner;
      // The same segment on the row before (both bounding labels there): its inner nodes walk
      // over as they are, held inside the segment, so the count only changes where it must.
      double f0 = -1, f1 = -1;
      for (const Breakpoint& x : from.breaks) {
        if (x.label == to.breaks[b].label) f0 = x.s;
        if (x.label == to.breaks[b + 1].label) f1 = x.s;
      }
      if (f0 >= 0 && f1 > f0) {
        const double margin = 0.1 * std::min(1.0, s1 - s0);
        for (std::size_t i = 0; i < ps.size(); ++i) {
          if (ps[i] <= f0 + 1e-12 || ps[i] >= f1 - 1e-12) continue;
          inner.push_back(std::clamp(marched[i], s0 + margin, s1 - margin));
        }
        std::sort(inner.begin(), inner.end());
        // Nodes squeezed onto one spot are spread evenly over their run.
        for (std::size_t i = 1; i < inner.size(); ++i) {
          if (inner[i] <= inner[i - 1]) inner[i] = inner[i - 1] + 1e-9;
        }
        if (!inner.empty() && inner.back() >= s1) {
          for (std::size_t i = 0; i < inner.size(); ++i) {
            inner[i] = s0 + (s1 - s0) * static_cast<double>(i + 1) / (inner.size() + 1);
          }
        }
      } else {
        for (double s : kept) {
          if (s > s0 + kBreakClearance && s < s1 - kBreakClearance) inner.push_back(s);
        }
      }
      nodes.push_back(s0);
      for (double s : fit_segment(std::move(inner), s0, s1)) nodes.push_back(s);
    }
    nodes.push_back(to.breaks.back().s);
  }
  return out;
}

}  // namespace

std::vector<RowNodes> grow_rows(std::span<const Row> rows, std::vector<double>* row_seconds) {
  std::vector<RowNodes> nodes(rows.size());
  std::vector<std::size_t> borders;
  for (std::size_t j = 0; j < rows.size(); ++j) {
    if (rows[j].border) borders.push_back(j);
  }
  std::vector<double> seconds(rows.size(), 0);
  auto timed = [&](std::size_t j, auto&& place) {
    const auto t0 = std::chrono::steady_clock::now();
    place();
    seconds[j] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  // Border rows first: they are shared by the columns on both sides.
  parallel_for_each_item(borders.size(), [&](std::size_t b) {
    timed(borders[b], [&] {
      for (const RowCurve& c : rows[borders[b]].curves)
        nodes[borders[b]].s.push_back(even_nodes(c));
    });
  });
  // Then each column, from its aft border row.
  parallel_for_each_item(borders.empty() ? 0 : borders.size() - 1, [&](std::size_t b) {
    for (std::size_t j = borders[b] + 1; j < borders[b + 1]; ++j) {
      timed(j, [&] { nodes[j] = grow_one(rows[j - 1], nodes[j - 1], rows[j]); });
    }
  });
  if (row_seconds) *row_seconds = std::move(seconds);
  return nodes;
}

}  // namespace hm::structured
