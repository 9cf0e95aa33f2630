// Small holes: where three or four patches meet at a corner, zipping their borders pairwise can
// leave a hole of one or two triangles' size. Closed boundary loops of 3 or 4 vertices that run
// along two or more patches are such holes (a true boundary of a hull is never that short); they
// are closed with one triangle or two (split along the diagonal whose faces lie in the planes of
// the faces beside them, else the shorter, that is not an edge already; where only one is free
// and it would fold, by collapsing the taken one). Longer loops (up to 16 vertices) are closed
// only when their perimeter is shorter than the longest edge of the faces along them (pinholes),
// or when they are slits: no wider, on average, than the gap tolerance at their edges, two
// borders that the snap left apart where it closes gaps as wide (a fold test or a third patch's
// tip in the way). A slit is closed by ear clipping, of the ears whose faces lie in the planes
// beside them the shortest diagonal first, that is not an edge of the mesh already.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numbers>
#include <set>
#include <vector>

#include "mesh/adjacency.h"
#include "unstructured/merge_steps.h"

namespace hm::merge {

namespace {

constexpr std::size_t kMaxHoleVertices = 16;
// A hole on one line may have more (close_flat_holes): its splits add no face of its own.
constexpr std::size_t kMaxFlatHoleVertices = 128;

// The angle between two face normals (radians; not normalised), accurate near 0.
double angle_between(const Vec3d& a, const Vec3d& b) {
  return std::atan2(norm(cross(a, b)), dot(a, b));
}

// A new face closing a hole should lie in the planes of the faces beside it. Where a knuckle
// runs through a hole (a keel through a junction of patches with gaps both ways, a stem post
// into a keel: a small cross of slits, corners on the line and off it to either side), the
// shortest diagonal runs across the line and bends the new faces over it. The generated full
// round-bilge hull of 100 patches with 0.1 m gaps broke its keel so (5 lines where the clean
// hull has 3), and the full Wigley of 24 patches with every defect, at 40,000 triangles, tied
// each end of its keel into a knot of three short lines (8 lines where it has 1). Faces that
// fit the planes beside them by less than kCreaseMargin better than the best are ranked by
// length instead: across a knuckle of 8 degrees the fits differ by about 3 degrees, on a smooth
// fine surface by far less than one.
constexpr double kCreaseMargin = 1.0 * std::numbers::pi / 180;

// How far new face f strays from the faces beside the two loop sides it closes: the larger
// angle between its normal and theirs (radians).
double misfit(const SurfaceMesh& m, const Face& f, const Vec3d& beside_a, const Vec3d& beside_b) {
  const Vec3d n = face_normal(m.positions, f);
  return std::max(angle_between(n, beside_a), angle_between(n, beside_b));
}

// A way to close (part of) a hole: its misfit and the length of its new diagonal.
struct Closing {
  double misfit, length;
};

// Of the closings that fit within kCreaseMargin of the best fit, the shortest (the first of
// equals); size() when there is none.
std::size_t fitting_shortest(const std::vector<Closing>& c) {
  double best_fit = std::numeric_limits<double>::infinity();
  for (const Closing& e : c) best_fit = std::min(best_fit, e.misfit);
  std::size_t best = c.size();
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c[i].misfit > best_fit + kCreaseMargin) continue;
    if (best == c.size() || c[i].length < c[best].length) best = i;
  }
  return best;
}

