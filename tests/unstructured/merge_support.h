// What the merge tests share: a generated hull tessellated and merged, and the checks of a clean
// half hull.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "mesh/adjacency.h"
#include "nurbs/generate_hull.h"
#include "support/test_support.h"
#include "tessellate/tessellate.h"
#include "unstructured/merge.h"
#include "unstructured/merge_steps.h"

namespace hm::test {

struct Merged {
  std::vector<Patch> patches;
  Tessellation tess;
  MergedSurface merged;
  EdgeAdjacency adj;
};

inline Merged merge_of(std::vector<Patch> patches, double edge_length = 0,
                       const MergeOptions& options = {}) {
  Merged m;
  m.patches = std::move(patches);
  TessellateOptions o;
  o.edge_length = edge_length;
  m.tess = tessellate(m.patches, o, silent_progress());
  m.merged = merge_patches(m.patches, m.tess.mesh, options, silent_progress());
  m.adj = build_edge_adjacency(m.merged.mesh.faces, m.merged.mesh.vertex_count());
  return m;
}

inline GeneratedHull generated(HullKind kind, int patches, HullDefects defects = {}) {
  HullSpec spec;
  spec.kind = kind;
  spec.patches = patches;
  spec.defects = defects;
  return generate_hull(spec);
}

inline double total_area(const SurfaceMesh& m) {
  double a = 0;
  for (const Face& f : m.faces) a += face_area(m.positions, f);
  return a;
}

// A half hull merges into one surface whose only boundary is its outline (centre plane, deck).
inline void expect_clean_half_hull(const Merged& m, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_TRUE(m.adj.nonmanifold_edges.empty());
  EXPECT_TRUE(m.adj.inconsistent_edges.empty());
  EXPECT_EQ(m.adj.boundary_loops.size(), 1u);
  EXPECT_GT(m.merged.report.enclosed_volume, 0.0);
  EXPECT_EQ(m.merged.mesh.face_patch.size(), m.merged.mesh.face_count());
  EXPECT_EQ(m.merged.face_new2old.size(), m.merged.mesh.face_count());
  for (std::size_t f = 0; f < m.merged.mesh.face_count(); ++f) {
    // Provenance: every face keeps the patch of the input triangle it was cut from.
    ASSERT_EQ(m.merged.mesh.face_patch[f], m.tess.mesh.face_patch[m.merged.face_new2old[f]]);
  }
}

// A hand-made mesh as the merge steps take it: no (u, v), and each face and vertex its own input.
inline void number_as_input(merge::Work& w) {
  SurfaceMesh& m = w.mesh;
  m.vertex_uv.assign(m.positions.size(), {});
  w.face_old.clear();
  w.vert_old.clear();
  for (std::size_t f = 0; f < m.faces.size(); ++f) w.face_old.push_back(Index(f));
  for (std::size_t v = 0; v < m.positions.size(); ++v) w.vert_old.push_back(Index(v));
}

}  // namespace hm::test
