// Triangle pairs into quads. The zips put a triangle wherever one row must advance alone, the
// caps fan, and the repairs and the wedge collapse split or shrink quads; two such triangles side
// by side often make a quad as good as the rows' own. Panel codes of the SHALLO and KELVIN kind
// want quads, and a quad in place of two triangles also halves the collocation points there.
//
// collect (each pair of triangles sharing a side: same block, off every knuckle, consistently
// oriented) -> score (the quad they make: convex, within the zip's warp and opposite-side tests
// and the side rule) -> select (best side ratio first, then face order) -> apply (when no more
// panels fail a rule among the pair and the faces beside it, the worst is no worse, and no more
// pairs of panels pass through each other nearby) -> drop the second triangles. Nothing moves.
// Serial, so deterministic.
#include <algorithm>
#include <set>
#include <tuple>

#include "query/find_self_intersections.h"
#include "structured/editable_faces.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// Orientation of triangle (a, b, c) against n: its doubled area, signed.
double turn(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& n) {
  return dot(cross(b - a, c - a), n);
}

// Each triangle of both diagonal splits covers at least this share of the quad (projected on its
// normal): a square's cover half each. Below it a corner is nearly flat, and the later steps (the
// open side's nodes put onto y = 0) may tip it over (property seed chine 1338).
constexpr double kMinCornerShare = 0.05;

// Convex with a margin: every triangle of both diagonal splits faces the quad's normal (the
// quality report's Newell normal: for four corners, the diagonals' cross product) and covers
// at least kMinCornerShare of it.
bool convex(const Vec3d (&p)[4]) {
  const Vec3d n = cross(p[2] - p[0], p[3] - p[1]);
  const double least = kMinCornerShare * squared_norm(n);
  return least > 0 && turn(p[0], p[1], p[2], n) > least && turn(p[0], p[2], p[3], n) > least &&
         turn(p[1], p[2], p[3], n) > least && turn(p[1], p[3], p[0], n) > least;
}

struct Candidate {
  double side = 0;  // the quad's side ratio
  Index first = kInvalid, second = kInvalid;
  Face quad{};
};

}  // namespace

std::size_t pair_triangles(std::span<const std::array<Index, 2>> knuckle_edges,
                           const ZipOptions& options, SurfaceMesh& mesh) {
  std::set<std::pair<Index, Index>> knuckle;
  for (const std::array<Index, 2>& k : knuckle_edges)
    knuckle.insert({std::min(k[0], k[1]), std::max(k[0], k[1])});
  const double cross_tol = crossing_tolerance(mesh.positions);
  EditableFaces m(mesh.faces, mesh.positions);
  const Index nf = static_cast<Index>(mesh.faces.size());

  // collect and score: triangle f with side u -> v, and the triangle g across it, which runs
  // v -> u when the two face the same way. The quad is u, x, v, w (x: g's third corner, w: f's).
  std::vector<Candidate> candidates;
  for (Index f = 0; f < nf; ++f) {
    const Face t = m.face(f);
    if (m.removed(f) || !is_triangle(t)) continue;
    for (int c = 0; c < 3; ++c) {
      const Index u = t[c], v = t[(c + 1) % 3], w = t[(c + 2) % 3];
      const Index g = m.across(f, u, v);
      if (g == kInvalid || g < f || !is_triangle(m.face(g))) continue;
      if (mesh.face_block[g] != mesh.face_block[f]) continue;
      if (knuckle.count({std::min(u, v), std::max(u, v)})) continue;
      const Face s = m.face(g);
      const int k = static_cast<int>(std::find(s.begin(), s.begin() + 3, v) - s.begin());
      if (k >= 3 || s[(k + 1) % 3] != u) continue;  // g runs u -> v: the pair is not oriented alike
      const Index x = s[(k + 2) % 3];
      if (x == w) continue;
      const Face q{u, x, v, w};
      const Vec3d p[4] = {m.position(u), m.position(x), m.position(v), m.position(w)};
      if (!convex(p) || quad_warp(p[0], p[1], p[2], p[3]) > options.max_warp ||
          opposite_ratio(p[0], p[1], p[2], p[3]) < options.min_opposite_ratio) {
        continue;
      }
      const double side = side_ratio(m.positions(), q);
      if (!(side <= kSideLimit)) continue;
      candidates.push_back({side, f, g, q});
    }
  }

  // select: the best quads first, ties in face order.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.side, a.first, a.second) < std::tie(b.side, b.first, b.second);
  });

  // apply, each against the mesh as the earlier pairs left it.
  std::size_t paired = 0;
  for (const Candidate& cand : candidates) {
    const Face before_first = m.face(cand.first), before_second = m.face(cand.second);
    if (m.removed(cand.first) || m.removed(cand.second) || !is_triangle(before_first) ||
        !is_triangle(before_second)) {
      continue;  // one of them went into an earlier quad
    }
    std::set<Index> judged{cand.first, cand.second};
    for (Index v : cand.quad)
      for (Index g : m.around(v)) judged.insert(g);
    // Crossings are looked for one ring further, on the quad's other split too (x-w; the mesh's
    // own split, u-v, is the pair's): where the hull is a few centimetres thick (a Wigley's
    // trimmed end), that diagonal may pass through the panels beyond.
    const std::set<Index> near = m.ring(judged);
    const EditableFaces::Score before = m.score({cand.first, cand.second}, judged);
    const std::size_t crossed = m.crossings({cand.first, cand.second}, near, cross_tol);
    m.set_face(cand.second, {kInvalid, kInvalid, kInvalid, kInvalid});
    m.set_face(cand.first, cand.quad);
    const EditableFaces::Score after = m.score({cand.first}, judged);
    const Face& q = cand.quad;
    m.set_face(cand.first, {q[1], q[2], q[3], q[0]});
    const std::size_t crossed_after = m.crossings({cand.first}, near, cross_tol);
    m.set_face(cand.first, q);
    if (before.better_than(after) || !m.manifold({cand.first}) || crossed_after > crossed) {
      m.set_face(cand.first, before_first);
      m.set_face(cand.second, before_second);
      continue;
    }
    ++paired;
  }

  // validate: the dropped triangles go, with their blocks, keeping the order.
  drop_removed_faces(mesh);
  return paired;
}

}  // namespace hm::structured