// Faces closing loop r (its vertices in its faces' winding) by ear clipping in the plane square to
// `up` (the faces' side the new faces must face too): of the ears that are convex there, hold no
// other loop vertex and whose diagonal is not an edge of the mesh already (is_edge), the one with
// the shortest diagonal of those that fit the faces beside them (`beside[i]`, the normal of the
// face across side r[i] - r[i + 1]) within kCreaseMargin of the best fit. Empty when no such ear
// is left. The new faces run against the loop.
template <class IsEdge>
std::vector<Face> clip_ears(const SurfaceMesh& m, std::vector<Index> r, std::vector<Vec3d> beside,
                            const Vec3d& up, IsEdge&& is_edge) {
  // A frame of the plane: e1, e2 with e1 x e2 along up.
  const Vec3d n = normalized(up);
  const Vec3d any = std::abs(n.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  const Vec3d e1 = normalized(cross(any, n)), e2 = cross(n, e1);
  const auto at = [&](Index v) { return Vec2d{dot(m.positions[v], e1), dot(m.positions[v], e2)}; };
  const auto turn = [](const Vec2d& a, const Vec2d& b, const Vec2d& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  };
  std::vector<std::size_t> ear_at;
  std::vector<Closing> ears;
  std::vector<Face> out;
  while (r.size() >= 3) {
    const std::size_t k = r.size();
    ear_at.clear();
    ears.clear();
    for (std::size_t i = 0; i < k; ++i) {
      const Index a = r[(i + k - 1) % k], b = r[i], c = r[(i + 1) % k];
      // The new face (a, c, b) must face `up`: in the loop's own winding (a, b, c) turns the
      // other way.
      const Vec2d pa = at(a), pb = at(b), pc = at(c);
      if (!(turn(pa, pb, pc) < 0)) continue;
      if (k > 3 && is_edge(a, c)) continue;
      bool holds = false;
      for (std::size_t j = 0; j < k && !holds; ++j) {
        const Index v = r[j];
        if (v == a || v == b || v == c) continue;
        const Vec2d p = at(v);
        holds = turn(pa, pb, p) <= 0 && turn(pb, pc, p) <= 0 && turn(pc, pa, p) <= 0;
      }
      if (holds) continue;
      ear_at.push_back(i);
      ears.push_back({misfit(m, {a, c, b, kInvalid}, beside[(i + k - 1) % k], beside[i]),
                      norm(m.positions[c] - m.positions[a])});
    }
    if (ears.empty()) return {};
    const std::size_t best = ear_at[fitting_shortest(ears)];
    const Index a = r[(best + k - 1) % k], b = r[best], c = r[(best + 1) % k];
    out.push_back({a, c, b, kInvalid});
    if (k == 3) break;
    // The new side a - c has the new face beside it.
    beside[(best + k - 1) % k] = face_normal(m.positions, out.back());
    r.erase(r.begin() + std::ptrdiff_t(best));
    beside.erase(beside.begin() + std::ptrdiff_t(best));
  }
  return out;
}

// Faces closing loop r by a fan from one of its vertices, the first none of whose diagonals is
// an edge of the mesh already (is_edge); empty when there is none. The new faces run against
// the loop.
template <class IsEdge>
std::vector<Face> fan_of_new_diagonals(const std::vector<Index>& r, IsEdge&& is_edge) {
  const std::size_t k = r.size();
  for (std::size_t s = 0; s < k; ++s) {
    bool free = true;
    for (std::size_t i = 2; i + 1 < k && free; ++i) free = !is_edge(r[s], r[(s + i) % k]);
    if (!free) continue;
    std::vector<Face> out;
    for (std::size_t i = 1; i + 1 < k; ++i) {
      out.push_back({r[s], r[(s + i + 1) % k], r[(s + i) % k], kInvalid});
    }
    return out;
  }
  return {};
}

// Heights of a hole's vertices over the line through its two farthest apart, as a share of
// their distance, at or below which it is flat: a triangle or fan there has no area.
constexpr double kFlatHole = 1e-3;
// Where along that line a three-vertex hole's middle vertex must lie (as a fraction from either
// end) for the split.
constexpr double kFlatHoleEnd = 0.02;
// A three-vertex hole whose triangle would stand 60 degrees or more off the faces beside it is a
// T-junction the snap left a little off the line: flat up to this share. The generated half
// round-bilge hull of 300 patches, clean, has one at each of three patch corners of its bow
// (x = 86-90 m), the middle vertex 1.4e-3 of the long side off it; their triangles stood across
// the hull, 90-100 degrees off their neighbours, and three false knuckle lines of 0.4-0.7 m ran
// along them.
constexpr double kNearlyFlatHole = 1e-2;
constexpr double kStandsOffCos = 0.5;

// Closes a hole whose vertices all lie on one line (within kFlatHole of its length): a slit of no
// width, two runs of border along the same line whose vertices the snap left apart, or three
// vertices with one on (or within a hair of) the border edge across it, a T-junction the snap
// left. Every face along it is split at the hole's vertices that lie inside its edge on the
// hole, as T-junctions are split, and the two runs then share their edges. A fan or ear would
// give faces of no area: where the two halves' keels of a full chine hull with a gap of 2e-4 L
// or more end at the transom's bottom edge, ten vertices on that edge. False (and nothing
// changed) when the hole is not flat, a three-vertex hole's middle vertex lies within
// kFlatHoleEnd of its long side's ends, a face along it is met twice or was split already in
// this pass, or the split runs would not pair up edge for edge.
bool split_flat_hole(Work& w, const EdgeAdjacency& adj, const std::vector<Index>& r,
                     const std::vector<Index>& edges, std::vector<std::uint8_t>& split,
                     double flat = kFlatHole) {
  SurfaceMesh& m = w.mesh;
  const std::size_t n = r.size();
  // The line: through the two vertices farthest apart.
  std::size_t i0 = 0, j0 = 0;
  double far = -1;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double d = squared_norm(m.positions[r[j]] - m.positions[r[i]]);
      if (d > far) far = d, i0 = i, j0 = j;
    }
  }
  if (!(far > 0)) return false;
  const Vec3d origin = m.positions[r[i0]];
  const Vec3d dir = (m.positions[r[j0]] - origin) / std::sqrt(far);
  const double length = std::sqrt(far);
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3d d = m.positions[r[i]] - origin;
    t[i] = dot(d, dir);
    if (norm(d - t[i] * dir) > flat * length) return false;
    if (n == 3 && (t[i] < kFlatHoleEnd * length || t[i] > (1 - kFlatHoleEnd) * length)) {
      if (i != i0 && i != j0) return false;
    }
  }
  // Each hole edge r[i] -> r[i + 1] with its face, the face's corner where that edge begins in
  // the face's own winding, and the hole's vertices strictly inside it, in order.
  struct Run {
    Index face;
    int corner;
    std::vector<Index> inner;
  };
  std::vector<Run> runs(n);
  std::vector<std::pair<Index, Index>> pieces;  // the hole's edges after the splits
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = (i + 1) % n;
    const Index f = adj.edges[edges[i]].first_slot / 4;
    if (split[f]) return false;
    for (std::size_t e = 0; e < i; ++e) {
      if (runs[e].face == f) return false;
    }
    const Face& face = m.faces[f];
    int c = 0;
    while (c < 3 && !((face[c] == r[i] && face[(c + 1) % 3] == r[k]) ||
                      (face[c] == r[k] && face[(c + 1) % 3] == r[i]))) {
      ++c;
    }
    if (c == 3) return false;
    runs[i].face = f;
    runs[i].corner = c;
    const double lo = std::min(t[i], t[k]), hi = std::max(t[i], t[k]);
    std::vector<std::pair<double, Index>> inside;
    for (std::size_t v = 0; v < n; ++v) {
      if (t[v] > lo && t[v] < hi && r[v] != r[i] && r[v] != r[k]) inside.push_back({t[v], r[v]});
    }
    std::sort(inside.begin(), inside.end());
    if (t[k] < t[i]) std::reverse(inside.begin(), inside.end());
    Index from = r[i];
    for (const auto& [tv, v] : inside) {
      runs[i].inner.push_back(v);
      pieces.push_back({from, v});
      from = v;
    }
    pieces.push_back({from, r[k]});
  }
  // Every piece must meet its reverse exactly once.
  std::vector<std::pair<Index, Index>> sorted = pieces;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
  for (const auto& [a, b] : pieces) {
    if (!std::binary_search(sorted.begin(), sorted.end(), std::pair<Index, Index>{b, a}))
      return false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (runs[i].inner.empty()) continue;
    const Index f = runs[i].face;
    const Face face = m.faces[f];
    const int c = runs[i].corner;
    const Index p = face[c], q = face[(c + 1) % 3], apex = face[(c + 2) % 3];
    std::vector<Index> chain{p};
    if (p == r[i]) {
      chain.insert(chain.end(), runs[i].inner.begin(), runs[i].inner.end());
    } else {
      chain.insert(chain.end(), runs[i].inner.rbegin(), runs[i].inner.rend());
    }
    chain.push_back(q);
    m.faces[f] = {chain[0], chain[1], apex, kInvalid};
    for (std::size_t s = 1; s + 1 < chain.size(); ++s) {
      m.faces.push_back({chain[s], chain[s + 1], apex, kInvalid});
      m.face_patch.push_back(m.face_patch[f]);
      w.face_old.push_back(w.face_old[f]);
    }
    split[f] = 1;  // the new faces are not in adj, so no later hole can name them
  }
  return true;
}

