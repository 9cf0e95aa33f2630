// Strips between rows of different curve counts. Each row's curves are grouped: two neighbouring
// curves are joined when the surface's boundary between them stays inside the strip (the slab
// between the two stations, a little wider), as where a skeg's trailing edge or a bulb's neck
// lies between them. The groups of the two rows are then matched in order: matched groups are
// zipped, and a group left over is a piece of hull that ends inside the strip (a propeller boss,
// a bulb's nose, a dome) and is capped against the boundary around its end. Where no such
// reading exists, each row's curves are joined the shorter way round and the chains zipped.
// Boundary nodes made for a join are shared by the strips on both sides that use them.
#include "structured/join_rows.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <optional>

#include "mesh/adjacency.h"
#include "structured/border_path.h"

namespace hm::structured {
namespace {

// Beyond the strip's other station a link may reach only this far (panel lengths along x): a
// boundary that crosses that station's plane lies partly in the next strip, where that row's
// curves end on it (ship_449_patches at 5 m and --trim 2: the waterline round the tip of the
// stern's shelf, 0.15 panel forward of the strip, joined the shelf's two sides there, and the
// piece of hull inboard of the shelf was capped 1.5 m long across the strips aft: 158 pairs of
// panels through each other).
constexpr double kFarMargin = 0.05;
// A cap may reach farther beyond the strip's far station: that station drops a fragment of a
// curve that ends just beyond it (a stem's last sliver above a bulb). The narrowest reach that
// gives a reading wins.
constexpr double kCapMargins[] = {0.25, 1.0, 3.0};

// Curves (or groups) can stand for the same piece of hull across a strip only if their heights
// overlap, to within this many panels.
constexpr double kOverlapPanels = 1.0;

// A cap costs more than any pair (in panels), so the alignment pairs the most groups it can.
constexpr double kCapCost = 1e6;

constexpr double kInf = std::numeric_limits<double>::infinity();

// A boundary path between two curves of a row; its nodes are made when a strip first uses it.
struct Link {
  double x_lo = kInf, x_hi = -kInf;  // of its points, m
  std::vector<Vec3d> points;         // ends included
  std::vector<Index> nodes;          // the resampled interior points, once made
  bool made = false;
};

// Consecutive curves c0..c1 of one row, joined by links.
struct Group {
  std::size_t row = 0, c0 = 0, c1 = 0;
  std::vector<Link*> links;          // links[i] joins curves c0 + i and c0 + i + 1
  double z_lo = kInf, z_hi = -kInf;  // of its curves, m
  Vec3d centre;                      // mean of its curves' nodes, m
};

class Joiner {
 public:
  Joiner(const SurfaceMesh& surface, const EdgeAdjacency& adj, std::span<const Row> rows,
         std::span<const RowNodes> nodes, std::span<const std::vector<Index>> first_vertex,
         const Metric& metric, const ZipOptions& zip, SurfaceMesh& mesh,
         std::vector<NodeSlot>& slots)
      : surface_(surface),
        adj_(adj),
        rows_(rows),
        nodes_(nodes),
        first_vertex_(first_vertex),
        metric_(metric),
        zip_(zip),
        mesh_(mesh),
        slots_(slots),
        tol_(0.25 * std::min({metric.size.x, metric.size.y, metric.size.z})) {}

  // Strip j by matched groups and caps; false (and nothing added) when there is no such reading.
  bool by_groups(std::size_t j, std::size_t& caps) {
    const double margin = kSlabMargin * metric_.size.x;
    const double lo = rows_[j].x - margin, hi = rows_[j + 1].x + margin;
    for (double panels : kCapMargins) {
      const double reach = panels * metric_.size.x;
      if (by_groups(j, lo, hi, rows_[j].x - reach, rows_[j + 1].x + reach, caps)) return true;
    }
    return false;
  }

