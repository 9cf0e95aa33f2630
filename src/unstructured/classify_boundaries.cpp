// Boundary kinds by the rules listed in classify_boundaries.h, then maximal runs per loop.
#include "unstructured/classify_boundaries.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "core/bbox.h"

namespace hm::detail {
namespace {

constexpr double kPlaneTolerance = 2e-4;   // of L: centre plane and waterline
constexpr double kTransomMaxDx = 0.5;      // |dx| / |edge|: within 30 degrees of y-z plane
constexpr double kTransomMaxFaceNx = 0.7;  // |n_x| of the face along a transom edge
constexpr double kTransomEndReach = 0.25;  // of L, from either x end of the surface
constexpr double kTransomMinSpan = 0.01;   // of L, the diagonal of a transom run's box
constexpr double kDeckTolerance = 0.05;    // of the z extent, below the local top
constexpr int kProfileSlabs = 256;         // x slabs of the top profile

// Highest z of the surface in slabs of x: the deck edge is at the top of its slab.
class TopProfile {
 public:
  TopProfile(std::span<const Vec3d> positions, const BBox3d& box)
      : x0_(box.lo.x),
        width_(std::max(box.extent().x, std::numeric_limits<double>::min()) / kProfileSlabs),
        zmax_(kProfileSlabs, -std::numeric_limits<double>::infinity()) {
    for (const Vec3d& p : positions) {
      double& z = zmax_[slab(p.x)];
      z = std::max(z, p.z);
    }
  }

  // Highest z over the slabs covering [xa, xb] and one slab either side.
  double top_near(double xa, double xb) const {
    const int lo = std::max(0, slab(std::min(xa, xb)) - 1);
    const int hi = std::min(kProfileSlabs - 1, slab(std::max(xa, xb)) + 1);
    return *std::max_element(zmax_.begin() + lo, zmax_.begin() + hi + 1);
  }

 private:
  int slab(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - x0_) / width_)), 0, kProfileSlabs - 1);
  }

  double x0_, width_;
  std::vector<double> zmax_;
};

// What one boundary edge is by itself; transom edges need their run (see classify).
struct EdgeVerdict {
  BoundaryKind kind = BoundaryKind::kHole;  // kind unless it joins a transom run
  bool transom_candidate = false;
};

struct Context {
  const SurfaceMesh& mesh;
  const EdgeAdjacency& adjacency;
  const FeatureOptions& options;
  double length;
  BBox3d box;
  TopProfile top;
};

EdgeVerdict judge_edge(const Context& c, Index e) {
  const MeshEdge& me = c.adjacency.edges[e];
  const Vec3d& p0 = c.mesh.positions[me.v0];
  const Vec3d& p1 = c.mesh.positions[me.v1];
  const double tol = kPlaneTolerance * c.length;
  const double wl = c.options.waterline_z;
  if (std::isfinite(wl) && std::abs(p0.z - wl) <= tol && std::abs(p1.z - wl) <= tol) {
    return {BoundaryKind::kWaterline, false};
  }
  if (std::abs(p0.y) <= tol && std::abs(p1.y) <= tol) return {BoundaryKind::kCentrePlane, false};

  const Face& face = c.mesh.faces[me.first_slot / 4];
  const Vec3d d = p1 - p0;
  const Vec3d n = face_normal(c.mesh.positions, face);
  EdgeVerdict v;
  v.transom_candidate =
      std::abs(d.x) <= kTransomMaxDx * norm(d) && std::abs(n.x) < kTransomMaxFaceNx;
  const double zmid = 0.5 * (p0.z + p1.z);
  const bool face_below = face_centroid(c.mesh.positions, face).z < zmid;
  const double deck_tol = kDeckTolerance * c.box.extent().z;
  const bool on_top = std::max(p0.z, p1.z) >= c.top.top_near(p0.x, p1.x) - deck_tol;
  v.kind = face_below && on_top ? BoundaryKind::kDeckEdge : BoundaryKind::kHole;
  return v;
}