// The dihedral beyond which two faces closing a four-vertex hole across its free diagonal fold
// back on each other (cosine of 120 degrees): the hole is a dart round the taken diagonal.
constexpr double kFoldedFill = -0.5;
// How far a face round the collapsed vertex may turn (cosine of 60 degrees).
constexpr double kCollapseTurn = 0.5;

// The faces using vertex v (a scan: collapses are rare).
std::vector<Index> faces_of(const SurfaceMesh& m, Index v) {
  std::vector<Index> out;
  for (std::size_t f = 0; f < m.face_count(); ++f) {
    const Face& t = m.faces[f];
    if (t[0] == v || t[1] == v || t[2] == v) out.push_back(Index(f));
  }
  return out;
}

// Closes the four-vertex hole r, whose diagonal r[1] - r[3] is an edge of the mesh already and
// whose other diagonal would fold (a dart: r[1] or r[3] lies inside the triangle of the other
// three), by collapsing that edge: one of its ends moves onto the other, its two faces lose
// their area, and the hole's sides pair up. This is where the overlap remnants of two chine
// hull halves meet the stem (generated chine hull, seed 1035): the stem's lowest edge of the
// sides stands on the bottoms' dart. The end moved is the one whose faces turn least, none more
// than kCollapseTurn allows; the link of the edge must be its two faces' far corners and the
// hole's other two vertices, or a third face would meet at an edge. The collapsed faces keep a
// repeated corner and the moved vertex stays unused (drop_degenerate removes both). False (and
// nothing changed) when no end may move or a face round it changed in this pass (`touched`).
bool collapse_across_dart(Work& w, const std::vector<Index>& r,
                          std::vector<std::uint8_t>& touched) {
  SurfaceMesh& m = w.mesh;
  const Index b = r[1], d = r[3];
  const std::vector<Index> fb = faces_of(m, b), fd = faces_of(m, d);
  std::vector<Index> shared;
  std::set_intersection(fb.begin(), fb.end(), fd.begin(), fd.end(), std::back_inserter(shared));
  if (shared.size() != 2) return false;
  // The link check: the vertices next to both ends.
  const auto ring = [&](const std::vector<Index>& fs, Index v) {
    std::set<Index> out;
    for (Index f : fs) {
      for (int c = 0; c < 3; ++c) {
        if (m.faces[f][c] != v) out.insert(m.faces[f][c]);
      }
    }
    return out;
  };
  const std::set<Index> rb = ring(fb, b), rd = ring(fd, d);
  std::set<Index> common;
  std::set_intersection(rb.begin(), rb.end(), rd.begin(), rd.end(),
                        std::inserter(common, common.end()));
  std::set<Index> want{r[0], r[2]};
  for (Index f : shared) {
    for (int c = 0; c < 3; ++c) {
      if (m.faces[f][c] != b && m.faces[f][c] != d) want.insert(m.faces[f][c]);
    }
  }
  if (common != want) return false;
  for (const std::vector<Index>* fs : {&fb, &fd}) {
    for (Index f : *fs) {
      if (f >= touched.size() || touched[f]) return false;
    }
  }
  // The least cosine of the turn of the faces round `from` when it moves onto `onto`.
  const auto least_turn = [&](const std::vector<Index>& fs, Index from, Index onto) {
    double least = 1;
    for (Index f : fs) {
      if (std::binary_search(shared.begin(), shared.end(), f)) continue;
      Face moved = m.faces[f];
      for (int c = 0; c < 3; ++c) {
        if (moved[c] == from) moved[c] = onto;
      }
      const Vec3d before = face_normal(m.positions, m.faces[f]);
      const Vec3d after = face_normal(m.positions, moved);
      const double nb = norm(before), na = norm(after);
      if (!(nb > 0) || !(na > 0)) return -1.0;
      least = std::min(least, dot(before, after) / (nb * na));
    }
    return least;
  };
  const double move_d = least_turn(fd, d, b), move_b = least_turn(fb, b, d);
  if (std::max(move_d, move_b) < kCollapseTurn) return false;
  const bool d_moves = move_d >= move_b;
  const Index from = d_moves ? d : b, onto = d_moves ? b : d;
  for (Index f : d_moves ? fd : fb) {
    for (int c = 0; c < 3; ++c) {
      if (m.faces[f][c] == from) m.faces[f][c] = onto;
    }
    touched[f] = 1;
  }
  for (Index f : d_moves ? fb : fd) touched[f] = 1;
  return true;
}