  // The end beyond row j (aft of it, or forward): its curves grouped through the boundary
  // beyond, and every group capped there; false (and nothing added) if a group cannot be.
  bool end_caps(std::size_t j, bool aft) {
    const double margin = kSlabMargin * metric_.size.x;
    const double lo = aft ? -kInf : rows_[j].x - margin, hi = aft ? rows_[j].x + margin : kInf;
    const std::vector<Group> g = groups(j, lo, hi, aft ? -1 : 1);
    std::vector<std::vector<Vec3d>> paths;
    for (const Group& group : g) {
      paths.push_back(cap_path(group, lo, hi));
      if (paths.back().empty()) return false;
    }
    for (std::size_t k = 0; k < g.size(); ++k) {
      if (aft) {
        zip(cap_chain(g[k], paths[k]), chain(g[k]));
      } else {
        zip(chain(g[k]), cap_chain(g[k], paths[k]));
      }
    }
    return true;
  }

  // Strip j as a last resort: every curve of each row joined the shorter way round.
  bool by_shortest_joins(std::size_t j) {
    const std::optional<Group> a = joined_all(j), b = joined_all(j + 1);
    if (!a || !b) return false;
    zip(chain(*a), chain(*b));
    return true;
  }

 private:
  // Strip j: links within [lo, hi], caps within [cap_lo, cap_hi].
  bool by_groups(std::size_t j, double lo, double hi, double cap_lo, double cap_hi,
                 std::size_t& caps) {
    const double far = kFarMargin * metric_.size.x;
    const std::vector<Group> a = groups(j, lo, std::min(hi, rows_[j + 1].x + far), 1),
                             b = groups(j + 1, std::max(lo, rows_[j].x - far), hi, -1);
    std::vector<std::vector<Vec3d>> cap_a, cap_b;
    for (const Group& g : a) cap_a.push_back(cap_path(g, cap_lo, cap_hi));
    for (const Group& g : b) cap_b.push_back(cap_path(g, cap_lo, cap_hi));
    // Order-preserving alignment: a pair costs the distance between the groups' centres across
    // the strip; a cap, possible where the group ends inside the strip, costs kCapCost.
    enum Move : int { kNone, kPair, kCapA, kCapB };
    const std::size_t m = a.size(), n = b.size();
    std::vector<std::vector<double>> cost(m + 1, std::vector<double>(n + 1, kInf));
    std::vector<std::vector<Move>> move(m + 1, std::vector<Move>(n + 1, kNone));
    cost[0][0] = 0;
    auto relax = [&](std::size_t i, std::size_t k, double c, Move mv) {
      if (c < cost[i][k]) {
        cost[i][k] = c;
        move[i][k] = mv;
      }
    };
    for (std::size_t i = 0; i <= m; ++i) {
      for (std::size_t k = 0; k <= n; ++k) {
        if (i > 0 && k > 0 && overlap(a[i - 1], b[k - 1]))
          relax(i, k, cost[i - 1][k - 1] + across(a[i - 1], b[k - 1]), kPair);
        if (i > 0 && !cap_a[i - 1].empty()) relax(i, k, cost[i - 1][k] + kCapCost, kCapA);
        if (k > 0 && !cap_b[k - 1].empty()) relax(i, k, cost[i][k - 1] + kCapCost, kCapB);
      }
    }
    if (!(cost[m][n] < kInf)) return false;
    std::vector<std::array<std::size_t, 3>> steps;  // (move, i, k), last first
    for (std::size_t i = m, k = n; i > 0 || k > 0;) {
      const Move mv = move[i][k];
      steps.push_back({static_cast<std::size_t>(mv), i, k});
      if (mv != kCapB) --i;
      if (mv != kCapA) --k;
    }
    std::reverse(steps.begin(), steps.end());
    for (const auto& [mv, i, k] : steps) {
      if (mv == kPair) zip(chain(a[i - 1]), chain(b[k - 1]));
      if (mv == kCapA) zip(chain(a[i - 1]), cap_chain(a[i - 1], cap_a[i - 1]));
      if (mv == kCapB) zip(cap_chain(b[k - 1], cap_b[k - 1]), chain(b[k - 1]));
      if (mv != kPair) ++caps;
    }
    return true;
  }

