// find_features: check the input, find the knuckle edges (score, confirm, hints), classify the
// boundaries, chain everything into lines and corners, then check the result covers every
// feature edge once.
#include "unstructured/features.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/bbox.h"
#include "core/error.h"
#include "unstructured/chain_features.h"
#include "unstructured/classify_boundaries.h"
#include "unstructured/find_knuckles.h"

namespace hm {
namespace {

void check_input(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                 std::span<const Patch> patches, const FeatureOptions& options) {
  const std::size_t nv = mesh.vertex_count(), nf = mesh.face_count();
  const auto fail = [](const std::string& what) { throw GeometryError("find_features: " + what); };
  if (adjacency.slot_edge.size() != 4 * nf || adjacency.opposite_face.size() != 4 * nf) {
    fail("the adjacency was built for another mesh");
  }
  for (const MeshEdge& e : adjacency.edges) {
    if (e.v0 >= nv || e.v1 >= nv) fail("the adjacency names a vertex past the mesh");
  }
  if (!adjacency.nonmanifold_edges.empty()) {
    fail("the mesh is not edge-manifold (" + std::to_string(adjacency.nonmanifold_edges.size()) +
         " edges with more than two faces)");
  }
  if (!mesh.vertex_patch.empty() && mesh.vertex_patch.size() != nv) {
    fail("vertex_patch has " + std::to_string(mesh.vertex_patch.size()) + " entries for " +
         std::to_string(nv) + " vertices");
  }
  if (!mesh.vertex_uv.empty() && mesh.vertex_uv.size() != nv) {
    fail("vertex_uv has " + std::to_string(mesh.vertex_uv.size()) + " entries for " +
         std::to_string(nv) + " vertices");
  }
  if (mesh.face_patch.size() != nf) {
    fail("face_patch has " + std::to_string(mesh.face_patch.size()) + " entries for " +
         std::to_string(nf) + " faces");
  }
  if (options.confirm_on_nurbs) {
    const auto bad = std::find_if(mesh.face_patch.begin(), mesh.face_patch.end(),
                                  [&](PatchId p) { return p >= patches.size(); });
    if (bad != mesh.face_patch.end()) {
      fail("face " + std::to_string(bad - mesh.face_patch.begin()) + " names patch " +
           std::to_string(*bad) + " of " + std::to_string(patches.size()));
    }
  }
  for (const auto* hints : {&options.add, &options.suppress}) {
    for (const KnuckleHint& h : *hints) {
      if (h.kind == KnuckleHint::Kind::kPlane && squared_norm(h.plane_normal) == 0) {
        throw UsageError("knuckle hint: a plane needs a non-zero normal");
      }
      if (h.kind == KnuckleHint::Kind::kPoints && h.points.empty()) {
        throw UsageError("knuckle hint: a list of points needs at least one point");
      }
    }
  }
}

// Every knuckle edge lies on exactly one knuckle line and every boundary edge on one run: the
// chaining and the run split must not drop or double an edge.
void check_result(const FeatureSet& f, const EdgeAdjacency& adjacency) {
  std::size_t knuckle_edges = 0, line_edges = 0, run_edges = 0;
  for (std::uint8_t k : f.edge_knuckle) knuckle_edges += k;
  for (const FeatureLine& l : f.knuckles) line_edges += l.vertices.size() - (l.closed ? 0 : 1);
  for (const BoundaryRun& r : f.boundaries) run_edges += r.vertices.size() - (r.closed ? 0 : 1);
  if (line_edges != knuckle_edges || run_edges != adjacency.boundary_edges.size()) {
    throw InternalError("find_features: feature lines cover " + std::to_string(line_edges) +
                        " of " + std::to_string(knuckle_edges) + " knuckle edges and " +
                        std::to_string(run_edges) + " of " +
                        std::to_string(adjacency.boundary_edges.size()) + " boundary edges");
  }
}

}  // namespace

const char* to_string(BoundaryKind k) {
  switch (k) {
    case BoundaryKind::kDeckEdge:
      return "deck edge";
    case BoundaryKind::kTransomEdge:
      return "transom edge";
    case BoundaryKind::kCentrePlane:
      return "centre plane";
    case BoundaryKind::kWaterline:
      return "waterline";
    case BoundaryKind::kHole:
      return "hole";
  }
  return "unknown";
}

double FeatureSet::knuckle_length() const {
  double sum = 0;
  for (const FeatureLine& l : knuckles) sum += l.length;
  return sum;
}

FeatureSet find_features(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                         std::span<const Patch> patches, const FeatureOptions& options) {
  check_input(mesh, adjacency, patches, options);
  BBox3d box;
  for (const Vec3d& p : mesh.positions) box.add(p);
  const Vec3d extent = box.extent();
  const double length = std::max({extent.x, extent.y, extent.z});

  FeatureSet f;
  detail::KnuckleEdges knuckles = detail::find_knuckles(mesh, adjacency, patches, options, length);
  f.edge_knuckle = std::move(knuckles.edge_knuckle);
  f.candidates_rejected_by_nurbs = knuckles.rejected_by_nurbs;

  const std::vector<BoundaryKind> edge_kind =
      detail::classify_boundary_edges(mesh, adjacency, options, length);
  f.boundaries = detail::boundary_runs(mesh, adjacency, edge_kind);

  detail::ChainedFeatures chained =
      detail::chain_features(mesh, adjacency, f.edge_knuckle, f.boundaries);
  f.knuckles = std::move(chained.knuckles);
  f.vertex_feature = std::move(chained.vertex_feature);
  f.corners = std::move(chained.corners);

  check_result(f, adjacency);
  return f;
}

}  // namespace hm
