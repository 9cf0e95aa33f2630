// Coincident nodes into one. Two rows can end on the same point of a line (a stem, the centre
// plane) as two nodes: the edge curves and the NURBS refinement put both there, and a panel
// between them has a side of no length and no area (`--validate` refuses it). Property seed
// 9107 (a round-bilge hull trimmed 0.75 degrees by the bow, 800 panels) had two stem nodes
// 2.5e-11 m apart at the bulb and a triangle of no area between them.
//
// collect (panel sides no longer than kOneSpot of the panel's longest side, in face order) ->
// apply (the later node merges into the earlier, when the panels around stay manifold; the
// knuckle edges follow) -> drop the removed faces. Nothing moves. Serial, so deterministic.
#include <algorithm>
#include <set>

#include "structured/editable_faces.h"
#include "structured/structured_steps.h"

namespace hm::structured {
namespace {

// A side this short, against its panel's longest, joins two nodes on one spot (the zero-area rule
// of the quality report is 1e-10 of the longest side squared).
constexpr double kOneSpot = 1e-8;

}  // namespace

std::size_t weld_coincident_nodes(std::vector<std::array<Index, 2>>& knuckle_edges,
                                  SurfaceMesh& mesh) {
  EditableFaces m(mesh.faces, mesh.positions);
  std::size_t welded = 0;
  const Index nf = static_cast<Index>(mesh.faces.size());
  for (Index f = 0; f < nf; ++f) {
    if (m.removed(f)) continue;
    const Face q = m.face(f);
    const int n = corner_count(q);
    double longest = 0;
    for (int i = 0; i < n; ++i)
      longest = std::max(longest, norm(m.position(q[(i + 1) % n]) - m.position(q[i])));
    for (int i = 0; i < n; ++i) {
      const Index a = q[i], b = q[(i + 1) % n];
      if (!(norm(m.position(b) - m.position(a)) <= kOneSpot * longest)) continue;
      const Index keep = std::min(a, b), from = std::max(a, b);
      std::set<Index> core(m.around(from).begin(), m.around(from).end());
      core.insert(m.around(keep).begin(), m.around(keep).end());
      std::vector<std::pair<Index, Face>> was;
      for (Index g : core) was.emplace_back(g, m.face(g));
      m.merge_node(from, keep);
      if (!m.manifold(core)) {
        for (const auto& [g, h] : was) m.set_face(g, h);
        continue;
      }
      ++welded;
      for (auto& e : knuckle_edges) {
        for (Index& v : e) v = v == from ? keep : v;
      }
      break;  // this face is changed or gone
    }
  }
  if (welded == 0) return 0;
  knuckle_edges.erase(std::remove_if(knuckle_edges.begin(), knuckle_edges.end(),
                                     [](const std::array<Index, 2>& e) { return e[0] == e[1]; }),
                      knuckle_edges.end());
  drop_removed_faces(mesh);
  return welded;
}

}  // namespace hm::structured
