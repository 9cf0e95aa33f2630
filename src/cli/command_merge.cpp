// hullmesh merge FILE -o merged.vtu: one watertight hull from the patch triangulations, with its
// knuckle lines and boundaries written beside it as VTK line sets.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/knuckle_hints.h"
#include "cli/load_hull.h"
#include "cli/run_record.h"
#include "cli/validate_stage.h"
#include "core/error.h"
#include "core/parallel.h"
#include "io/write_mesh.h"
#include "io/write_polylines.h"
#include "mesh/adjacency.h"
#include "tessellate/tessellate.h"
#include "unstructured/features.h"
#include "unstructured/merge.h"

namespace hm::cli {
namespace {

struct MergeCommand {
  std::string file;
  std::string output;
  std::string units;
  std::string lines_prefix;  // default: the output path without its extension
  TessellateOptions tessellate;
  std::size_t triangles = 0;
  MergeOptions merge;
  FeatureOptions features;
  KnuckleHintArgs hints;
};

std::vector<PolylineRecord> to_records(const SurfaceMesh& m, std::span<const FeatureLine> lines,
                                       const std::string& label) {
  std::vector<PolylineRecord> out;
  for (const FeatureLine& l : lines) {
    PolylineRecord r;
    r.label = label;
    r.closed = l.closed;
    for (Index v : l.vertices) r.points.push_back(m.positions[v]);
    out.push_back(std::move(r));
  }
  return out;
}

int run_merge(const MergeCommand& c, const GlobalOptions& g) {
  check_mesh_output(c.output);
  const KnuckleHintSpecs hints = parse_knuckle_hints(c.hints);
  RunRecord& record = *g.record;
  record.log.stage("import");
  const long long t0 = now_ns();
  const ImportResult hull = load_hull(c.file, c.units, g.quiet);
  FeatureOptions feature_options = c.features;
  apply_knuckle_hints(hints, hull.patches, nullptr, c.file, feature_options);
  const double t_import = seconds_since(t0);
  TessellateOptions o = c.tessellate;
  o.measure_chord = false;  // the merge reads no chord error
  if (c.triangles > 0) o.edge_length = edge_length_for_triangles(hull.patches, c.triangles);
  record.log.stage("tessellate");
  const Tessellation t = tessellate(hull.patches, o, record.log);
  record.log.stage("merge");
  const MergedSurface merged = merge_patches(hull.patches, t.mesh, c.merge, record.log);
  record.log.stage("features");
  const long long t1 = now_ns();
  const EdgeAdjacency adj = build_edge_adjacency(merged.mesh.faces, merged.mesh.vertex_count());
  if (!adj.nonmanifold_edges.empty()) {
    // Keep the surface for inspection, but fail: no later stage can use it.
    MeshWriteOptions w;
    w.info.title = "hullmesh merged surface (non-manifold) of " + file_name(c.file);
    write_mesh(c.output, merged.mesh, w);
    check_merged_manifold(
        c.file, merged.mesh, adj,
        "overlapping patches there? The surface is in " + c.output + " for inspection");
  }
  // The surface's invariants (edge-manifold, consistently oriented, no face of no area), as
  // the meshers check the surface they start from; it fails before anything is written.
  if (g.validate) validate_stage(c.file, "merge", merged.mesh, {});
  // Faces through each other (patches crossing that the merge did not cut, or a fold it left):
  // counted for the report, as the meshers count them on the surface they start from, beside
  // the features and the writing (a quarter of a second at 470,000 triangles).
  SelfIntersections crossings;
  BackgroundTask crossing_task([&] { crossings = measure_crossings(merged.mesh); });
  const FeatureSet features = find_features(merged.mesh, adj, hull.patches, feature_options);
  const double t_features = seconds_since(t1);

  // Write the lines first: the mesh is the main output, and a failure leaves no mesh behind
  // that looks complete without its lines.
  std::filesystem::path prefix = c.lines_prefix;
  if (prefix.empty()) prefix = std::filesystem::path(c.output).replace_extension();
  const std::string knuckle_path = prefix.string() + "_knuckles.vtk";
  const std::string boundary_path = prefix.string() + "_boundaries.vtk";
  write_polylines(knuckle_path, to_records(merged.mesh, features.knuckles, "knuckle"));
  std::vector<PolylineRecord> runs;
  for (const BoundaryRun& b : features.boundaries) {
    const FeatureLine& line = b;
    std::vector<PolylineRecord> one =
        to_records(merged.mesh, std::span<const FeatureLine>(&line, 1), to_string(b.kind));
    runs.push_back(std::move(one.front()));
  }
  write_polylines(boundary_path, runs);
  MeshWriteOptions w;
  w.info.title = "hullmesh merged surface of " + file_name(c.file);
  record.log.stage("write");
  write_mesh(c.output, merged.mesh, w);
  crossing_task.wait();
  const std::string crossing_warning =
      describe_crossings(c.file, hull.patches, merged.mesh, crossings, "the merged surface");
  if (!crossing_warning.empty() && !g.quiet) {
    std::fprintf(stderr, "hullmesh: warning: %s\n", crossing_warning.c_str());
  }
  record.log.finish();
  record.input = c.file;
  record.outputs = {c.output, knuckle_path, boundary_path};
  record.results = {{"triangles", merged.mesh.face_count()},
                    {"vertices", merged.mesh.vertex_count()},
                    {"gaps_closed", merged.report.gaps_closed},
                    {"gaps_open", merged.report.open_gaps.size()},
                    {"overlap_triangles_removed", merged.report.overlap_triangles_removed},
                    {"patches_flipped", merged.report.patches_flipped.size()},
                    {"overlaps_cut_oriented", merged.report.overlaps_cut_oriented},
                    {"crossing_pairs", crossings.count},
                    {"knuckle_lines", features.knuckles.size()},
                    {"boundary_runs", features.boundaries.size()},
                    {"validated", g.validate}};

  if (!g.quiet) {
    const MergeReport& r = merged.report;
    std::printf("%s: %zu patches, %zu triangles -> %zu triangles, %zu vertices\n", c.output.c_str(),
                hull.patches.size(), r.input_triangles, merged.mesh.face_count(),
                merged.mesh.vertex_count());
    std::printf("  gaps closed: %zu (widest %.3g m); vertices welded %zu; T-junctions split %zu\n",
                r.gaps_closed, r.widest_gap_closed, r.vertices_welded, r.tjunctions_split);
    if (r.snap_retries > 0) {
      std::printf(
          "  snap run again %zu time%s with a smaller tolerance near edges with three "
          "faces or folded holes\n",
          r.snap_retries, r.snap_retries == 1 ? "" : "s");
    }
    if (r.folded_faces_dropped > 0) {
      std::printf("  overlap remnants lying on another patch across an edge dropped: %zu\n",
                  r.folded_faces_dropped);
    }
    if (r.flat_faces_split > 0) {
      std::printf("  faces with their corners on one line split away: %zu\n", r.flat_faces_split);
    }
    if (r.folds_welded > 0) {
      std::printf("  folds closed (two faces on each other across an edge): %zu\n", r.folds_welded);
    }
    if (r.folds_flipped > 0) {
      std::printf("  folded triangles flipped flat (a fan turned against its neighbours): %zu\n",
                  r.folds_flipped);
    }
    if (r.gap_vertices_widened > 0) {
      std::printf("  tolerance widened to the gap measured at %zu border vertices (up to %.3g m)\n",
                  r.gap_vertices_widened, r.widened_to);
    }
    if (r.gaps_bridged > 0) {
      std::printf("  gaps wider than the border edges zipped shut: %zu\n", r.gaps_bridged);
    }
    std::printf("  gaps left open: %zu", r.open_gaps.size());
    if (!r.open_gaps.empty()) {
      const OpenGap& gw = r.open_gaps.front();
      std::printf(" (widest %.3g m between patches %u and %u at %.4g, %.4g, %.4g)", gw.width,
                  gw.patch_a, gw.patch_b, gw.location.x, gw.location.y, gw.location.z);
    }
    std::printf("\n  overlaps removed: %zu triangles, %.4g m^2%s\n", r.overlap_triangles_removed,
                r.overlap_area_removed,
                r.overlaps_cut_oriented ? " (cut again with the flipped patches turned)" : "");
    std::printf("  patches flipped: %zu", r.patches_flipped.size());
    for (std::size_t i = 0; i < r.patches_flipped.size() && i < 10; ++i) {
      std::printf("%s%u", i ? ", " : " (", r.patches_flipped[i]);
    }
    std::printf("%s\n", r.patches_flipped.empty()       ? ""
                        : r.patches_flipped.size() > 10 ? ", ...)"
                                                        : ")");
    std::printf("  knuckle lines: %zu, %.4g m", features.knuckles.size(),
                features.knuckle_length());
    std::printf("; corners: %zu\n", features.corners.size());
    std::size_t by_kind[5] = {0, 0, 0, 0, 0};
    double len_kind[5] = {0, 0, 0, 0, 0};
    for (const BoundaryRun& b : features.boundaries) {
      ++by_kind[int(b.kind)];
      len_kind[int(b.kind)] += b.length;
    }
    std::printf("  boundary loops: %zu;", r.boundary_loops);
    for (int k = 0; k < 5; ++k) {
      if (by_kind[k])
        std::printf(" %s %zu (%.4g m)", to_string(BoundaryKind(k)), by_kind[k], len_kind[k]);
    }
    std::printf(
        "\n  topology: %zu non-manifold edges, %zu inconsistent edges, %zu pairs of faces "
        "through each other, enclosed volume %.6g m^3\n",
        r.nonmanifold_edges, r.inconsistent_edges, crossings.count, r.enclosed_volume);
    std::printf("  lines: %s, %s\n", knuckle_path.c_str(), boundary_path.c_str());
    std::printf("  time: import %.3f s, tessellate %.3f s, merge %.3f s, features %.3f s\n",
                t_import, t.summary.seconds, r.seconds, t_features);
  }
  return 0;
}

}  // namespace

void register_merge(CLI::App& app, const GlobalOptions& global, Action& action) {
  auto c = std::make_shared<MergeCommand>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "One watertight hull from the patches, with knuckle lines and boundaries");
  cmd->add_option("file", c->file, "IGES file")->required();
  cmd->add_option("-o,--output", c->output, "Output mesh (.vtu, .vtk, .stl, .obj, ...)")
      ->required();
  cmd->add_option("--lines", c->lines_prefix,
                  "Prefix of the line files (default: the output without extension); writes "
                  "PREFIX_knuckles.vtk and PREFIX_boundaries.vtk");
  cmd->add_option("--edge-length", c->tessellate.edge_length,
                  "Tessellation edge in metres (default L/100)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--triangles", c->triangles, "Tessellate to about this many triangles")
      ->check(CLI::Range(std::size_t{1}, std::size_t{50'000'000}));
  cmd->add_option("--chord-tol", c->tessellate.chord_tolerance,
                  "Chord tolerance in metres (default 1e-4 L)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--gap-tol", c->merge.gap_tolerance,
                  "Widest gap closed, metres (default half the local border edge)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("!--keep-overlaps", c->merge.remove_overlaps,
                "Do not remove layers where patches cover each other");
  cmd->add_option("--knuckle-angle", c->features.knuckle_angle_deg,
                  "Dihedral angle in degrees above which an edge may be a knuckle")
      ->check(CLI::Range(1.0, 179.0));
  add_knuckle_hint_options(cmd, c->hints);
  cmd->add_option("--waterline-z", c->features.waterline_z,
                  "z of a waterline cut: boundary edges on it are waterline");
  cmd->add_option("--units", c->units, "Force the file's unit (m, mm, cm, in, ft, km)")
      ->check(CLI::IsMember({"m", "mm", "cm", "in", "ft", "km"}));
  cmd->callback([c, &global, &action] { action = [c, &global] { return run_merge(*c, global); }; });
}

}  // namespace hm::cli
