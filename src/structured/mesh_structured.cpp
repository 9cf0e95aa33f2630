// The structured mesher's driver: plan -> rows -> grow -> zip -> caps -> relax -> refine ->
// repair border panels -> onto the edge curves -> orient -> report.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>

#include "core/error.h"
#include "core/parallel.h"
#include "structured/bridge_starts.h"
#include "structured/cap_ends.h"
#include "structured/close_border_gaps.h"
#include "structured/join_rows.h"
#include "structured/structured_steps.h"

namespace hm {
namespace structured {

// Vertices no face uses (nodes the border repairs merged away) leave the arrays; the faces and
// the knuckle edges are renumbered (vert_old2new).
void drop_unused_vertices(StructuredMesh& out) {
  SurfaceMesh& mesh = out.mesh;
  const std::size_t nv = mesh.vertex_count();
  std::vector<std::uint8_t> used(nv, 0);
  for (const Face& f : mesh.faces)
    for (int c = 0; c < corner_count(f); ++c) used[f[c]] = 1;
  for (const auto& e : out.knuckle_edges) used[e[0]] = used[e[1]] = 1;
  if (std::all_of(used.begin(), used.end(), [](std::uint8_t u) { return u != 0; })) return;
  std::vector<Index> vert_old2new(nv, kInvalid);
  Index next = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    vert_old2new[v] = next;
    mesh.positions[next] = mesh.positions[v];
    if (!mesh.vertex_patch.empty()) mesh.vertex_patch[next] = mesh.vertex_patch[v];
    if (!mesh.vertex_uv.empty()) mesh.vertex_uv[next] = mesh.vertex_uv[v];
    ++next;
  }
  mesh.positions.resize(next);
  if (!mesh.vertex_patch.empty()) mesh.vertex_patch.resize(next);
  if (!mesh.vertex_uv.empty()) mesh.vertex_uv.resize(next);
  for (Face& f : mesh.faces)
    for (int c = 0; c < corner_count(f); ++c) f[c] = vert_old2new[f[c]];
  for (auto& e : out.knuckle_edges) e = {vert_old2new[e[0]], vert_old2new[e[1]]};
}

}  // namespace structured

namespace {

using namespace structured;

// --panels with match_panels: within 3% of the target, in at most three meshing passes.
constexpr double kMatchTolerance = 0.03;
constexpr std::size_t kMatchPasses = 3;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double surface_area(const SurfaceMesh& m) {
  double a = 0;
  for (const Face& f : m.faces) a += face_area(m.positions, f);
  return a;
}

Metric make_metric(const SurfaceMesh& surface, const StructuredOptions& o) {
  Metric m;
  m.boxes = o.size_boxes;
  m.size = structured_sizes(surface, o);
  return m;
}

// F = sum of h n_h A over the faces, h the height along `up` above `top`: the volume under the
// surface, signed by its orientation. The panels and the surface they cover share it (and their
// open borders), so its sign compares their orientations. Heights from the surface's top (the
// waterplane where it was cut), so that a lid across the open top adds nothing: measured from
// the keel of a side meshed in the ship's frame, the lid's share nearly cancelled the rest.
double orientation_measure(const SurfaceMesh& m, const Vec3d& up, double top) {
  double f = 0;
  for (const Face& face : m.faces) {
    const Vec3d n = face_normal(m.positions, face);
    f += (dot(up, face_centroid(m.positions, face)) - top) * dot(up, n) *
         face_area(m.positions, face);
  }
  return f;
}

// The hull beyond the end stations (caps), strips between rows of different curve counts
// (joined rows), and slivers between row ends and the surface's border (fans): one block.
void close_ends(const SurfaceMesh& surface, const EdgeAdjacency& adjacency, const BBox3d& box,
                const FeatureSet& features, std::span<const Row> rows,
                std::span<const RowNodes> nodes, std::span<const StripFaces> strips,
                const Vec3d& up, const Metric& metric, const ZipOptions& zo, NodeLayout& layout,
                StructuredMesh& out) {
  SurfaceMesh& mesh = out.mesh;
  StructuredReport& rep = out.report;
  std::vector<NodeSlot>& slots = layout.slots;
  const std::vector<std::vector<Index>>& first_vertex = layout.first_vertex;
  // Row ends, for the border gaps (after the caps, which add none).
  std::vector<std::uint8_t> row_end(mesh.vertex_count(), 0);
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (std::size_t c = 0; c < rows[j].curves.size(); ++c) {
      row_end[first_vertex[j][c]] = 1;
      row_end[first_vertex[j][c] + nodes[j].s[c].size() - 1] = 1;
    }
  }
  const std::size_t before_caps = mesh.faces.size();
  const CapCounts caps =
      cap_ends(surface, adjacency, features, rows, nodes, first_vertex, metric, zo, mesh, slots);
  rep.cap_quads = caps.quads;
  rep.cap_triangles = caps.triangles;
  rep.transoms = caps.transoms;
  out.knuckle_edges.insert(out.knuckle_edges.end(), caps.knuckle_edges.begin(),
                           caps.knuckle_edges.end());
  rep.rows_unmatched += (caps.open[0] ? 1 : 0) + (caps.open[1] ? 1 : 0);
  std::vector<std::size_t> unpaired;
  for (std::size_t j = 0; j < strips.size(); ++j)
    if (strips[j].unmatched) unpaired.push_back(j);
  const JoinCounts joined = join_rows(surface, adjacency, rows, nodes, first_vertex, unpaired,
                                      metric, zo, caps.open, mesh, slots);
  rep.rows_unmatched -= joined.closed.size() + joined.ends_closed;
  rep.rows_joined = joined.closed.size();
  rep.curve_caps = joined.caps;
  const GapCounts gaps = close_border_gaps(surface, adjacency, row_end, up, metric, mesh, slots);
  rep.border_gaps = gaps.gaps;
  rep.cap_triangles += gaps.triangles;
  if (mesh.faces.size() > before_caps) {
    BlockReport br;
    br.id = static_cast<Index>(rep.blocks.size());
    br.lower = "hull ends and joined rows";
    br.upper = "stations " + std::to_string(0) + " and " + std::to_string(rows.size() - 1);
    br.x0 = box.lo.x;
    br.x1 = box.hi.x;
    mesh.face_block.resize(mesh.faces.size(), br.id);
    rep.blocks.push_back(br);
  }
}

