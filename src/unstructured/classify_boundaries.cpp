// Boundary kinds by the rules listed in classify_boundaries.h, then maximal runs per loop.
#include "unstructured/classify_boundaries.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>

#include "core/bbox.h"
#include "core/parallel.h"

namespace hm::detail {
namespace {

constexpr double kTransomMaxDx = 0.5;      // |dx| / |edge|: within 30 degrees of y-z plane
constexpr double kTransomMaxFaceNx = 0.7;  // |n_x| of the face along a transom edge
constexpr double kTransomEndReach = 0.25;  // of L, from either x end of the surface
constexpr double kTransomMinSpan = 0.01;   // of L, the diagonal of a transom run's box
constexpr double kDeckTolerance = 0.05;    // of the z extent, below the local top
constexpr int kProfileSlabs = 256;         // x slabs of the top profile
constexpr std::size_t kChunk = 1 << 16;    // faces per task of the top profile
constexpr double kEndShrink = 1e-6;        // of L, off each end of an edge's x range

// Whether some part of the surface with x in [lo, hi] stands above z (m, mesh frame).
struct TopQuestion {
  double lo, hi, z;
};

// Answers TopQuestions exactly, not widened by a slab either side: a deck edge that ends where
// the side beside it rises (a raised forecastle's end) has nothing above it up to the step. One
// pass over the faces lists, per slab of x, the faces standing higher than the lowest question
// touching that slab (on a clean hull, next to none); each question then clips the faces of its
// slabs, highest first, until one stands higher or none can.
class TopProfile {
 public:
  TopProfile(const SurfaceMesh& mesh, const BBox3d& box)
      : positions_(mesh.positions),
        faces_(mesh.faces),
        x0_(box.lo.x),
        inv_width_(kProfileSlabs / std::max(box.extent().x, std::numeric_limits<double>::min())) {}

  // Answers, in order (1: something stands higher).
  std::vector<std::uint8_t> higher_than(std::span<const TopQuestion> questions) const {
    std::vector<std::uint8_t> answer(questions.size(), 0);
    if (questions.empty()) return answer;
    std::vector<double> lowest(kProfileSlabs, std::numeric_limits<double>::infinity());
    for (const TopQuestion& t : questions) {
      for (int k = slab(t.lo); k <= slab(t.hi); ++k) lowest[k] = std::min(lowest[k], t.z);
    }
    const double lowest_any = *std::min_element(lowest.begin(), lowest.end());
    // Chunks of faces in parallel, each listing its own, joined in chunk order: the lists come
    // out in face order whatever the thread count.
    const std::size_t chunks = (faces_.size() + kChunk - 1) / kChunk;
    std::vector<std::vector<std::vector<Entry>>> part(chunks);
    parallel_for(
        0, chunks,
        [&](std::size_t c) {
          std::vector<std::vector<Entry>>& out = part[c];
          out.resize(kProfileSlabs);
          const std::size_t end = std::min(faces_.size(), (c + 1) * kChunk);
          for (std::size_t f = c * kChunk; f < end; ++f) {
            const Face& face = faces_[f];
            const int n = corner_count(face);
            double top = -std::numeric_limits<double>::infinity();
            for (int i = 0; i < n; ++i) top = std::max(top, positions_[face[i]].z);
            if (top <= lowest_any) continue;
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (int i = 0; i < n; ++i) {
              lo = std::min(lo, positions_[face[i]].x);
              hi = std::max(hi, positions_[face[i]].x);
            }
            for (int k = slab(lo), last = slab(hi); k <= last; ++k) {
              if (top > lowest[k]) out[k].push_back({top, static_cast<Index>(f)});
            }
          }
        },
        1, 2);
    std::vector<std::vector<Entry>> higher(kProfileSlabs);
    for (const auto& p : part) {
      for (int k = 0; k < kProfileSlabs; ++k)
        higher[k].insert(higher[k].end(), p[k].begin(), p[k].end());
    }
    for (std::vector<Entry>& list : higher) {
      std::sort(list.begin(), list.end(), [](const Entry& a, const Entry& b) {
        return a.top != b.top ? a.top > b.top : a.face < b.face;
      });
    }
    for (std::size_t q = 0; q < questions.size(); ++q) {
      const TopQuestion& t = questions[q];
      for (int k = slab(t.lo); k <= slab(t.hi) && !answer[q]; ++k) {
        for (const Entry& e : higher[k]) {
          if (e.top <= t.z) break;
          if (clipped_top(faces_[e.face], t.lo, t.hi) > t.z) {
            answer[q] = 1;
            break;
          }
        }
      }
    }
    return answer;
  }

 private:
  struct Entry {
    double top;  // highest z of the face
    Index face;
  };

