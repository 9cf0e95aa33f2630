// EdgeTable::build: a patch triangulation's half-edges sorted by (edge key, corner), rebuilt at
// every refinement level. A comparison sort of the 3T half-edges was a tenth of a large trimmed
// patch's tessellation; the pairs are distinct, so any exact sort gives the same array, and a
// counting sort on the lower vertex with a short stable sort per vertex is linear.
#include <algorithm>

#include "tessellate/patch_mesh.h"

namespace hm {

void EdgeTable::build(const std::vector<Tri>& tris) {
  const std::size_t n = 3 * tris.size();
  Index vertices = 0;
  for (const Tri& t : tris) vertices = std::max({vertices, t[0] + 1, t[1] + 1, t[2] + 1});
  // Count -> exclusive scan -> scatter, in corner order: each vertex's run then holds its
  // half-edges with ascending corners.
  std::vector<Index> start(std::size_t{vertices} + 1, 0);
  for (const Tri& t : tris)
    for (int i = 0; i < 3; ++i) ++start[std::min(t[i], t[(i + 1) % 3]) + 1];
  for (std::size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
  he.resize(n);
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (std::size_t t = 0; t < tris.size(); ++t) {
    for (int i = 0; i < 3; ++i) {
      const Index a = tris[t][i], b = tris[t][(i + 1) % 3];
      he[fill[std::min(a, b)]++] = {edge_key(a, b), Index(3 * t + i)};
    }
  }
  // Within a run (a vertex's few edges) by key, stably: equal keys keep ascending corners.
  for (std::size_t v = 0; v < vertices; ++v) {
    for (Index k = start[v] + 1; k < start[v + 1]; ++k) {
      const HalfEdge x = he[k];
      Index j = k;
      for (; j > start[v] && he[j - 1].key > x.key; --j) he[j] = he[j - 1];
      he[j] = x;
    }
  }
  first.clear();
  edge_of_corner.resize(he.size());
  for (std::size_t k = 0; k < he.size(); ++k) {
    if (k == 0 || he[k].key != he[k - 1].key) first.push_back(Index(k));
    edge_of_corner[he[k].corner] = Index(first.size() - 1);
  }
  first.push_back(Index(he.size()));
}

}  // namespace hm