// One meshing pass at the given sizes: plan -> rows -> grow -> zip -> caps -> relax -> refine ->
// repair border panels -> onto the edge curves -> wedges -> non-convex quads -> folded pairs ->
// orient.
StructuredMesh mesh_with(std::span<const Patch> patches, const SurfaceMesh& surface,
                         const EdgeAdjacency& adjacency, const HullQuery& query,
                         const FeatureSet& features, const StructuredOptions& options,
                         const Metric& metric) {
  using clock = std::chrono::steady_clock;
  StructuredMesh out;
  StructuredReport& rep = out.report;
  auto t = clock::now();
  rep.size = metric.size;
  const StationPlan plan = plan_stations(query, features, surface, metric, options);
  rep.stations = plan.x.size();
  rep.cut_stations = plan.cuts;
  rep.seconds_plan = seconds_since(t);

  t = clock::now();
  const std::vector<Row> rows =
      extract_rows(query, surface, adjacency, features, options.planes, plan, metric);
  rep.seconds_rows = seconds_since(t);

  t = clock::now();
  std::vector<double> row_seconds;
  const std::vector<RowNodes> nodes = grow_rows(rows, &row_seconds);
  SurfaceMesh& mesh = out.mesh;
  NodeLayout layout = place_nodes(rows, nodes, mesh);
  std::vector<NodeSlot>& slots = layout.slots;
  const std::vector<std::vector<Index>>& first_vertex = layout.first_vertex;
  const ZipOptions zo{options.min_opposite_ratio, options.max_warp};
  const std::vector<std::vector<StartBridge>> bridges =
      bridge_starts(surface, adjacency, rows, first_vertex, metric,
                    kPlaneTolerance * query.length_scale(), mesh, slots);
  const std::vector<StripFaces> strips =
      zip_strips(rows, nodes, first_vertex, bridges, mesh.positions, zo, row_seconds);

  rep.seconds_grow = seconds_since(t);
  commit_strips(rows, strips, out);

  close_ends(surface, adjacency, query.bbox(), features, rows, nodes, strips,
             options.waterplane_normal, metric, zo, layout, out);

  t = clock::now();
  relax_nodes(rows, slots, mesh.faces, mesh.positions, options.relax_passes);
  rep.quality_moves = improve_nodes(rows, slots, mesh.faces, mesh.positions, options.relax_passes);
  rep.seconds_relax = seconds_since(t);
  refine_nodes(patches, rows, slots, 1e-10 * query.length_scale(), metric, mesh);
  if (options.repair_border_panels) {
    const BorderRepairCounts b = repair_border_panels(query, slots, out.knuckle_edges, mesh);
    rep.border_distorted = b.distorted;
    rep.border_removed = b.removed;
    rep.border_extended = b.extended;
    rep.border_split = b.split;
  }
  rep.edge_snaps =
      snap_to_edge_curves(patches, surface, features, rows, slots, out.knuckle_edges,
                          query.length_scale(), options.waterplane_normal, metric, mesh);
  rep.nodes_welded = weld_coincident_nodes(out.knuckle_edges, mesh);
  if (options.repair_border_panels) {
    rep.wedges_collapsed =
        collapse_wedges(slots, out.knuckle_edges, options.min_opposite_ratio, mesh);
  }
  rep.non_convex_split = split_non_convex(mesh);
  rep.folds_flipped = unfold_triangles(out.knuckle_edges, mesh);
  if (options.pair_triangles) rep.triangles_paired = pair_triangles(out.knuckle_edges, zo, mesh);

  drop_unused_vertices(out);
  // The blocks' panel counts, as the repairs left them (a block's id is its place in the list).
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    BlockReport& b = rep.blocks[mesh.face_block[f]];
    ++(is_triangle(mesh.faces[f]) ? b.triangles : b.quads);
  }

  // Provenance, then one orientation for all: that of the surface.
  mesh.face_patch.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    mesh.face_patch[f] = mesh.vertex_patch[mesh.faces[f][0]];
  const Vec3d& up = options.waterplane_normal;
  double top = -std::numeric_limits<double>::infinity();
  for (const Vec3d& p : surface.positions) top = std::max(top, dot(up, p));
  if ((orientation_measure(mesh, up, top) > 0) != (orientation_measure(surface, up, top) > 0)) {
    for (Face& f : mesh.faces) {
      if (is_triangle(f))
        std::swap(f[1], f[2]);
      else
        std::swap(f[1], f[3]);
    }
  }
  for (const Face& f : mesh.faces) ++(is_triangle(f) ? rep.triangles : rep.quads);
  return out;
}

}  // namespace

