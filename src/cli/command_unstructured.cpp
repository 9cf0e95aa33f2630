// hullmesh unstructured FILE -o panels.gdf --panels 4000: the paper's unstructured path. Import,
// tessellate fine, merge into one hull, find knuckles and boundaries, coarsen by edge collapse
// under the weighted quality index, and report the panels against the panel-code rules.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/floating_options.h"
#include "cli/knuckle_hints.h"
#include "cli/lid_output.h"
#include "cli/load_hull.h"
#include "cli/prepare_hull.h"
#include "cli/run_record.h"
#include "cli/validate_stage.h"
#include "core/bbox.h"
#include "core/error.h"
#include "core/parallel.h"
#include "io/write_mesh.h"
#include "mesh/adjacency.h"
#include "mesh/mirror_mesh.h"
#include "mesh/snap_centre_plane.h"
#include "quality/hydrostatics.h"
#include "quality/quality_report.h"
#include "query/hull_query.h"
#include "tessellate/tessellate.h"
#include "unstructured/coarsen.h"
#include "unstructured/cut_at_plane.h"
#include "unstructured/features.h"
#include "unstructured/measure_deviation.h"
#include "unstructured/merge.h"

namespace hm::cli {
namespace {

// Fine triangles per panel when the user does not size the fine mesh: enough for the collapses
// to choose from, bounded both ways. On the six shared hulls at 1,000, 4,000 and 16,000 panels,
// 6 per panel and at least 24,000 give the share rules of 8 and at least 40,000 within half a
// point, in 0.5-0.76 of the coarsening's time. Sparser fine vertices needed the panels' sample
// check (coarsen_state.cpp), the closest-point query's restart (a false deviation on chine
// hulls) and the parting of back-to-back panels (improve_panels.cpp) first; see the README.
constexpr std::size_t kFinePerPanel = 6;
constexpr std::size_t kFineMin = 24'000, kFineMax = 2'000'000;

struct UnstructuredCommand {
  std::string file, output, units;
  TessellateOptions tessellate;
  std::size_t triangles = 0;
  MergeOptions merge;
  FeatureOptions features;
  KnuckleHintArgs hints;
  CoarsenOptions coarsen;
  std::string weights;
  std::vector<std::string> point_sources, line_sources, box_sources;
  FloatingArgs floating;
  std::string symmetry = "auto";
  LidArgs lid;
};

void parse_sources(UnstructuredCommand& c) {
  for (const std::string& s : c.point_sources) {
    const auto v = parse_numbers(s, 5, "--source");
    c.coarsen.sources.push_back({SizeSource::Kind::kPoint, {v[0], v[1], v[2]}, {}, v[3], v[4]});
  }
  for (const std::string& s : c.line_sources) {
    const auto v = parse_numbers(s, 8, "--line-source");
    c.coarsen.sources.push_back(
        {SizeSource::Kind::kLine, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], v[7]});
  }
  for (const std::string& s : c.box_sources) {
    const auto v = parse_numbers(s, 8, "--box-source");
    c.coarsen.sources.push_back(
        {SizeSource::Kind::kBox, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], v[7]});
  }
  if (!c.weights.empty()) {
    const auto w = parse_numbers(c.weights, 4, "--weights");
    c.coarsen.weights = {w[0], w[1], w[2], w[3]};
  }
}