  // The row's curves in groups: curve c joins c + 1 where the boundary between them stays in
  // [lo, hi] and reaches farther to the strip's side of the row (side +1: forward, -1: aft) than
  // away from it. A boundary that lies beyond the row joins its curves in the neighbouring strip
  // only: a bulb's neck just aft of a station joins bulb and stem in the strip aft of it, while
  // in the strip forward of it the stem is a piece of its own.
  std::vector<Group> groups(std::size_t j, double lo, double hi, int side) {
    std::vector<Group> out{Group{j, 0, 0, {}, kInf, -kInf, {}}};
    const double x = rows_[j].x;
    for (std::size_t c = 0; c + 1 < rows_[j].curves.size(); ++c) {
      Link* l = link(j, c, lo, hi);
      if (l && (side > 0 ? l->x_hi - x >= x - l->x_lo : x - l->x_lo >= l->x_hi - x)) {
        out.back().links.push_back(l);
        out.back().c1 = c + 1;
      } else {
        out.push_back(Group{j, c + 1, c + 1, {}, kInf, -kInf, {}});
      }
    }
    for (Group& g : out) finish(g);
    return out;
  }

  std::optional<Group> joined_all(std::size_t j) {
    const std::size_t n = rows_[j].curves.size();
    Group g{j, 0, n - 1, {}, kInf, -kInf, {}};
    for (std::size_t c = 0; c + 1 < n; ++c) {
      Link* l = link(j, c, -kInf, kInf);
      if (!l) return std::nullopt;
      g.links.push_back(l);
    }
    finish(g);
    return g;
  }

  Index first_node(std::size_t j, std::size_t c) const { return first_vertex_[j][c]; }
  Index last_node(std::size_t j, std::size_t c) const {
    return first_vertex_[j][c] + static_cast<Index>(nodes_[j].s[c].size() - 1);
  }

  void finish(Group& g) const {
    Vec3d sum;
    std::size_t count = 0;
    for (std::size_t c = g.c0; c <= g.c1; ++c) {
      g.z_lo = std::min(g.z_lo, rows_[g.row].curves[c].z_min);
      g.z_hi = std::max(g.z_hi, rows_[g.row].curves[c].z_max);
      for (Index v = first_node(g.row, c); v <= last_node(g.row, c); ++v, ++count)
        sum += mesh_.positions[v];
    }
    g.centre = sum / static_cast<double>(std::max<std::size_t>(count, 1));
  }

  // The boundary from curve c's upper end to curve c + 1's lower end, within [lo, hi]: found
  // once per way round and shared by every strip that uses it; null if none.
  Link* link(std::size_t j, std::size_t c, double lo, double hi) {
    std::deque<Link>& known = links_[{j, c}];
    for (Link& l : known) {
      if (l.x_lo >= lo && l.x_hi <= hi) return &l;
    }
    const Vec3d from = mesh_.positions[last_node(j, c)];
    const Vec3d to = mesh_.positions[first_node(j, c + 1)];
    Link l;
    l.points = shortest_border_path(surface_, adj_, from, to, metric_, tol_, lo, hi);
    if (l.points.empty()) return nullptr;
    for (const Vec3d& p : l.points) {
      l.x_lo = std::min(l.x_lo, p.x);
      l.x_hi = std::max(l.x_hi, p.x);
    }
    known.push_back(std::move(l));
    return &known.back();
  }

  // The group's nodes, lowest first, with its links' nodes (made on first use).
  std::vector<Index> chain(const Group& g) {
    std::vector<Index> ids;
    for (std::size_t c = g.c0; c <= g.c1; ++c) {
      for (Index v = first_node(g.row, c); v <= last_node(g.row, c); ++v) ids.push_back(v);
      if (c == g.c1) break;
      Link& l = *g.links[c - g.c0];
      if (!l.made) {
        for (const Vec3d& p : resample(l.points, metric_))
          l.nodes.push_back(new_node(p, first_node(g.row, c)));
        l.made = true;
      }
      ids.insert(ids.end(), l.nodes.begin(), l.nodes.end());
    }
    return ids;
  }