StructuredMesh mesh_to_count(const std::function<StructuredMesh(const Vec3d&)>& mesh_at, Vec3d size,
                             const StructuredOptions& options) {
  StructuredMesh out = mesh_at(size);
  const std::size_t first = out.mesh.face_count();
  const bool from_count = !(options.size.x > 0 && options.size.y > 0 && options.size.z > 0);
  std::size_t passes = 1;
  while (options.match_panels && from_count && passes < kMatchPasses) {
    const double ratio =
        static_cast<double>(out.mesh.face_count()) / static_cast<double>(options.target_panels);
    if (std::abs(ratio - 1) <= kMatchTolerance || !(ratio > 0)) break;
    size = size * std::sqrt(ratio);
    const StructuredReport before = out.report;
    out = mesh_at(size);
    // The stage times are of every pass.
    out.report.seconds_plan += before.seconds_plan;
    out.report.seconds_rows += before.seconds_rows;
    out.report.seconds_grow += before.seconds_grow;
    out.report.seconds_relax += before.seconds_relax;
    ++passes;
  }
  out.report.size_passes = passes;
  out.report.first_pass_faces = first;
  return out;
}

StructuredMesh mesh_structured(std::span<const Patch> patches, const SurfaceMesh& surface,
                               const EdgeAdjacency& adjacency, const HullQuery& query,
                               const FeatureSet& features, const StructuredOptions& options) {
  Metric metric = make_metric(surface, options);
  return mesh_to_count(
      [&](const Vec3d& size) {
        metric.size = size;
        return mesh_with(patches, surface, adjacency, query, features, options, metric);
      },
      metric.size, options);
}

Vec3d structured_sizes(const SurfaceMesh& surface, const StructuredOptions& o) {
  if (o.size.x > 0 && o.size.y > 0 && o.size.z > 0) return o.size;
  if (o.target_panels < 4) throw UsageError("structured: --panels must be at least 4");
  const double h = std::sqrt(surface_area(surface) / static_cast<double>(o.target_panels));
  if (!(h > 0)) throw GeometryError("structured: the hull surface has no area");
  return {h, h, h};
}

StationList plan_structured_stations(const SurfaceMesh& surface, const HullQuery& query,
                                     const FeatureSet& features, const StructuredOptions& options) {
  const StationPlan plan =
      plan_stations(query, features, surface, make_metric(surface, options), options);
  return {plan.x, plan.border};
}

}  // namespace hm
