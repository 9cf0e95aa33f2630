// Wedge quads into triangles. A quad that breaks the side rule and whose shortest side is under
// min_opposite_ratio of the side opposite it is a triangle in all but name: rows that converge at
// a keel's end, a sonar dome's nose or a cap leave such quads once the nodes have settled (the
// zip splits the ones it sees). The paper turns them into triangles. A split along a diagonal
// would leave a sliver on the short side; here the short side collapses instead: one of its
// nodes merges into the other, the quad becomes a triangle and the panel across the short side
// loses a corner (a quad becomes a triangle, a triangle goes). Nothing moves, so every node stays
// exactly where the rows and the edge curves put it.
//
// collect (wedges, in face order) -> score (each of the two merges against the panels as they
// stand; a merge that leaves a face flat, three corners on a line, or drags panels through
// others, is not one) -> apply the better, when it leaves fewer panels failing a rule nearby, or
// as many and a milder worst -> drop the removed faces. Serial and in face order, so
// deterministic.
#include <algorithm>
#include <set>

#include "query/find_self_intersections.h"
#include "structured/editable_faces.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// Side i of quad q runs from corner i to corner i + 1.
double side_length(const EditableFaces& m, const Face& q, int i) {
  return norm(m.position(q[(i + 1) % 4]) - m.position(q[i]));
}

// The shortest side of quad q (the first of equals) when it is a wedge's: under `ratio` of the
// side opposite it. -1 otherwise.
int wedge_side(const EditableFaces& m, const Face& q, double ratio) {
  int s = 0;
  for (int i = 1; i < 4; ++i)
    if (side_length(m, q, i) < side_length(m, q, s)) s = i;
  return side_length(m, q, s) < ratio * side_length(m, q, (s + 2) % 4) ? s : -1;
}

}  // namespace

std::size_t collapse_wedges(std::span<const NodeSlot> slots,
                            std::span<const std::array<Index, 2>> knuckle_edges,
                            double min_opposite_ratio, SurfaceMesh& mesh) {
  const NodeFreedom freedom = node_freedom(slots, knuckle_edges, mesh);
  const double cross_tol = crossing_tolerance(mesh.positions);
  EditableFaces m(mesh.faces, mesh.positions);
  std::vector<std::uint8_t> merged(mesh.vertex_count(), 0);
  std::size_t collapsed = 0;
  const Index nf = static_cast<Index>(mesh.faces.size());
  for (Index f = 0; f < nf; ++f) {
    // collect: a quad breaking the side rule, with a wedge's short side.
    if (m.removed(f) || is_triangle(m.face(f))) continue;
    double side = 0, area = 0;
    m.rules(f, side, area);
    if (side <= kSideLimit) continue;
    const Face q = m.face(f);
    const int s = wedge_side(m, q, min_opposite_ratio);
    if (s < 0) continue;
    const Index a = q[s], b = q[(s + 1) % 4];

    // score: the faces around both ends, as they stand and after each merge.
    std::set<Index> core(m.around(a).begin(), m.around(a).end());
    core.insert(m.around(b).begin(), m.around(b).end());
    std::vector<std::pair<Index, Face>> was;
    for (Index g : core) was.emplace_back(g, m.face(g));
    // Failing panels are counted over the faces around every corner of these, the same faces
    // for every candidate.
    std::set<Index> judged;
    for (Index g : core) {
      const Face& h = m.face(g);
      for (int c = 0; c < corner_count(h); ++c)
        judged.insert(m.around(h[c]).begin(), m.around(h[c]).end());
    }
    EditableFaces::Score best = m.score(core, judged);
    const std::size_t crossed = m.crossings(core, judged, cross_tol);
    Index best_from = kInvalid;
    for (auto [from, to] : {std::pair{a, b}, std::pair{b, a}}) {
      if (merged[from] || !freedom.may_merge(from, to, slots)) continue;
      m.merge_node(from, to);
      if (m.manifold(core) && !m.flat(core) && m.crossings(core, judged, cross_tol) <= crossed) {
        const EditableFaces::Score sc = m.score(core, judged);
        if (sc.better_than(best)) {
          best = sc;
          best_from = from;
        }
      }
      for (const auto& [g, h] : was) m.set_face(g, h);
    }

    // apply.
    if (best_from == kInvalid) continue;
    m.merge_node(best_from, best_from == a ? b : a);
    merged[best_from] = 1;
    ++collapsed;
  }
  drop_removed_faces(mesh);
  return collapsed;
}

}  // namespace hm::structured
