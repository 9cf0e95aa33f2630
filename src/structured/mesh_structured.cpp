// The structured mesher's driver: plan -> rows -> grow -> zip -> caps -> relax -> refine ->
// orient -> report.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "core/error.h"
#include "core/parallel.h"
#include "query/surface_refine.h"
#include "structured/cap_ends.h"
#include "structured/close_border_gaps.h"
#include "structured/join_rows.h"
#include "structured/structured_steps.h"

namespace hm {
namespace {

using namespace structured;

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
  if (o.size.x > 0 && o.size.y > 0 && o.size.z > 0) {
    m.size = o.size;
  } else {
    if (o.target_panels < 4) throw UsageError("structured: --panels must be at least 4");
    const double h = std::sqrt(surface_area(surface) / static_cast<double>(o.target_panels));
    if (!(h > 0)) throw GeometryError("structured: the hull surface has no area");
    m.size = {h, h, h};
  }
  return m;
}

// The labels two curves share, in the order along the first (a label out of order on the second
// is dropped: the strip cannot follow it).
std::vector<BreakLabel> common_labels(const RowCurve& a, const RowCurve& b) {
  std::vector<BreakLabel> out;
  std::size_t from = 0;
  for (const Breakpoint& x : a.breaks) {
    for (std::size_t k = from; k < b.breaks.size(); ++k) {
      if (b.breaks[k].label == x.label) {
        out.push_back(x.label);
        from = k + 1;
        break;
      }
    }
  }
  return out;
}

double break_s(const RowCurve& c, const BreakLabel& l) {
  for (const Breakpoint& b : c.breaks)
    if (b.label == l) return b.s;
  return -1;
}

// Vertex ids and arc lengths of a row curve's nodes within [s0, s1].
void chain(const std::vector<double>& s, Index first_vertex, double s0, double s1,
           std::vector<Index>& ids, std::vector<double>& frac) {
  ids.clear();
  frac.clear();
  const double len = std::max(s1 - s0, 1e-300);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] < s0 - 1e-9 || s[i] > s1 + 1e-9) continue;
    ids.push_back(first_vertex + static_cast<Index>(i));
    frac.push_back((s[i] - s0) / len);
  }
}

// F = sum of z n_z A over the faces: the volume under the surface, signed by its orientation.
// The panels and the surface they cover share it (and their open borders), so its sign compares
// their orientations.
double orientation_measure(const SurfaceMesh& m) {
  double f = 0;
  for (const Face& face : m.faces) {
    const Vec3d n = face_normal(m.positions, face);
    f += face_centroid(m.positions, face).z * n.z * face_area(m.positions, face);
  }
  return f;
}

}  // namespace

