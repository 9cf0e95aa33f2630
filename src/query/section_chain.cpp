#include "query/section_chain.h"

#include <algorithm>
#include <tuple>

#include "core/types.h"

namespace hm::query {
namespace {

// End e of piece e / 2: its first point when e is even, its last when odd.
const SectionPoint& end_point(const std::vector<SectionPolyline>& pieces, Index e) {
  const auto& pts = pieces[e / 2].points;
  return e % 2 == 0 ? pts.front() : pts.back();
}

// Pairs of ends within tol, closest first (ties by index), each end used once: link[e] is the
// end that e joins, or kInvalid.
std::vector<Index> link_ends(const std::vector<SectionPolyline>& pieces, double tol) {
  const Index n_ends = static_cast<Index>(2 * pieces.size());
  std::vector<Index> by_x(n_ends);
  for (Index e = 0; e < n_ends; ++e) by_x[e] = e;
  std::sort(by_x.begin(), by_x.end(), [&](Index a, Index b) {
    return std::make_pair(end_point(pieces, a).point.x, a) <
           std::make_pair(end_point(pieces, b).point.x, b);
  });
  std::vector<std::tuple<double, Index, Index>> pairs;
  for (std::size_t i = 0; i < by_x.size(); ++i) {
    const Vec3d& a = end_point(pieces, by_x[i]).point;
    for (std::size_t j = i + 1; j < by_x.size(); ++j) {
      const Vec3d& b = end_point(pieces, by_x[j]).point;
      if (b.x - a.x > tol) break;
      const Index ea = std::min(by_x[i], by_x[j]), eb = std::max(by_x[i], by_x[j]);
      // A piece may close on itself, but not through a single segment.
      if (ea / 2 == eb / 2 && pieces[ea / 2].points.size() < 3) continue;
      const double d = norm(a - b);
      if (d <= tol) pairs.emplace_back(d, ea, eb);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<Index> link(n_ends, kInvalid);
  for (const auto& [d, a, b] : pairs) {
    if (link[a] != kInvalid || link[b] != kInvalid) continue;
    link[a] = b;
    link[b] = a;
  }
  return link;
}

// Follows links from piece `first`, entered at end `entry`, until an unlinked end or back at
// `first`. Appends points (dropping the duplicate at every joint) and marks pieces used.
SectionPolyline follow(std::vector<SectionPolyline>& pieces, const std::vector<Index>& link,
                       Index first, Index entry, std::vector<bool>& used) {
  SectionPolyline out;
  Index piece = first, in = entry;
  // A piece with no link at its far end is the whole chain: move it.
  if (link[in % 2 == 0 ? 2 * piece + 1 : 2 * piece] == kInvalid) {
    used[piece] = true;
    out.points = std::move(pieces[piece].points);
    if (in % 2 != 0) std::reverse(out.points.begin(), out.points.end());
    return out;
  }
  while (true) {
    used[piece] = true;
    const auto& pts = pieces[piece].points;
    const bool forward = in % 2 == 0;
    const std::size_t skip = out.points.empty() ? 0 : 1;
    for (std::size_t k = skip; k < pts.size(); ++k) {
      out.points.push_back(forward ? pts[k] : pts[pts.size() - 1 - k]);
    }
    const Index exit = forward ? 2 * piece + 1 : 2 * piece;
    const Index next_in = link[exit];
    if (next_in == kInvalid) break;
    if (next_in / 2 == first) {
      out.closed = true;
      out.points.pop_back();  // the joint with the first point
      break;
    }
    piece = next_in / 2;
    in = next_in;
  }
  return out;
}

// Lexicographic in (z, y, x), treating differences within tol as ties for z and y.
bool lower_zyx(const Vec3d& a, const Vec3d& b, double tol) {
  if (std::abs(a.z - b.z) > tol) return a.z < b.z;
  if (std::abs(a.y - b.y) > tol) return a.y < b.y;
  return a.x < b.x;
}

void orient(SectionPolyline& line, const Vec3d& n, double tol) {
  auto& pts = line.points;
  if (pts.size() < 2) return;
  if (!line.closed) {
    if (lower_zyx(pts.back().point, pts.front().point, tol)) std::reverse(pts.begin(), pts.end());
    return;
  }
  // Twice the signed area about n; counter-clockwise (right-hand rule about n) is positive.
  double area = 0;
  const Vec3d o = pts[0].point;
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) {
    area += dot(cross(pts[i].point - o, pts[i + 1].point - o), n);
  }
  if (area < 0) std::reverse(pts.begin(), pts.end());
  // Start at the lowest point (exact comparison: only the choice of start depends on it).
  auto start = std::min_element(pts.begin(), pts.end(), [](const auto& a, const auto& b) {
    return std::tie(a.point.z, a.point.y, a.point.x) < std::tie(b.point.z, b.point.y, b.point.x);
  });
  std::rotate(pts.begin(), start, pts.end());
}

}  // namespace

void drop_repeated_points(SectionPolyline& line, double tol) {
  auto& pts = line.points;
  std::size_t kept = 0;  // in place: pts[0, kept) are the points kept so far
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (kept > 0 && norm(pts[i].point - pts[kept - 1].point) <= tol) continue;
    if (kept != i) pts[kept] = pts[i];
    ++kept;
  }
  pts.resize(kept);
  if (line.closed && pts.size() > 1 && norm(pts.back().point - pts.front().point) <= tol) {
    pts.pop_back();
  }
}

Section assemble_section(std::vector<SectionPolyline> pieces, const Vec3d& n, double join_tol) {
  Section section;
  std::vector<SectionPolyline> open;
  for (auto& p : pieces) (p.closed ? section.polylines : open).push_back(std::move(p));

  const std::vector<Index> link = link_ends(open, join_tol);
  std::vector<bool> used(open.size(), false);
  // Chains with a free end first, started from that end; what is left are rings of pieces.
  for (Index i = 0; i < open.size(); ++i) {
    if (used[i]) continue;
    if (link[2 * i] == kInvalid) {
      section.polylines.push_back(follow(open, link, i, 2 * i, used));
    } else if (link[2 * i + 1] == kInvalid) {
      section.polylines.push_back(follow(open, link, i, 2 * i + 1, used));
    }
  }
  for (Index i = 0; i < open.size(); ++i) {
    if (!used[i]) section.polylines.push_back(follow(open, link, i, 2 * i, used));
  }

  for (SectionPolyline& line : section.polylines) orient(line, n, join_tol);
  std::sort(section.polylines.begin(), section.polylines.end(),
            [&](const SectionPolyline& a, const SectionPolyline& b) {
              const Vec3d& pa = a.points.front().point;
              const Vec3d& pb = b.points.front().point;
              if (pa != pb) {
                return std::tie(pa.z, pa.y, pa.x) < std::tie(pb.z, pb.y, pb.x);
              }
              return a.points.size() < b.points.size();
            });
  return section;
}

}  // namespace hm::query