// Closes the four-vertex hole r (edges[i] leaving r[i]), whose both diagonals are edges already,
// where one face runs along two of its sides: an overlap remnant the snap folded over the faces
// of the patch below (the generated 24-patch round-bilge hull with 0.1 m gaps and 5% overlaps,
// x = 25 m: a 2.2 m hole). That face covers the triangle the hole's other corner spans with its
// ends a second time, and leaves the other half of the quad open. It goes (its corners are made
// one, for drop_degenerate) and the triangle of the other half closes the hole, provided no
// face along that triangle's sides turns from it by 90 degrees or more. False (and nothing
// changed) otherwise, or when that face changed in this pass (`touched`).
bool replace_remnant_in_hole(Work& w, const EdgeAdjacency& adj, const std::vector<Index>& r,
                             const std::vector<Index>& edges, std::vector<std::uint8_t>& touched) {
  SurfaceMesh& m = w.mesh;
  for (std::size_t i = 0; i < 4; ++i) {
    const Index f = adj.edges[edges[i]].first_slot / 4;
    if (adj.edges[edges[(i + 1) % 4]].first_slot / 4 != f) continue;
    if (f >= touched.size() || touched[f]) return false;
    // f runs r[i] -> r[i + 1] -> r[i + 2]; without it the hole is r[i], r[i + 2], r[i + 3] in
    // the winding of the faces along it, and the new face runs against that.
    const Index a = r[i], c = r[(i + 2) % 4], d = r[(i + 3) % 4];
    const Face add{a, d, c, kInvalid};
    const Vec3d n = face_normal(m.positions, add);
    if (!(norm(n) > 0.5)) return false;  // no area
    // The faces along the new triangle: across a - c (f's neighbour there), c - d and d - a.
    std::vector<Index> around{adj.edges[edges[(i + 2) % 4]].first_slot / 4,
                              adj.edges[edges[(i + 3) % 4]].first_slot / 4};
    const Face& t = m.faces[f];
    int k = 0;  // f's corner where its edge c -> a begins
    while (k < 3 && !(t[k] == c && t[(k + 1) % 3] == a)) ++k;
    if (k == 3) return false;
    const Index g = adj.opposite_face[4 * f + Index(k)];
    if (g == kInvalid) return false;
    around.push_back(g);
    for (Index h : around) {
      if (h >= touched.size() || touched[h]) return false;
      if (!(dot(face_normal(m.positions, m.faces[h]), n) > 0)) return false;
    }
    m.faces[f] = {a, a, a, kInvalid};
    touched[f] = 1;
    append_faces(w, std::span<const Face>(&add, 1), around);
    return true;
  }
  return false;
}

}  // namespace