int run_unstructured(UnstructuredCommand c, const GlobalOptions& g) {
  require_waterplane("--lid", c.lid.wanted(), c.floating);
  require_waterplane("--above-waterline", c.floating.above_waterline > 0, c.floating);
  parse_sources(c);
  check_mesh_output(c.output);
  // The fine mesh: sized from the panel target unless the user sized it (over the whole hull, so
  // that a draft does not change the panel size).
  PrepareArgs pa;
  pa.file = c.file;
  pa.units = c.units;
  pa.floating = c.floating;
  if (c.floating.heel_deg != 0 && c.symmetry == "half") {
    throw UsageError("--symmetry half with --heel: a heeled hull is not symmetric about y = 0");
  }
  pa.cut_centre_plane = c.symmetry == "half";
  pa.tessellate = c.tessellate;
  pa.merge = c.merge;
  pa.features = c.features;
  pa.knuckle_hints = parse_knuckle_hints(c.hints);
  pa.quiet = g.quiet;
  pa.validate = g.validate;
  RunRecord& record = *g.record;
  pa.progress = &record.log;
  const std::size_t panels = c.coarsen.target_panels > 0 ? c.coarsen.target_panels : 4000;
  pa.fine_triangles = c.triangles;
  if (pa.fine_triangles == 0 && c.tessellate.edge_length <= 0) {
    pa.fine_triangles = std::clamp(kFinePerPanel * panels, kFineMin, kFineMax);
    // A merge left non-manifold at one resolution (issue 4's open failures, on kcs and npl) is
    // tried again denser; only the fine mesh the coarsening starts from changes. The failures
    // are coincidences of where the fine vertices fall (kcs.iges fails at 40,000, 44,000 and
    // 52,000-62,500 triangles and passes at 45,000-50,000), so a quarter more moves them enough;
    // doubling, as the structured mesher does, made every later stage twice as slow. Six
    // retries reach 3.8 times the first count.
    pa.finer_retries = 6;
    pa.retry_growth = 1.25;
  }
  PreparedHull ph;
  prepare_hull(pa, ph);
  // The report's NURBS hydrostatics, beside the coarsening.
  Hydrostatics nurbs_hydro;
  std::optional<BackgroundTask> nurbs_task;
  if (ph.floating) nurbs_task.emplace([&] { nurbs_hydro = nurbs_hydrostatics(ph); });
  const std::span<const Patch> patches = ph.patches();
  const std::optional<Floating>& floating = ph.floating;
  const Tessellation& t = ph.tessellation;
  const MergedSurface& merged = ph.merged;
  const double centre_tol = ph.centre_tol;
  const bool file_half = ph.file_half;
  const std::optional<PlaneCut>& cut = ph.waterplane_cut;
  const std::optional<PlaneCut>& centre_cut = ph.centre_cut;
  const SurfaceMesh& fine = ph.fine();
  const EdgeAdjacency& adj = ph.adjacency;
  const FeatureSet& features = ph.features;
  const double t_import = ph.seconds_import;
  const double t_features = ph.seconds_features;

  c.coarsen.fine_chord_error = t.summary.max_chord_error;
  // The report's hull query (17 ms of BVHs and corner projections on ship_449's 37,000 fine
  // triangles) reads only the fine surface: it is built beside the coarsening, whose rounds
  // leave the second core idle part of the time.
  std::unique_ptr<HullQuery> query;
  BackgroundTask query_task([&] { query = std::make_unique<HullQuery>(patches, fine); });
  const CoarsenedMesh panels_mesh = coarsen(patches, fine, adj, features, c.coarsen, record.log);
  const CoarsenReport& r = panels_mesh.report;
  // The panels; a half hull's open side exactly on y = 0 (its file may draw it a little off).
  SurfaceMesh coarse = panels_mesh.mesh;
  const std::size_t centre_snapped =
      file_half || centre_cut ? snap_to_centre_plane(coarse, centre_tol) : 0;
  // A sliver along the open side whose corners all ended on y = 0 has no area there (npl's
  // transom): it goes, and the open side runs along its other edges, in the same line.
  const std::size_t on_plane_dropped =
      file_half || centre_cut ? drop_centre_plane_faces(coarse) : 0;
  record.log.stage("report");
  const long long t2 = now_ns();
  query_task.wait();
  const DeviationMeasure dev = measure_deviation(*query, coarse);
  if (g.validate) {
    // The coarsening keeps every knuckle and boundary line (chords of it) and every boundary
    // loop, and stays within its deviation bound.
    InvariantOptions io;
    io.deviation = dev.max;
    io.deviation_where = dev.where;
    // The merge closed the patches' gaps by moving their borders: up to the widest gap there.
    io.max_deviation = r.max_deviation + merged.report.widest_gap_closed;
    io.feature_length_in = features.knuckle_length();
    for (const BoundaryRun& b : features.boundaries) io.feature_length_in += b.length;
    io.feature_length_out = edges_length(coarse, panels_mesh.feature_edges);
    io.boundary_loops_in = adj.boundary_loops.size();
    validate_stage(c.file, "coarsen", coarse, io);
  }

  // The full hull from a half, mirrored after coarsening (so both sides are panelled alike).
  const SurfaceMesh* output = &coarse;
  std::vector<std::array<Index, 2>> knuckle_edges = panels_mesh.feature_edges;
  std::optional<MirroredMesh> mirrored;
  if (c.symmetry == "full" && is_half_hull(coarse, centre_tol)) {
    mirrored = mirror_half_hull(coarse, centre_tol);
    output = &mirrored->mesh;
    const auto images = mirrored_edges(*mirrored, coarse.vertex_count(), panels_mesh.feature_edges);
    knuckle_edges.insert(knuckle_edges.end(), images.begin(), images.end());
  }
  if (g.validate && mirrored) validate_stage(c.file, "mirror", *output, {});
  QualityOptions qo;
  qo.knuckle_edges = knuckle_edges;
  qo.rules.min_triangle_angle_share = 0;
  if (floating) qo.waterline_z = 0;
  qo.uncut = !floating;  // no draft: the mesh ends at the deck edge
  // No panel may pass through another (a panel code cannot integrate over such a surface): a
  // hard rule of the report, and a warning naming the patches.
  report_surface_crossings(ph, g.quiet);
  measure_panel_crossings(c.file, patches, *output, g.quiet, qo);
  const QualityReport quality = assess_quality(*output, qo);
  // The mesh's hydrostatics against the exact NURBS at the same position: the direct measure of
  // the panels' geometric accuracy.
  std::optional<Hydrostatics> hydro_mesh, hydro_nurbs;
  if (floating) {
    nurbs_task->wait();
    const HydrostaticsPair h = compare_hydrostatics(*output, quality.half_hull, nurbs_hydro);
    hydro_mesh = h.mesh;
    hydro_nurbs = h.nurbs;
  }
  const double t_report = seconds_since(t2);

  MeshWriteOptions w;
  w.info.title = "hullmesh unstructured panels of " + file_name(c.file);
  // A half hull goes out with its symmetry flag wherever the format has one (a panel code
  // would otherwise take it for half a ship).
  w.info.symmetry.about_y0 = quality.half_hull;
  record.log.stage("write");
  // The lid, if asked for, from the finished wetted panels: its border is their waterline.
  const LidOutput lid = write_hull_and_lid(c.lid, c.output, *output, w);
  record.log.finish();
  record.input = c.file;
  record.outputs = {c.output};
  record.quality = quality_summary(quality, qo.rules);
  record.results = {{"panel_size_m", r.panel_size},       {"collapses", r.collapses},
                    {"target_reached", r.target_reached}, {"quality_index_mean", r.mean_quality},
                    {"quality_index_min", r.min_quality}, {"deviation_max_m", dev.max},
                    {"deviation_mean_m", dev.mean},       {"validated", g.validate}};
  if (hydro_mesh) record.results["hydrostatics"] = hydrostatics_summary(*hydro_mesh, &*hydro_nurbs);
  record_lid(lid, c.lid, record);

  if (!g.quiet) {
    std::printf("%s: %zu panels, %zu vertices (from %zu fine triangles)\n", c.output.c_str(),
                coarse.face_count(), r.vertices, r.input_faces);
    print_lid(lid, c.lid, c.output);
    if (mirrored) {
      std::printf("  mirrored about y = 0: %zu panels, %zu vertices in the full hull\n",
                  output->face_count(), output->vertex_count());
    }
    if (centre_cut) {
      std::printf(
          "  centre-plane cut of the fine mesh (the port half of a full hull): %zu faces split, "
          "%zu vertices snapped, %zu new on y = 0\n",
          centre_cut->report.faces_split, centre_cut->report.vertices_snapped,
          centre_cut->report.edges_cut);
    }
    if (centre_snapped > 0) {
      std::printf("  %zu vertices of the open side moved onto y = 0 (at most %.3g m)\n",
                  centre_snapped, centre_tol);
    }
    if (on_plane_dropped > 0) {
      std::printf("  %zu panels lying in the centre plane dropped\n", on_plane_dropped);
    }
    std::printf("  symmetry: %s\n", quality.half_hull
                                        ? "half hull, y = 0 flag written where the format has one"
                                        : "full hull, no flag");
    if (!r.target_reached) {
      std::printf(
          "  note: stopped above the panel target: no further collapse keeps the "
          "panels within the deviation bound and the shape rules\n");
    }
    std::printf(
        "  panel size h %.4g m, size level %.3g; %zu collapses in %zu rounds, %zu flips, "
        "%zu smoothing moves\n",
        r.panel_size, r.size_level, r.collapses, r.rounds, r.flips, r.smoothing_moves);
    std::printf("  refused: %zu by the deviation bound, %zu by the fold / sliver filters\n",
                r.rejected_deviation, r.rejected_shape);
    std::printf("  quality index: mean %.3f, min %.3f\n", r.mean_quality, r.min_quality);
    std::printf("  triangles with all angles >= 30 deg: %.1f%%; min angle %.1f deg\n",
                100 * quality.triangle_angle_share, quality.min_triangle_angle_deg);
    std::printf("  panels with every neighbour's area ratio < 2: %.1f%%; neighbour pairs: %.1f%%\n",
                100 * quality.area_ratio_share, 100 * quality.area_ratio_pair_share);
    std::printf(
        "  deviation from the NURBS: max %.3g m at (%.4g, %.4g, %.4g) (bound %.3g m), "
        "mean %.3g m\n",
        dev.max, dev.where.x, dev.where.y, dev.where.z, r.max_deviation, dev.mean);
    if (floating) {
      const PlaneCutReport& cr = cut->report;
      std::printf(
          "  floating: draft %.4g m above z = %.4g m, trim %.3g deg, heel %.3g deg (pivot x %.4g "
          "m); output frame: free surface z = 0\n",
          floating->draft, floating->baseline_z, floating->trim_deg, floating->heel_deg,
          floating->pivot_x);
      std::printf(
          "  waterplane cut of the fine mesh: %zu of %zu faces kept, %zu split, %zu vertices "
          "snapped onto the plane, %zu new on the waterline (%zu not refined to tolerance)\n",
          cr.faces_kept, cr.faces_in, cr.faces_split, cr.vertices_snapped, cr.edges_cut,
          cr.unconverged);
      print_hydrostatics(*hydro_mesh, *hydro_nurbs);
      std::printf("  free edges below the waterline: %zu\n", quality.topology.free_edges_below);
      if (floating->meshes_above()) {
        std::printf(
            "  above the waterline up to z = %.4g m: %zu panels end on the waterline from above, "
            "%zu cross it\n",
            floating->above_waterline, quality.topology.panels_above_on_waterline,
            quality.topology.panels_across_waterline);
      }
    }
    std::printf("  topology: %zu boundary loops, %zu non-manifold edges, orientation %s\n",
                quality.topology.boundary_loops, quality.topology.nonmanifold_edges,
                quality.topology.orientation_consistent ? "consistent" : "INCONSISTENT");
    std::printf(
        "  time: import %.3f s, tessellate %.3f s, merge %.3f s, features %.3f s, "
        "coarsen %.3f s (setup %.3f, collapse %.3f, improve %.3f), report %.3f s\n",
        t_import, t.summary.seconds, merged.report.seconds, t_features,
        r.seconds_setup + r.seconds_collapse + r.seconds_improve, r.seconds_setup,
        r.seconds_collapse, r.seconds_improve, t_report);
  }
  return 0;
}

}  // namespace

