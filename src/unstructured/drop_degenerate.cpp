// Cleanup after welding: faces that collapsed (a repeated corner, or no area) go, and so do the
// vertices no face uses any more. Two faces on the same three vertices go too: back to back (a
// zero-thickness double layer, as where the two halves of a hull meet in a corner triangle that
// lies in the centre plane) both go; wound alike, one stays (a face given twice), unless the two
// are such a layer with one patch still flipped (drop_alike_pairs).
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {

void compact_faces(Work& w, std::span<const std::uint8_t> keep) {
  SurfaceMesh& m = w.mesh;
  std::size_t kept = 0;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    if (!keep[f]) continue;
    m.faces[kept] = m.faces[f];
    m.face_patch[kept] = m.face_patch[f];
    w.face_old[kept] = w.face_old[f];
    ++kept;
  }
  m.faces.resize(kept);
  m.face_patch.resize(kept);
  w.face_old.resize(kept);
}

void append_faces(Work& w, std::span<const Face> faces, std::span<const Index> around) {
  SurfaceMesh& m = w.mesh;
  std::vector<Vec3d> around_normal(around.size());
  for (std::size_t i = 0; i < around.size(); ++i) {
    around_normal[i] = face_normal(m.positions, m.faces[around[i]]);
  }
  for (const Face& f : faces) {
    // The face along the hole that lies most nearly in the new face's plane (the first of
    // equals, in the order given): a face that closes a hole at a chine lies on the patch on
    // its own side of it, and a knuckle found between two faces of one patch is not confirmed.
    const Vec3d n = face_normal(m.positions, f);
    Index like = around.front();
    double best = -2;
    for (std::size_t i = 0; i < around.size(); ++i) {
      const double agree = dot(n, around_normal[i]);
      if (agree > best) {
        best = agree;
        like = around[i];
      }
    }
    m.faces.push_back(f);
    m.face_patch.push_back(m.face_patch[like]);
    w.face_old.push_back(w.face_old[like]);
  }
}

namespace {

// Two faces on the same corners wound alike: a face given twice (one stays), or a double layer
// whose patches do not agree yet, one of them flipped (both go). The second is a fin: its edges
// have no other face except one, which has two (one from each side). It is the corner triangle
// that two halves of a full hull both put in the centre plane, where keel and stem meet (a full
// Wigley with every third patch flipped left an edge with three faces there). A face given twice
// has one other face on an edge (or on the hull's outline, a corner, none on two), and removing
// both copies would open a hole or a notch.
void drop_alike_pairs(const SurfaceMesh& m, std::span<const std::pair<Index, Index>> alike,
                      std::vector<std::uint8_t>& keep) {
  if (alike.empty()) return;
  const auto key = [](Index u, Index v) {
    return std::uint64_t{std::min(u, v)} << 32 | std::max(u, v);
  };
  std::vector<std::uint64_t> edges;  // every kept face's edges, repeated once per use
  edges.reserve(3 * m.face_count());
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    if (!keep[f]) continue;
    const Face& t = m.faces[f];
    for (int c = 0; c < 3; ++c) edges.push_back(key(t[c], t[(c + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  const auto uses = [&](Index u, Index v) {
    const auto [lo, hi] = std::equal_range(edges.begin(), edges.end(), key(u, v));
    return hi - lo;
  };
  for (const auto& [a, b] : alike) {
    const Face& t = m.faces[a];
    // Without both, each edge of theirs must be left with no face or two (a fin: the two halves'
    // faces meet along its third edge); without one, a face given twice leaves one or two.
    bool fin = true, joined = false;
    for (int c = 0; c < 3; ++c) {
      const auto others = uses(t[c], t[(c + 1) % 3]) - 2;
      fin = fin && (others == 0 || others == 2);
      joined = joined || others == 2;
    }
    keep[b] = 0;
    if (fin && joined) keep[a] = 0;
  }
}

}  // namespace

std::size_t drop_degenerate(Work& w, double length) {
  SurfaceMesh& m = w.mesh;
  // Area floor: a triangle this small has lost a dimension to welding, not to the geometry.
  const double floor = 1e-14 * length * length;
  std::vector<std::uint8_t> keep(m.face_count());
  // Each face's corners rotated to start at the lowest index: equal triples are the same face,
  // wound alike; equal sorted triples with different rotations are back to back.
  std::vector<std::array<Index, 3>> corners(m.face_count());
  parallel_for(0, m.face_count(), [&](std::size_t f) {
    const Face& t = m.faces[f];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[2] == t[0];
    keep[f] = !repeated && face_area(m.positions, t) > floor;
    corners[f] = {t[0], t[1], t[2]};
    std::sort(corners[f].begin(), corners[f].end());
  });
  std::vector<std::pair<std::array<Index, 3>, Index>> by_corners;
  by_corners.reserve(m.face_count());
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    if (keep[f]) by_corners.push_back({corners[f], static_cast<Index>(f)});
  }
  // Every pair is distinct (the face index), so the parallel sort's order is the serial one.
  parallel_sort(by_corners.begin(), by_corners.end(), std::less<>{});
  const auto rotated = [&](Index f) {
    const Face& t = m.faces[f];
    const int k = t[0] < t[1] ? (t[0] < t[2] ? 0 : 2) : (t[1] < t[2] ? 1 : 2);
    return std::array<Index, 3>{t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
  };
  std::vector<std::pair<Index, Index>> alike;
  for (std::size_t i = 0; i + 1 < by_corners.size(); ++i) {
    if (by_corners[i].first != by_corners[i + 1].first) continue;
    if (i + 2 < by_corners.size() && by_corners[i + 2].first == by_corners[i].first) continue;
    const Index a = by_corners[i].second, b = by_corners[i + 1].second;
    if (rotated(a) == rotated(b)) {
      alike.emplace_back(a, b);
    } else {
      keep[a] = keep[b] = 0;
    }
    ++i;
  }
  drop_alike_pairs(m, alike, keep);
  const std::size_t before = m.face_count();
  compact_faces(w, keep);
  const std::size_t dropped = before - m.face_count();

  std::vector<Index> old2new(m.vertex_count(), kInvalid);
  for (const Face& t : m.faces) {
    for (int c = 0; c < 3; ++c) old2new[t[c]] = 0;
  }
  Index next = 0;
  for (std::size_t v = 0; v < old2new.size(); ++v) {
    if (old2new[v] == kInvalid) continue;
    old2new[v] = next;
    m.positions[next] = m.positions[v];
    m.vertex_patch[next] = m.vertex_patch[v];
    m.vertex_uv[next] = m.vertex_uv[v];
    w.vert_old[next] = w.vert_old[v];
    ++next;
  }
  m.positions.resize(next);
  m.vertex_patch.resize(next);
  m.vertex_uv.resize(next);
  w.vert_old.resize(next);
  for (Face& t : m.faces) {
    for (int c = 0; c < 3; ++c) t[c] = old2new[t[c]];
  }
  return dropped;
}

}  // namespace hm::merge