// A boundary loop that passes a vertex twice (a hole touching the hull's outline at one vertex)
// is several cycles; cut it there. Each cycle is (vertices, edges), edges[i] leaving vertices[i].
std::vector<std::pair<std::vector<Index>, std::vector<Index>>> cycles_of(const BoundaryLoop& loop) {
  std::vector<std::pair<std::vector<Index>, std::vector<Index>>> out;
  std::vector<Index> vs, es;
  for (std::size_t i = 0; i < loop.vertices.size(); ++i) {
    const Index v = loop.vertices[i];
    auto again = std::find(vs.begin(), vs.end(), v);
    if (again != vs.end()) {
      const std::ptrdiff_t at = again - vs.begin();
      out.push_back({std::vector<Index>(vs.begin() + at, vs.end()),
                     std::vector<Index>(es.begin() + at, es.end())});
      vs.resize(std::size_t(at));
      es.resize(std::size_t(at));
    }
    vs.push_back(v);
    es.push_back(loop.edges[i]);
  }
  out.push_back({std::move(vs), std::move(es)});
  return out;
}

// Whether a four-vertex hole r is split along r[0] - r[2] when both diagonals are free: the
// diagonal whose two new faces fit the faces beside them (around[i], across side r[i] -
// r[i + 1]) best, by the largest angle between a new face and a face beside it, where the other
// fits kCreaseMargin worse; else the shorter.
bool split_02_first(const SurfaceMesh& m, const std::vector<Index>& r,
                    const std::vector<Index>& around) {
  // Split k: new faces (r[k], r[k + 2], r[k + 1]) (sides k and k + 1) and (r[k], r[k + 3],
  // r[k + 2]) (sides k + 2 and k + 3), the worse fit of the two.
  const auto split = [&](std::size_t k) {
    double worst = 0;
    for (std::size_t h = 0; h < 2; ++h) {
      const std::size_t a = k + 2 * h;
      worst = std::max(worst, misfit(m, {r[a % 4], r[(a + 2) % 4], r[(a + 1) % 4], kInvalid},
                                     face_normal(m.positions, m.faces[around[a % 4]]),
                                     face_normal(m.positions, m.faces[around[(a + 1) % 4]])));
    }
    return Closing{worst, norm(m.positions[r[(k + 2) % 4]] - m.positions[r[k]])};
  };
  return fitting_shortest({split(0), split(1)}) == 0;
}