// Maximal runs [start, start + count) (indices mod n) of items that `same` joins. A closed
// sequence's runs start after a break; an unbroken closed sequence is one run with whole = true.
template <class Same>
std::vector<std::pair<std::size_t, std::size_t>> runs_of(std::size_t n, bool closed, Same same,
                                                         bool* whole) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  *whole = false;
  if (n == 0) return runs;
  std::size_t start = 0;
  if (closed) {
    std::size_t k = 0;
    while (k < n && same((k + n - 1) % n, k)) ++k;
    if (k == n) {
      *whole = true;
      runs.emplace_back(0, n);
      return runs;
    }
    start = k;
  }
  std::size_t run_start = start, count = 1;
  for (std::size_t i = 1; i < n; ++i) {
    const std::size_t prev = (start + i - 1) % n, cur = (start + i) % n;
    if (same(prev, cur)) {
      ++count;
    } else {
      runs.emplace_back(run_start, count);
      run_start = cur;
      count = 1;
    }
  }
  runs.emplace_back(run_start, count);
  return runs;
}

// Vertex i of a loop's run (edge i joins vertices[i] and vertices[i + 1], wrapping).
Index loop_vertex(const BoundaryLoop& loop, std::size_t i) {
  return loop.vertices[i % loop.vertices.size()];
}

// Whether the candidate edges [start, start + count) of the loop make a transom run.
bool is_transom_run(const Context& c, const BoundaryLoop& loop, std::size_t start,
                    std::size_t count) {
  BBox3d run;
  for (std::size_t i = 0; i <= count; ++i) run.add(c.mesh.positions[loop_vertex(loop, start + i)]);
  const double reach = kTransomEndReach * c.length;
  const bool at_end = run.hi.x <= c.box.lo.x + reach || run.lo.x >= c.box.hi.x - reach;
  return at_end && run.diagonal() >= kTransomMinSpan * c.length;
}

void classify_loop(const Context& c, const BoundaryLoop& loop, std::vector<BoundaryKind>& kind) {
  const std::size_t n = loop.edges.size();
  std::vector<EdgeVerdict> verdict(n);
  for (std::size_t i = 0; i < n; ++i) verdict[i] = judge_edge(c, loop.edges[i]);
  bool whole = false;
  const auto runs = runs_of(
      n, loop.closed,
      [&](std::size_t a, std::size_t b) {
        return verdict[a].transom_candidate == verdict[b].transom_candidate;
      },
      &whole);
  for (const auto& [start, count] : runs) {
    const bool transom = verdict[start].transom_candidate && is_transom_run(c, loop, start, count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t k = (start + i) % n;
      kind[loop.edges[k]] = transom ? BoundaryKind::kTransomEdge : verdict[k].kind;
    }
  }
}

double distance(const SurfaceMesh& mesh, Index a, Index b) {
  return norm(mesh.positions[a] - mesh.positions[b]);
}

}  // namespace

std::vector<BoundaryKind> classify_boundary_edges(const SurfaceMesh& mesh,
                                                  const EdgeAdjacency& adjacency,
                                                  const FeatureOptions& options, double length) {
  BBox3d box;
  for (const Vec3d& p : mesh.positions) box.add(p);
  const Context c{mesh, adjacency, options, length, box, TopProfile(mesh.positions, box)};
  std::vector<BoundaryKind> kind(adjacency.edges.size(), BoundaryKind::kHole);
  // Loops are few and short next to the mesh; serial keeps the run logic plain.
  for (const BoundaryLoop& loop : adjacency.boundary_loops) classify_loop(c, loop, kind);
  return kind;
}

std::vector<BoundaryRun> boundary_runs(const SurfaceMesh& mesh, const EdgeAdjacency& adjacency,
                                       std::span<const BoundaryKind> edge_kind) {
  std::vector<BoundaryRun> out;
  for (const BoundaryLoop& loop : adjacency.boundary_loops) {
    const std::size_t n = loop.edges.size();
    bool whole = false;
    const auto runs = runs_of(
        n, loop.closed,
        [&](std::size_t a, std::size_t b) {
          return edge_kind[loop.edges[a]] == edge_kind[loop.edges[b]];
        },
        &whole);
    for (const auto& [start, count] : runs) {
      BoundaryRun run;
      run.kind = edge_kind[loop.edges[start]];
      run.closed = whole;
      const std::size_t vertices = whole ? n : count + 1;
      for (std::size_t i = 0; i < vertices; ++i) {
        run.vertices.push_back(loop_vertex(loop, start + i));
      }
      for (std::size_t i = 0; i < count; ++i) {
        run.length +=
            distance(mesh, loop_vertex(loop, start + i), loop_vertex(loop, start + i + 1));
      }
      out.push_back(std::move(run));
    }
  }
  return out;
}

}  // namespace hm::detail