  // The boundary around a group's end inside [lo, hi], from its lower end to its upper end
  // (points, ends included); empty when the group does not end inside the strip.
  std::vector<Vec3d> cap_path(const Group& g, double lo, double hi) const {
    const Vec3d a = mesh_.positions[first_node(g.row, g.c0)];
    const Vec3d b = mesh_.positions[last_node(g.row, g.c1)];
    return shortest_border_path(surface_, adj_, a, b, metric_, tol_, lo, hi);
  }

  // The cap's chain: the group's two end nodes with new boundary nodes between them.
  std::vector<Index> cap_chain(const Group& g, const std::vector<Vec3d>& path) {
    const Index first = first_node(g.row, g.c0);
    std::vector<Index> ids{first};
    for (const Vec3d& p : resample(path, metric_)) ids.push_back(new_node(p, first));
    ids.push_back(last_node(g.row, g.c1));
    return ids;
  }

  Index new_node(const Vec3d& p, Index near) {
    mesh_.positions.push_back(p);
    mesh_.vertex_patch.push_back(mesh_.vertex_patch[near]);
    mesh_.vertex_uv.push_back(mesh_.vertex_uv[near]);
    slots_.push_back(NodeSlot{});
    return static_cast<Index>(mesh_.positions.size() - 1);
  }

  bool overlap(const Group& a, const Group& b) const {
    const double pad = kOverlapPanels * metric_.size.z;
    return a.z_lo <= b.z_hi + pad && b.z_lo <= a.z_hi + pad;
  }

  // Distance between the groups' centres seen along x (panels).
  double across(const Group& a, const Group& b) const {
    return metric_.length(a.centre, Vec3d{a.centre.x, b.centre.y, b.centre.z});
  }

  // a runs along the aft side of the strip, b along the forward one, both lowest end first.
  void zip(const std::vector<Index>& a, const std::vector<Index>& b) {
    zip_chains(a, chain_fractions(a, mesh_, metric_), b, chain_fractions(b, mesh_, metric_),
               mesh_.positions, zip_, mesh_.faces);
  }

  const SurfaceMesh& surface_;
  const EdgeAdjacency& adj_;
  std::span<const Row> rows_;
  std::span<const RowNodes> nodes_;
  std::span<const std::vector<Index>> first_vertex_;
  const Metric& metric_;
  ZipOptions zip_;
  SurfaceMesh& mesh_;
  std::vector<NodeSlot>& slots_;
  double tol_;
  std::map<std::pair<std::size_t, std::size_t>, std::deque<Link>> links_;
};

}  // namespace

JoinCounts join_rows(const SurfaceMesh& surface, const EdgeAdjacency& adj,
                     std::span<const Row> rows, std::span<const RowNodes> nodes,
                     std::span<const std::vector<Index>> first_vertex,
                     std::span<const std::size_t> strips, const Metric& metric,
                     const ZipOptions& zip, std::array<bool, 2> open_ends, SurfaceMesh& mesh,
                     std::vector<NodeSlot>& slots) {
  JoinCounts counts;
  Joiner joiner(surface, adj, rows, nodes, first_vertex, metric, zip, mesh, slots);
  for (const bool aft : {true, false}) {
    const std::size_t j = aft ? 0 : rows.size() - 1;
    if (!open_ends[aft ? 0 : 1] || rows.empty() || rows[j].curves.empty()) continue;
    if (joiner.end_caps(j, aft)) ++counts.ends_closed;
  }
  for (std::size_t j : strips) {
    if (rows[j].curves.empty() || rows[j + 1].curves.empty()) continue;
    if (joiner.by_groups(j, counts.caps) || joiner.by_shortest_joins(j)) counts.closed.push_back(j);
  }
  return counts;
}

}  // namespace hm::structured