void register_unstructured(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto c = std::make_shared<UnstructuredCommand>();
  CLI::App* cmd =
      app.add_subcommand("unstructured",
                         "Panels by edge-collapse coarsening of the merged hull (the paper's "
                         "unstructured algorithm)");
  cmd->add_option("file", c->file, "IGES file")->required();
  cmd->add_option("-o,--output", c->output, "Output mesh (.gdf, .vtu, .stl, .obj, ...)")
      ->required();
  cmd->add_option("--panels", c->coarsen.target_panels, "Stop at this many panels (default 4000)")
      ->check(CLI::Range(std::size_t{4}, std::size_t{10'000'000}));
  cmd->add_option("--panel-size", c->coarsen.panel_size,
                  "Panel edge on flat hull away from sources, m (default: from --panels)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--mean-quality", c->coarsen.mean_quality,
                  "Stop once the mean quality index falls to this level (0..1)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--min-quality", c->coarsen.min_quality,
                  "Stop once the smallest quality index falls to this level (0..1)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--weights", c->weights,
                  "w_shape,w_area_ratio,w_curvature,w_sources (default 1,1,1,1)");
  // One value per occurrence: a repeatable option must not take the input file after it as
  // one more value.
  cmd->add_option("--source", c->point_sources, "Point source x,y,z,radius,size (m); may repeat")
      ->allow_extra_args(false);
  cmd->add_option("--line-source", c->line_sources,
                  "Line source x1,y1,z1,x2,y2,z2,radius,size (m); may repeat")
      ->allow_extra_args(false);
  cmd->add_option("--box-source", c->box_sources,
                  "Box source xmin,ymin,zmin,xmax,ymax,zmax,radius,size (m); may repeat")
      ->allow_extra_args(false);
  cmd->add_option("--max-deviation", c->coarsen.max_deviation,
                  "Largest distance of the panels from the NURBS, m (default 1e-3 L)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--curvature-length", c->coarsen.curvature_length,
                  "R in h / sqrt(1 + k R), m (default 0.05 L)")
      ->check(CLI::PositiveNumber);
  add_knuckle_hint_options(cmd, c->hints);
  cmd->add_option("--knuckle-angle", c->features.knuckle_angle_deg,
                  "Dihedral angle in degrees above which an edge may be a knuckle")
      ->check(CLI::Range(1.0, 179.0));
  cmd->add_option("--triangles", c->triangles,
                  "Fine triangles to coarsen from (default 6 per panel, 24k to 2M)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{50'000'000}));
  cmd->add_option("--edge-length", c->tessellate.edge_length, "Fine tessellation edge, m")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--chord-tol", c->tessellate.chord_tolerance,
                  "Fine chord tolerance, m (default 1e-4 L)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--improve-passes", c->coarsen.improve_passes,
                  "Passes of edge flips and smoothing after the collapses (default 8)")
      ->check(CLI::Range(0, 100));
  cmd->add_flag("--serial", c->coarsen.serial_reference,
                "One collapse at a time from a priority queue (the reference)");
  cmd->add_option("--units", c->units, "Force the file's unit (m, mm, cm, in, ft, km)")
      ->check(CLI::IsMember({"m", "mm", "cm", "in", "ft", "km"}));
  add_floating_options(cmd, c->floating);
  add_lid_options(cmd, c->lid);
  cmd->add_option("--symmetry", c->symmetry,
                  "auto: as the file is (a half hull gets its y = 0 flag); half: keep the port "
                  "half of a full hull (cut at y = 0 before meshing); full: mirror a half hull")
      ->check(CLI::IsMember({"auto", "half", "full"}));
  cmd->callback(
      [c, &global, &action] { action = [c, &global] { return run_unstructured(*c, global); }; });
}

}  // namespace hm::cli