StructuredMesh mesh_structured(std::span<const Patch> patches, const SurfaceMesh& surface,
                               const HullQuery& query, const FeatureSet& features,
                               const StructuredOptions& options) {
  using clock = std::chrono::steady_clock;
  StructuredMesh out;
  StructuredReport& rep = out.report;
  auto t = clock::now();
  const Metric metric = make_metric(surface, options);
  rep.size = metric.size;
  const StationPlan plan = plan_stations(query, features, surface, metric, options);
  rep.stations = plan.x.size();
  rep.cut_stations = plan.cuts;
  rep.seconds_plan = seconds_since(t);

  t = clock::now();
  const std::vector<Row> rows =
      extract_rows(query, surface, features, options.planes, plan, metric);
  rep.seconds_rows = seconds_since(t);

  t = clock::now();
  std::vector<double> row_seconds;
  const std::vector<RowNodes> nodes = grow_rows(rows, &row_seconds);

  // Vertices, row by row, curve by curve, node by node.
  SurfaceMesh& mesh = out.mesh;
  std::vector<NodeSlot> slots;
  std::vector<std::vector<Index>> first_vertex(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (std::size_t c = 0; c < rows[j].curves.size(); ++c) {
      const RowCurve& curve = rows[j].curves[c];
      first_vertex[j].push_back(static_cast<Index>(mesh.positions.size()));
      for (double s : nodes[j].s[c]) {
        bool on_break = false;
        for (const Breakpoint& b : curve.breaks) on_break = on_break || std::abs(b.s - s) < 1e-12;
        std::size_t k;
        double f;
        curve.locate(s, k, f);
        mesh.positions.push_back(curve.at(s));
        mesh.vertex_patch.push_back(f < 0.5 ? curve.patch[k] : curve.patch[k + 1]);
        mesh.vertex_uv.push_back(curve.patch[k] == curve.patch[k + 1]
                                     ? curve.uv[k] * (1 - f) + curve.uv[k + 1] * f
                                     : (f < 0.5 ? curve.uv[k] : curve.uv[k + 1]));
        slots.push_back({static_cast<Index>(j), static_cast<Index>(c), s,
                         rows[j].border || on_break, on_break});
      }
    }
  }

  // Columns: the strips between consecutive border rows; a block is a column's share between
  // two labels every row of it carries.
  std::vector<std::size_t> column_of(rows.size(), 0);
  std::vector<std::size_t> column_start;
  for (std::size_t j = 0, p = 0; j + 1 < rows.size(); ++j) {
    if (rows[j].border && j > 0) ++p;
    if (rows[j].border) column_start.push_back(j);
    column_of[j] = p;
  }
  struct StripFaces {
    std::vector<Face> faces;
    std::vector<std::uint32_t> block_key;  // (column << 16) | (curve << 8) | segment
    std::vector<std::array<Index, 2>> knuckle_edges;
    std::map<std::uint32_t, std::array<std::string, 2>> block_names;
    ZipCounts counts;
    bool unmatched = false;
    double seconds = 0;  // growing its forward row and zipping it
  };
  std::vector<StripFaces> strips(rows.size() > 0 ? rows.size() - 1 : 0);
  const ZipOptions zo{options.min_opposite_ratio, options.max_warp};
  parallel_for_each_item(strips.size(), [&](std::size_t j) {
    const auto t0 = std::chrono::steady_clock::now();
    StripFaces& sf = strips[j];
    struct Stamp {
      StripFaces& sf;
      double grown;
      std::chrono::steady_clock::time_point t0;
      ~Stamp() {
        sf.seconds =
            grown + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      }
    } stamp{sf, row_seconds[j + 1], t0};
    const Row& a = rows[j];
    const Row& b = rows[j + 1];
    if (a.curves.size() != b.curves.size() || a.curves.empty()) {
      sf.unmatched = true;
      return;
    }
    // The labels every row of this column carries, per curve.
    const std::size_t p = column_of[j];
    const std::size_t j0 = column_start[p];
    std::vector<Index> ids_a, ids_b;
    std::vector<double> fa, fb;
    for (std::size_t c = 0; c < a.curves.size(); ++c) {
      std::vector<BreakLabel> column = rows[j0].curves.size() > c
                                           ? common_labels(rows[j0].curves[c], a.curves[c])
                                           : std::vector<BreakLabel>{};
      const std::vector<BreakLabel> labels = common_labels(a.curves[c], b.curves[c]);
      for (std::size_t q = 0; q + 1 < labels.size(); ++q) {
        const double a0 = break_s(a.curves[c], labels[q]), a1 = break_s(a.curves[c], labels[q + 1]);
        const double b0 = break_s(b.curves[c], labels[q]), b1 = break_s(b.curves[c], labels[q + 1]);
        chain(nodes[j].s[c], first_vertex[j][c], a0, a1, ids_a, fa);
        chain(nodes[j + 1].s[c], first_vertex[j + 1][c], b0, b1, ids_b, fb);
        if (ids_a.size() < 1 || ids_b.size() < 1) continue;
        const std::size_t before = sf.faces.size();
        const ZipCounts n = zip_chains(ids_a, fa, ids_b, fb, mesh.positions, zo, sf.faces);
        sf.counts.quads += n.quads;
        sf.counts.triangles += n.triangles;
        sf.counts.split += n.split;
        // The block: how many of the column's labels lie at or below this segment's start.
        std::size_t seg = 0;
        for (const BreakLabel& l : column) {
          if (break_s(a.curves[c], l) <= a0 + 1e-12) ++seg;
        }
        const std::uint32_t key =
            static_cast<std::uint32_t>((p << 16) | (c << 8) | std::min<std::size_t>(seg, 255));
        sf.block_key.insert(sf.block_key.end(), sf.faces.size() - before, key);
        if (seg >= 1 && seg < column.size()) {
          sf.block_names[key] = {to_string(column[seg - 1]), to_string(column[seg])};
        }
        if (labels[q].kind == BreakKind::kKnuckle) {
          sf.knuckle_edges.push_back({ids_a.front(), ids_b.front()});
        }
      }
    }
  });
  rep.seconds_grow = seconds_since(t);

  // Commit the strips in row order; blocks numbered by their keys in ascending order.
  std::map<std::uint32_t, Index> block_ids;
  for (const StripFaces& sf : strips)
    for (std::uint32_t k : sf.block_key) block_ids.emplace(k, 0);
  Index next_id = 0;
  for (auto& [key, id] : block_ids) id = next_id++;
  rep.blocks.resize(block_ids.size());
  for (const auto& [key, id] : block_ids) {
    BlockReport& br = rep.blocks[id];
    br.id = id;
    br.x0 = std::numeric_limits<double>::infinity();
    br.x1 = -br.x0;
  }
  for (std::size_t j = 0; j < strips.size(); ++j) {
    const StripFaces& sf = strips[j];
    for (const auto& [key, names] : sf.block_names) {
      BlockReport& br = rep.blocks[block_ids[key]];
      if (br.lower.empty()) {
        br.lower =
            (rows[j].curves.size() > 1 ? "curve " + std::to_string((key >> 8) & 255) + " " : "") +
            names[0];
        br.upper = names[1];
      }
    }
    if (sf.unmatched) ++rep.rows_unmatched;
    rep.split_twisted += sf.counts.split;
    for (std::size_t f = 0; f < sf.faces.size(); ++f) {
      const Index id = block_ids[sf.block_key[f]];
      BlockReport& br = rep.blocks[id];
      br.x0 = std::min(br.x0, rows[j].x);
      br.x1 = std::max(br.x1, rows[j + 1].x);
      ++(is_triangle(sf.faces[f]) ? br.triangles : br.quads);
      br.seconds += sf.seconds / static_cast<double>(sf.faces.size());
      mesh.faces.push_back(sf.faces[f]);
      mesh.face_block.push_back(id);
    }
    out.knuckle_edges.insert(out.knuckle_edges.end(), sf.knuckle_edges.begin(),
                             sf.knuckle_edges.end());
  }
  for (BlockReport& br : rep.blocks) {
    br.rows = 0;
    for (const Row& r : rows) br.rows += r.x >= br.x0 - 1e-12 && r.x <= br.x1 + 1e-12;
  }

  // The ends of the hull beyond the first and last stations.
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
      cap_ends(surface, features, rows, nodes, first_vertex, metric, zo, mesh, slots);
  rep.cap_quads = caps.quads;
  rep.cap_triangles = caps.triangles;
  rep.transoms = caps.transoms;
  out.knuckle_edges.insert(out.knuckle_edges.end(), caps.knuckle_edges.begin(),
                           caps.knuckle_edges.end());
  rep.rows_unmatched += caps.unmatched;
  std::vector<std::size_t> unpaired;
  for (std::size_t j = 0; j < strips.size(); ++j)
    if (strips[j].unmatched) unpaired.push_back(j);
  const std::vector<std::size_t> joined =
      join_rows(surface, rows, nodes, first_vertex, unpaired, metric, zo, mesh, slots);
  rep.rows_unmatched -= joined.size();
  rep.rows_joined = joined.size();
  const GapCounts gaps = close_border_gaps(surface, row_end, metric, mesh, slots);
  rep.border_gaps = gaps.gaps;
  rep.cap_triangles += gaps.triangles;
  if (mesh.faces.size() > before_caps) {
    BlockReport br;
    br.id = static_cast<Index>(rep.blocks.size());
    br.lower = "hull ends and joined rows";
    br.upper = "stations " + std::to_string(0) + " and " + std::to_string(rows.size() - 1);
    br.x0 = query.bbox().lo.x;
    br.x1 = query.bbox().hi.x;
    for (std::size_t f = before_caps; f < mesh.faces.size(); ++f) {
      ++(is_triangle(mesh.faces[f]) ? br.triangles : br.quads);
    }
    mesh.face_block.resize(mesh.faces.size(), br.id);
    rep.blocks.push_back(br);
  }

  t = clock::now();
  relax_nodes(rows, slots, mesh.faces, mesh.positions, options.relax_passes);
  rep.quality_moves = improve_nodes(rows, slots, mesh.faces, mesh.positions, options.relax_passes);
  rep.seconds_relax = seconds_since(t);

  // Row nodes back onto the exact NURBS (still on their station plane): they were placed on the
  // section polylines, within the triangulation's chord error.
  const double tol = 1e-10 * query.length_scale();
  std::vector<query::ParamDomain> domains(patches.size());
  parallel_for_each_item(patches.size(), [&](std::size_t p) {
    domains[p] = query::make_domain(patches[p].surface, tol);
  });
  parallel_for(0, slots.size(), [&](std::size_t v) {
    const NodeSlot& n = slots[v];
    // Cap nodes lie on the surface's boundary, breakpoints on a section point, the waterline or a
    // knuckle: refining would only move them off it.
    if (n.row == kInvalid || n.on_break) return;
    const RowCurve& c = rows[n.row].curves[n.curve];
    std::size_t k;
    double f;
    c.locate(n.s, k, f);
    // A segment across a patch border: refined on the nearer point's patch, from its (u, v)
    // alone (the other end's belongs to another surface).
    const bool same = c.patch[k] == c.patch[k + 1];
    const std::size_t near = same || f < 0.5 ? k : k + 1;
    const PatchId p = c.patch[near];
    const query::RefinedPlanePoint r = query::refine_plane_edge(
        patches[p].surface, domains[p], {1, 0, 0}, {rows[n.row].x, 0, 0}, c.uv[near],
        same ? c.uv[k + 1] : c.uv[near], same ? f : 0.0, mesh.positions[v], tol);
    // The curve's z range holds it: the waterplane cut snapped the surface's last vertices onto
    // the plane, and the exact NURBS can cross it a little way off, so a node near the waterline
    // would otherwise rise above it.
    if (r.converged &&
        squared_norm(r.point - mesh.positions[v]) < 1e-4 * metric.size.x * metric.size.x &&
        r.point.z <= c.z_max && r.point.z >= c.z_min) {
      mesh.positions[v] = r.point;
      mesh.vertex_uv[v] = r.uv;
      mesh.vertex_patch[v] = p;
    }
  });

  // Provenance, then one orientation for all: that of the surface.
  mesh.face_patch.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f)
    mesh.face_patch[f] = mesh.vertex_patch[mesh.faces[f][0]];
  if ((orientation_measure(mesh) > 0) != (orientation_measure(surface) > 0)) {
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

}  // namespace hm