HoleStats fill_small_holes(Work& w, const EdgeAdjacency& adj, const MergeOptions& options,
                           std::vector<std::array<Index, 2>>* left_open) {
  SurfaceMesh& m = w.mesh;
  if (left_open) left_open->clear();
  // A hole this step would close but cannot: its edges go to left_open.
  const auto leave_open = [&](const std::vector<Index>& r) {
    if (!left_open) return;
    for (std::size_t i = 0; i < r.size(); ++i) left_open->push_back({r[i], r[(i + 1) % r.size()]});
  };
  HoleStats stats;
  // The adjacency's edges are in key order, so a binary search finds one.
  const auto is_edge = [&](Index a, Index b) { return find_edge(adj, a, b) != kInvalid; };
  std::vector<std::uint8_t> split(m.face_count(), 0);  // faces split or collapsed in this pass
  // Vertices of the holes closed by a collapse: a later hole through them waits for the next
  // pass, whose adjacency is current.
  std::vector<std::uint8_t> changed(m.vertex_count(), 0);
  for (const BoundaryLoop& loop : adj.boundary_loops) {
    if (!loop.closed) continue;
    for (const auto& [r, edges] : cycles_of(loop)) {
      if (r.size() < 3 || r.size() > kMaxHoleVertices) continue;
      if (std::any_of(r.begin(), r.end(), [&](Index v) { return changed[v] != 0; })) continue;
      std::set<PatchId> patches;
      std::vector<Index> around;  // the faces along the hole
      double perimeter = 0, local = 0, tolerance = 0;
      Vec3d centroid{0, 0, 0};
      for (Index v : r) centroid += m.positions[v] / double(r.size());
      double area2 = 0;   // twice the area of the fan from the centroid (unsigned: a twist adds)
      Vec3d up{0, 0, 0};  // the side the faces along the loop face
      for (std::size_t i = 0; i < edges.size(); ++i) {
        const Index f = adj.edges[edges[i]].first_slot / 4;
        patches.insert(m.face_patch[f]);
        up += face_normal(m.positions, m.faces[f]);
        around.push_back(f);
        const Vec3d& p = m.positions[r[i]];
        const Vec3d& q = m.positions[r[(i + 1) % r.size()]];
        const double edge = norm(q - p);
        perimeter += edge;
        tolerance += vertex_tolerance(options, edge) * edge;
        area2 += norm(cross(p - centroid, q - centroid));
        const Face& t = m.faces[f];
        for (int c = 0; c < 3; ++c) {
          local = std::max(local, norm(m.positions[t[(c + 1) % 3]] - m.positions[t[c]]));
        }
      }
      if (patches.size() < 2) continue;
      // Beyond four vertices only holes far smaller than the faces around them (pinholes left
      // where several short border edges met) and slits: mean width (twice the area over the
      // perimeter) within the mean gap tolerance along them (by edge length), both times the
      // perimeter.
      const bool pinhole = perimeter < local;
      const bool slit = area2 <= tolerance;
      if (r.size() > 4 && !pinhole && !slit) continue;
      // The loop follows its faces' winding, so the new faces run against it.
      std::vector<Face> add;
      if (split_flat_hole(w, adj, r, edges, split)) {
        for (Index v : r) changed[v] = 1;
        ++stats.filled;
        continue;
      }
      if (r.size() == 3) {
        const Face tri{r[0], r[2], r[1], kInvalid};
        const Vec3d n = face_normal(m.positions, tri);
        const double nn = norm(n);
        bool stands_off = false;
        for (Index f : around) {
          const Vec3d nf = face_normal(m.positions, m.faces[f]);
          stands_off = stands_off || dot(n, nf) < kStandsOffCos * nn * norm(nf);
        }
        if (stands_off && split_flat_hole(w, adj, r, edges, split, kNearlyFlatHole)) {
          for (Index v : r) changed[v] = 1;
          ++stats.filled;
          continue;
        }
        add.push_back(tri);
      } else if (r.size() > 4 && pinhole) {
        // A pinhole: a fan from its first vertex (its shape is below the mesh's resolution).
        for (std::size_t i = 1; i + 1 < r.size(); ++i)
          add.push_back({r[0], r[i + 1], r[i], kInvalid});
      } else if (r.size() > 4) {
        std::vector<Vec3d> beside(around.size());
        for (std::size_t i = 0; i < around.size(); ++i) {
          beside[i] = face_normal(m.positions, m.faces[around[i]]);
        }
        add = clip_ears(m, r, std::move(beside), up, is_edge);
        // Where its two runs cross (each half's chords of a tight curve, sampled apart: the
        // forefoot of a full hull at 40,000 triangles), its ears run out: a fan closes it, from
        // the first vertex none of whose diagonals is an edge already. Its faces fold within
        // the slit's width.
        if (add.empty()) add = fan_of_new_diagonals(r, is_edge);
        if (add.empty()) {
          leave_open(r);
          continue;
        }
      } else {
        // The shorter diagonal, unless it is an edge of the mesh already (the hole then folds
        // round it, and a third face would meet there).
        const bool d02 = !is_edge(r[0], r[2]), d13 = !is_edge(r[1], r[3]);
        if (!d02 && !d13) {
          if (replace_remnant_in_hole(w, adj, r, edges, split)) {
            for (Index v : r) changed[v] = 1;
            ++stats.filled;
            ++stats.left_degenerate;
            continue;
          }
          leave_open(r);
          continue;
        }
        if (d02 != d13) {
          // One diagonal taken: closing across the other must not fold back on itself.
          const std::vector<Index> q =
              d02 ? r : std::vector<Index>{r[1], r[2], r[3], r[0]};  // taken: q[1] - q[3]
          const Vec3d n0 = face_normal(m.positions, {q[0], q[2], q[1], kInvalid});
          const Vec3d n1 = face_normal(m.positions, {q[0], q[3], q[2], kInvalid});
          const double nn = norm(n0) * norm(n1);
          if (nn > 0 && dot(n0, n1) < kFoldedFill * nn) {
            if (collapse_across_dart(w, q, split)) {
              for (Index v : q) changed[v] = 1;
              ++stats.filled;
              ++stats.left_degenerate;
              continue;
            }
          }
        }
        if (d02 && (!d13 || split_02_first(m, r, around))) {
          add.push_back({r[0], r[2], r[1], kInvalid});
          add.push_back({r[0], r[3], r[2], kInvalid});
        } else {
          add.push_back({r[1], r[3], r[2], kInvalid});
          add.push_back({r[1], r[0], r[3], kInvalid});
        }
      }
      append_faces(w, add, around);
      ++stats.filled;
    }
  }
  return stats;
}

std::size_t close_flat_holes(Work& w, const EdgeAdjacency& adj) {
  std::vector<std::uint8_t> split(w.mesh.face_count(), 0);
  std::vector<std::uint8_t> changed(w.mesh.vertex_count(), 0);
  std::size_t closed = 0;
  for (const BoundaryLoop& loop : adj.boundary_loops) {
    if (!loop.closed) continue;
    for (const auto& [r, edges] : cycles_of(loop)) {
      if (r.size() < 3 || r.size() > kMaxFlatHoleVertices) continue;
      if (std::any_of(r.begin(), r.end(), [&](Index v) { return changed[v] != 0; })) continue;
      if (!split_flat_hole(w, adj, r, edges, split)) continue;
      for (Index v : r) changed[v] = 1;
      ++closed;
    }
  }
  return closed;
}

}  // namespace hm::merge
