#include "tessellate/tessellate.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>
#include <string>

#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"
#include "tessellate/chord_error.h"
#include "tessellate/degenerate.h"
#include "tessellate/initial_grid.h"
#include "tessellate/refine_butterfly.h"
#include "tessellate/sample_normals.h"
#include "tessellate/trim.h"

namespace hm {
namespace {

constexpr double kDefaultEdgeFraction = 1.0 / 100;  // edge_length = L / 100
constexpr double kDefaultChordFraction = 1e-4;      // chord_tolerance = 1e-4 L
// Boundary vertices closer than this fraction of the chord tolerance are one point (collapsed
// edges, seams): far below any edge of the mesh, far above the round-off of a shared point.
constexpr double kMergeFraction = 0.1;
constexpr int kMinClosedCells = 3;
// A triangle whose area is below this fraction of its longest edge squared has zero area (its
// smallest angle is below about 1e-7 degrees... far below any real sliver of the refinement).
constexpr double kZeroAreaFraction = 1e-9;
// A patch is sheared when its grid has this many times the cells its area needs (cells of edge
// h: area / h^2) and at least kShearMinCells: its parameter lines run side by side in 3D
// somewhere. A patch tapering to a point needs about twice; ship_449's keel plate (DE 8385), a
// four-sided patch with two sides almost in line, needed 48 times.
constexpr double kShearRatio = 4;
constexpr double kShearMinCells = 64;
// ... and, unless its parametrisation folds (below), at least this many edges wide on average
// (area / longest side). A narrower strip has little inside to thin, and the merge's overlap
// removal finds a strip lying on its neighbour by the grid's inner vertices (npl_round_bilge's
// keel strips, 0.4 to 1.5 edges wide, overlap their neighbours at the stern and merge cleanly
// only on the grid).
constexpr double kShearMinWidth = 2;
// A fold: su x sv against its mean over more than this share of |su x sv| (sample_normals).
// ship_449's keel plate folds over 5e-4 of its Jacobian; the collapsed sides of kcs's stern
// patches read as 1e-5 and less.
constexpr double kFoldShare = 1e-4;
constexpr int kSideSamples = 16;  // per side, for its length

// The normal samples of a sheared patch, or nothing: its grid has kShearRatio times the cells its
// area needs, and it is kShearMinWidth edges wide or its Jacobian folds (su x sv against its mean
// over more than kFoldShare of |su x sv|: a grid of it would cross itself).
std::optional<NormalSamples> sheared_samples(const Patch& p, const GridLines& lines, double h) {
  const double cells = double(lines.u.size() - 1) * double(lines.v.size() - 1);
  if (cells < kShearMinCells) return std::nullopt;
  const double area = patch_extent(p).grid_area;
  if (!(area > 0) || cells <= kShearRatio * area / (h * h)) return std::nullopt;
  const NurbsSurface& s = p.surface;
  const double longest_side = std::max({iso_line_length(s, true, s.v0, s.u0, s.u1, kSideSamples),
                                        iso_line_length(s, true, s.v1, s.u0, s.u1, kSideSamples),
                                        iso_line_length(s, false, s.u0, s.v0, s.v1, kSideSamples),
                                        iso_line_length(s, false, s.u1, s.v0, s.v1, kSideSamples)});
  NormalSamples ns = sample_normals(s);
  const double len = norm(ns.sum);
  const bool folds = len > 0 && ns.share_beyond(ns.sum / len, 0) > kFoldShare;
  if (area >= kShearMinWidth * h * longest_side || folds) return ns;
  return std::nullopt;
}

struct PatchResult {
  PatchMesh mesh;
  std::vector<double> chord;
};

PatchResult mesh_patch(const Patch& p, const TessellateOptions& o) {
  const NurbsSurface& s = p.surface;
  const double merge_tol = kMergeFraction * o.chord_tolerance;
  PatchResult r;
  std::optional<NormalSamples> sheared;
  if (p.loops.empty()) {
    const Closure c = detect_closure(s, merge_tol);
    const GridLines lines = grid_lines(s, o.edge_length, o.limits, c.closed_u ? kMinClosedCells : 1,
                                       c.closed_v ? kMinClosedCells : 1);
    if (!c.closed_u && !c.closed_v) sheared = sheared_samples(p, lines, o.edge_length);
    if (sheared) {
      // The domain's sides as one loop, the grid thinned inside: a structured grid would crowd.
      r.mesh = trimmed_mesh(p, lines, o.edge_length, o.chord_tolerance, &*sheared);
    } else {
      r.mesh = grid_mesh(s, lines);
      join_seams(r.mesh, lines.u.size(), lines.v.size(), c);
      join_collapsed(r.mesh, lines.u.size(), lines.v.size(), detect_collapsed(s, merge_tol));
      compact_vertices(r.mesh);
    }
  } else {
    const GridLines lines = grid_lines(s, o.edge_length, o.limits);
    sheared = sheared_samples(p, lines, o.edge_length);
    r.mesh =
        trimmed_mesh(p, lines, o.edge_length, o.chord_tolerance, sheared ? &*sheared : nullptr);
  }
  const CollapsedSides collapsed = detect_collapsed(s, merge_tol);
  const ChordSampling sampling =
      sheared ? ChordSampling::kFromTriangle : ChordSampling::kParametric;
  refine_butterfly(s, r.mesh,
                   {o.chord_tolerance, o.max_area, o.max_refine_levels, o.butterfly_tension,
                    merge_tol, collapsed, sampling});
  merge_coincident(r.mesh, merge_tol);
  remove_zero_area(r.mesh, kZeroAreaFraction);
  if (o.measure_chord) r.chord = measure_chord_error(s, r.mesh, collapsed, sampling);
  return r;
}

BBox3d control_box(std::span<const Patch> patches) {
  BBox3d b;
  for (const Patch& p : patches)
    for (const Vec3d& q : p.surface.points) b.add(q);
  return b;
}

}  // namespace

TessellateOptions resolve_options(std::span<const Patch> patches, const TessellateOptions& in) {
  TessellateOptions o = in;
  const Vec3d e = control_box(patches).extent();
  const double length = std::max({e.x, e.y, e.z});
  const bool need = !(o.edge_length > 0) || !(o.chord_tolerance > 0);
  if (need && !(length > 0))
    throw UsageError("tessellate: no hull size to derive the edge length and tolerance from");
  if (!(o.edge_length > 0)) o.edge_length = kDefaultEdgeFraction * length;
  if (!(o.chord_tolerance > 0)) o.chord_tolerance = kDefaultChordFraction * length;
  if (!(o.max_area > 0)) o.max_area = o.edge_length * o.edge_length;
  o.max_refine_levels = std::clamp(o.max_refine_levels, 0, o.limits.max_refine_depth);
  return o;
}

double edge_length_for_triangles(std::span<const Patch> patches, std::size_t triangles) {
  if (triangles == 0) throw UsageError("tessellate: the triangle target must be positive");
  std::vector<double> area(patches.size(), 0.0);
  // A count of triangles does not need the area to 1e-11: the estimate costs about half.
  parallel_for_each_item(
      patches.size(), [&](std::size_t i) { area[i] = patch_area(patches[i], kAreaEstimateTol); });
  double total = 0;
  for (double a : area) total += a;
  // Two triangles per grid quad of edge h: N = 2 A / h^2.
  return std::sqrt(2 * total / double(triangles));
}

Tessellation tessellate(std::span<const Patch> patches, const TessellateOptions& options,
                        Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const TessellateOptions o = resolve_options(patches, options);
  progress.stage("tessellate");
  const std::size_t n = patches.size();
  std::vector<PatchResult> results(n);
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  parallel_for_each_item(n, [&](std::size_t i) {
    if (progress.cancelled()) return;
    try {
      results[i] = mesh_patch(patches[i], o);
    } catch (const GeometryError& e) {
      throw GeometryError(std::string(e.what()) + " (patch " + std::to_string(i) + ", DE " +
                          std::to_string(patches[i].de) + ")");
    }
    const std::size_t k = ++done;
    if (progress_mutex.try_lock()) {  // the callback runs on one thread at a time
      progress.update(double(k) / double(n));
      progress_mutex.unlock();
    }
  });
  if (progress.cancelled()) throw UsageError("tessellation cancelled");

  // Exclusive scan of the per-patch counts: each patch writes its own slice of the output.
  std::vector<std::size_t> v_off(n + 1, 0), t_off(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    v_off[i + 1] = v_off[i] + results[i].mesh.vertex_count();
    t_off[i + 1] = t_off[i] + results[i].mesh.tri_count();
  }
  if (t_off[n] > o.limits.max_triangles || v_off[n] >= kInvalid)
    throw LimitError("tessellate: " + std::to_string(t_off[n]) +
                     " triangles exceed the triangle limit; raise the edge length");
  Tessellation out;
  SurfaceMesh& m = out.mesh;
  m.positions.resize(v_off[n]);
  m.vertex_patch.resize(v_off[n]);
  m.vertex_uv.resize(v_off[n]);
  m.faces.resize(t_off[n]);
  m.face_patch.resize(t_off[n]);
  if (o.measure_chord) out.chord_error.resize(t_off[n]);
  parallel_for_each_item(n, [&](std::size_t i) {
    const PatchMesh& pm = results[i].mesh;
    const PatchId pid = PatchId(i);
    std::copy(pm.xyz.begin(), pm.xyz.end(), m.positions.begin() + v_off[i]);
    std::copy(pm.uv.begin(), pm.uv.end(), m.vertex_uv.begin() + v_off[i]);
    std::fill_n(m.vertex_patch.begin() + v_off[i], pm.vertex_count(), pid);
    const Index base = Index(v_off[i]);
    for (std::size_t t = 0; t < pm.tri_count(); ++t) {
      const Tri& tr = pm.tris[t];
      m.faces[t_off[i] + t] = {base + tr[0], base + tr[1], base + tr[2], kInvalid};
    }
    std::fill_n(m.face_patch.begin() + t_off[i], pm.tri_count(), pid);
    if (o.measure_chord) {
      std::copy(results[i].chord.begin(), results[i].chord.end(),
                out.chord_error.begin() + t_off[i]);
    }
  });
  TessellateSummary& sum = out.summary;
  sum.patches = n;
  sum.triangles = t_off[n];
  sum.vertices = v_off[n];
  for (double e : out.chord_error) sum.max_chord_error = std::max(sum.max_chord_error, e);
  sum.chord_tolerance = o.chord_tolerance;
  sum.edge_length = o.edge_length;
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  progress.update(1.0);
  return out;
}

}  // namespace hm