  int slab(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - x0_) * inv_width_)), 0, kProfileSlabs - 1);
  }

  // Highest z of the face's part with x in [lo, hi] (-inf when none): z is linear on a flat
  // face, so it peaks at a corner of the clipped polygon, a corner in the interval or where an
  // edge crosses x = lo or x = hi.
  double clipped_top(const Face& f, double lo, double hi) const {
    double top = -std::numeric_limits<double>::infinity();
    const int n = corner_count(f);
    for (int i = 0; i < n; ++i) {
      const Vec3d& p = positions_[f[i]];
      const Vec3d& q = positions_[f[(i + 1) % n]];
      if (p.x >= lo && p.x <= hi) top = std::max(top, p.z);
      for (double x : {lo, hi}) {
        if ((p.x < x && x < q.x) || (q.x < x && x < p.x)) {
          top = std::max(top, p.z + (q.z - p.z) * ((x - p.x) / (q.x - p.x)));
        }
      }
    }
    return top;
  }

  std::span<const Vec3d> positions_;
  std::span<const Face> faces_;
  double x0_, inv_width_;
};

// What one boundary edge is by itself; transom edges need their run (see classify), and a deck
// edge candidate the answer to its question (nothing higher: deck edge, else hole).
struct EdgeVerdict {
  BoundaryKind kind = BoundaryKind::kHole;  // kind unless it joins a transom run
  bool transom_candidate = false;
  bool deck_candidate = false;
  TopQuestion question{};
};

struct Context {
  const SurfaceMesh& mesh;
  const EdgeAdjacency& adjacency;
  const FeatureOptions& options;
  double length;
  BBox3d box;
};

EdgeVerdict judge_edge(const Context& c, Index e) {
  const MeshEdge& me = c.adjacency.edges[e];
  const Vec3d& p0 = c.mesh.positions[me.v0];
  const Vec3d& p1 = c.mesh.positions[me.v1];
  const double tol = kPlaneTolerance * c.length;
  const double wl = c.options.waterline_z;
  const Vec3d& up = c.options.waterplane_normal;
  if (std::isfinite(wl) && std::abs(dot(up, p0) - wl) <= tol && std::abs(dot(up, p1) - wl) <= tol) {
    return {BoundaryKind::kWaterline, false};
  }
  if (std::abs(p0.y) <= tol && std::abs(p1.y) <= tol) return {BoundaryKind::kCentrePlane, false};

  const Face& face = c.mesh.faces[me.first_slot / 4];
  const Vec3d d = p1 - p0;
  const Vec3d n = face_normal(c.mesh.positions, face);
  EdgeVerdict v;
  v.transom_candidate =
      std::abs(d.x) <= kTransomMaxDx * norm(d) && std::abs(n.x) < kTransomMaxFaceNx;
  // Its face below it: the centroid below the edge's line, measured square to the edge (a
  // centroid below the edge's mid-height is not enough where the edge rises: the last sliver
  // of a fan at a patch tip lies along a rising sheer, its centroid near the upper end).
  const Vec3d off = face_centroid(c.mesh.positions, face) - p0;
  const double dd = dot(d, d);
  v.deck_candidate = (dd > 0 ? off - (dot(off, d) / dd) * d : off).z < 0;
  // Asked over the edge's own x range, shrunk off its ends by a hair so that a side rising from
  // the edge's end point does not count as standing above it (a range of one x stays one x).
  const double xa = std::min(p0.x, p1.x), xb = std::max(p0.x, p1.x);
  const double shrink = std::min(kEndShrink * c.length, 0.25 * (xb - xa));
  const double deck_tol = kDeckTolerance * c.box.extent().z;
  v.question = {xa + shrink, xb - shrink, std::max(p0.z, p1.z) + deck_tol};
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

void classify_loop(const Context& c, const BoundaryLoop& loop, std::span<const EdgeVerdict> verdict,
                   std::vector<BoundaryKind>& kind) {
  const std::size_t n = loop.edges.size();
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
  const Context c{mesh, adjacency, options, length, box};
  // Loops are few and short next to the mesh; serial keeps the run logic plain.
  // Judge every edge; ask the deck candidates' questions at once; classify loop by loop.
  std::vector<std::vector<EdgeVerdict>> verdicts;
  std::vector<TopQuestion> questions;
  for (const BoundaryLoop& loop : adjacency.boundary_loops) {
    std::vector<EdgeVerdict>& v = verdicts.emplace_back();
    for (Index e : loop.edges) {
      v.push_back(judge_edge(c, e));
      if (v.back().deck_candidate) questions.push_back(v.back().question);
    }
  }
  const std::vector<std::uint8_t> higher = TopProfile(mesh, box).higher_than(questions);
  std::size_t q = 0;
  for (std::vector<EdgeVerdict>& loop : verdicts) {
    for (EdgeVerdict& v : loop) {
      if (v.deck_candidate) v.kind = higher[q++] ? BoundaryKind::kHole : BoundaryKind::kDeckEdge;
    }
  }
  std::vector<BoundaryKind> kind(adjacency.edges.size(), BoundaryKind::kHole);
  for (std::size_t l = 0; l < verdicts.size(); ++l) {
    classify_loop(c, adjacency.boundary_loops[l], verdicts[l], kind);
  }
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
