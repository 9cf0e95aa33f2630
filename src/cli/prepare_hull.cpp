#include "cli/prepare_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli/load_hull.h"
#include "cli/merge_mirrored.h"
#include "cli/validate_stage.h"
#include "core/bbox.h"
#include "core/error.h"
#include "mesh/mirror_mesh.h"
#include "nurbs/knot_ops.h"
#include "quality/hydrostatics.h"

namespace hm::cli {

double hull_length(const SurfaceMesh& m) {
  BBox3d box;
  for (const Vec3d& p : m.positions) box.add(p);
  const Vec3d e = box.extent();
  return std::max({e.x, e.y, e.z});
}

namespace {

// A trim curve in (u, v) under u -> u0 + u1 - u, run backwards (so a loop of such curves keeps
// its sense of rotation in the reflected domain).
NurbsCurve reflected_in_u(const NurbsCurve& c, double u0, double u1) {
  NurbsCurve r = c;
  const std::size_t n = c.points.size(), m = c.knots.size();
  for (std::size_t i = 0; i < n; ++i) {
    r.points[i] = c.points[n - 1 - i];
    r.points[i].x = u0 + u1 - r.points[i].x;
    if (c.weights.size() == n) r.weights[i] = c.weights[n - 1 - i];
  }
  for (std::size_t k = 0; k < m; ++k) {
    const double t = c.knots[m - 1 - k];
    r.knots[k] = t == c.t0 ? c.t1 : (t == c.t1 ? c.t0 : c.t0 + (c.t1 - t));
  }
  return r;
}

}  // namespace

void add_mirror_image(ImportResult& hull) {
  const std::size_t n = hull.patches.size();
  hull.patches.reserve(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    Patch image = hull.patches[i];
    for (Vec3d& c : image.surface.points) c.y = -c.y;
    // A reflection turns su x sv inside out: u runs backwards in the image, as the generator's
    // starboard side does (flagging the patch reversed instead leaves the merge non-manifold at
    // the keel of a mirrored Wigley). Its trim loops follow u, each loop still running the same
    // way round.
    const double u0 = image.surface.u0, u1 = image.surface.u1;
    image.surface = reverse_u(image.surface);
    for (TrimLoop& loop : image.loops) {
      std::reverse(loop.curves_uv.begin(), loop.curves_uv.end());
      for (NurbsCurve& c : loop.curves_uv) c = reflected_in_u(c, u0, u1);
    }
    if (!image.name.empty()) image.name += " (mirror)";
    hull.patches.push_back(std::move(image));
  }
  hull.bbox.add(Vec3d{hull.bbox.lo.x, -hull.bbox.hi.y, hull.bbox.lo.z});
  hull.bbox.add(Vec3d{hull.bbox.hi.x, -hull.bbox.lo.y, hull.bbox.hi.z});
}

HydrostaticsPair compare_hydrostatics(const SurfaceMesh& panels, bool panels_half_hull,
                                      const Hydrostatics& nurbs) {
  HydrostaticsPair h;
  FloatingPosition position;
  position.waterline_z = 0;
  position.half_hull = panels_half_hull;
  h.mesh = hydrostatics_mesh(panels, position);
  h.nurbs = nurbs;
  return h;
}

Hydrostatics nurbs_hydrostatics(const PreparedHull& hull) {
  // The NURBS integrals follow each patch's declared normal: turn the patches the merge found
  // wound into the hull, as it turned their faces. The report prints to 1e-5 relative and the
  // panels' own error is about 1e-3: 1e-6 on cells and trim loops, 5 levels deep, agrees with a
  // 1e-10, 9-level reference to 5e-7 on the shared hulls (DTMB 5415's trimmed dome; 1e-9 on the
  // others), at a third of the time 1e-7 and 7 levels took (DTMB 5415: 0.155 -> 0.048 s; a trimmed
  // cell's kinked integrand otherwise splits to the deepest level).
  const std::span<const Patch> patches = hull.patches();
  std::vector<Patch> outward(patches.begin(), patches.end());
  for (PatchId p : hull.merged.report.patches_flipped) outward[p].reversed = !outward[p].reversed;
  NurbsHydrostaticsOptions ho;
  ho.rel_tol = 1e-6;
  ho.trim_tol = 1e-6;
  ho.max_depth = 5;
  FloatingPosition position;
  position.waterline_z = 0;
  position.half_hull = hull.file_half;
  return hydrostatics_nurbs(outward, position, ho);
}

void print_hydrostatics(const Hydrostatics& mesh, const Hydrostatics& nurbs) {
  auto rel = [](double a, double b) { return b != 0 ? 100 * (a - b) / b : 0.0; };
  std::printf(
      "  hydrostatics, mesh against NURBS: volume %.6g m^3 (%+.3f%%), wetted area %.6g m^2 "
      "(%+.3f%%), waterplane area %.6g m^2 (%+.3f%%%s), LCB %.5g m (NURBS %.5g)\n",
      mesh.volume, rel(mesh.volume, nurbs.volume), mesh.wetted_area,
      rel(mesh.wetted_area, nurbs.wetted_area), mesh.waterplane_area,
      rel(mesh.waterplane_area, nurbs.waterplane_area),
      mesh.waterplane_from_fluxes ? ", from the panels' fluxes: the waterline is open" : "",
      mesh.buoyancy_centre.x, nurbs.buoyancy_centre.x);
}

void prepare_hull(const PrepareArgs& args, PreparedHull& out) {
  Progress& progress = args.progress ? *args.progress : silent_progress();
  progress.stage("import");
  const long long t0 = now_ns();
  out.hull = load_hull(args.file, args.units, args.quiet);
  FeatureOptions features = args.features;
  // Floating: the patches are placed first, so that everything below works in the floating frame
  // and the waterplane z = 0 cuts the merged fine mesh before it is meshed.
  if (args.floating.given()) {
    // A heeled hull has no y = 0 symmetry, so a half hull cannot stand for it: its mirror image
    // joins it first, and the whole hull is meshed.
    const Vec3d e = out.hull.bbox.extent();
    const double tol = kPlaneTolerance * std::max({e.x, e.y, e.z});
    if (args.floating.heel_deg != 0 && (out.hull.bbox.lo.y >= -tol || out.hull.bbox.hi.y <= tol)) {
      add_mirror_image(out.hull);
      out.mirrored_before_meshing = true;
      if (!args.quiet) {
        std::fprintf(stderr,
                     "hullmesh: note: %s is a half hull; heeled, it is mirrored about y = 0 "
                     "first and meshed whole (%zu patches)\n",
                     args.file.c_str(), out.hull.patches.size());
      }
    }
    try {
      out.floating = resolve_floating(args.floating, out.hull.patches, out.hull.bbox);
    } catch (const UsageError& e) {
      // A batch runs many hulls: the message must say which one cannot float so.
      throw UsageError(args.file + ": " + e.what());
    }
    out.placed = transformed(out.hull.patches, out.floating->transform);
    features.waterline_z = 0;
    features.waterline_inside = out.floating->meshes_above();
  }
  out.seconds_import = seconds_since(t0);
  const std::span<const Patch> patches = out.patches();
  apply_knuckle_hints(args.knuckle_hints, patches,
                      out.floating ? &out.floating->transform : nullptr, args.file, features);

  // The merge can leave an edge with three faces where three patch borders meet at a
  // resolution that happens to split them badly (issue 4). Where the caller allows it, the fine
  // mesh is made again denser (retry_growth), and the retry is reported.
  std::size_t triangles = args.fine_triangles;
  for (int attempt = 0;; ++attempt) {
    TessellateOptions o = args.tessellate;
    if (triangles > 0 && o.edge_length <= 0)
      o.edge_length = edge_length_for_triangles(patches, triangles);
    progress.stage("tessellate");
    // A heeled half hull: the file's half alone, in the file's frame, merged and then mirrored
    // with its merged surface (merge_mirrored_half), and placed.
    const std::span<const Patch> file_patches = out.hull.patches;
    out.tessellation = tessellate(
        out.mirrored_before_meshing ? file_patches.first(file_patches.size() / 2) : patches, o,
        progress);
    if (args.validate) {
      // Each patch's triangulation on its own: the patches are not welded yet.
      InvariantOptions io;
      io.no_zero_area = false;  // a pole of a patch may leave slivers the merge removes
      validate_stage(args.file, "tessellate", out.tessellation.mesh, io);
    }
    progress.stage("merge");
    out.merged = out.mirrored_before_meshing
                     ? merge_mirrored_half(file_patches, out.tessellation, args.merge,
                                           out.floating->transform, progress)
                     : merge_patches(patches, out.tessellation.mesh, args.merge, progress);
    progress.stage("cut");
    // The cuts before meshing: the waterplane, then the centre plane when one half of a full
    // hull is wanted.
    out.centre_tol = kPlaneTolerance * hull_length(out.merged.mesh);
    out.file_half = is_half_hull(out.merged.mesh, out.centre_tol);
    out.top_cut.reset();
    out.waterplane_cut.reset();
    out.centre_cut.reset();
    if (out.floating && out.floating->meshes_above()) {
      PlaneCutOptions to;
      to.value = out.floating->above_waterline;
      out.top_cut = cut_at_plane(patches, out.fine(), to);
    }
    if (out.floating) {
      // Meshed above the waterline too: the waterplane splits the surface and stays a line in it.
      PlaneCutOptions wo;
      wo.keep_both = out.floating->meshes_above();
      out.waterplane_cut = cut_at_plane(patches, out.fine(), wo);
    }
    if (args.cut_centre_plane && !out.file_half) {
      PlaneCutOptions co;
      co.axis = 1;
      co.keep_below = false;  // the port half, y >= 0
      out.centre_cut = cut_at_plane(patches, out.fine(), co);
    }
    const SurfaceMesh& fine = out.fine();
    out.adjacency = build_edge_adjacency(fine.faces, fine.vertex_count());
    // Two faces running the same way along an edge is the same kind of accident (npl at some
    // resolutions), and --validate refuses it.
    const std::size_t faults =
        out.adjacency.nonmanifold_edges.size() + out.adjacency.inconsistent_edges.size();
    const bool retry = faults > 0 && triangles > 0 && attempt < args.finer_retries;
    if (!retry) break;
    const auto denser =
        static_cast<std::size_t>(std::ceil(static_cast<double>(triangles) * args.retry_growth));
    if (!args.quiet) {
      std::fprintf(stderr,
                   "hullmesh: note: %s: the merge left %zu edges with more than two faces and %zu "
                   "run the same way by two faces at %zu fine triangles; trying again at %zu\n",
                   args.file.c_str(), out.adjacency.nonmanifold_edges.size(),
                   out.adjacency.inconsistent_edges.size(), triangles, denser);
    }
    out.retried_triangles = denser;
    triangles = denser;
  }
  progress.stage("features");
  const long long t1 = now_ns();
  const SurfaceMesh& fine = out.fine();
  check_merged_manifold(args.file, fine, out.adjacency,
                        "`hullmesh merge` writes the surface for inspection");
  // Two patches through each other (an appendage left untrimmed), or a fold the merge left. The
  // meshers check their panels for the same before writing; here the fine faces name the patches.
  // Nothing downstream reads it, so it runs beside the meshing (in the cores the mesher's serial
  // steps leave idle).
  out.crossing_check = std::make_unique<BackgroundTask>([&out, file = args.file, patches] {
    const SurfaceMesh& surface = out.fine();
    out.crossing_warning = describe_crossings(file, patches, surface, measure_crossings(surface),
                                              "the merged surface");
  });
  // What the meshers are given: a merge fault in a part a cut takes away is not passed on.
  if (args.validate) {
    const bool cut = out.top_cut || out.waterplane_cut || out.centre_cut;
    validate_stage(args.file, cut ? "merge and cut" : "merge", fine, {});
  }
  out.feature_options = features;
  out.features = find_features(fine, out.adjacency, patches, features);
  out.seconds_features = seconds_since(t1);
}

void report_surface_crossings(PreparedHull& hull, bool quiet) {
  if (!hull.crossing_check) return;
  hull.crossing_check->wait();
  if (!hull.crossing_warning.empty() && !quiet) {
    std::fprintf(stderr, "hullmesh: warning: %s\n", hull.crossing_warning.c_str());
  }
}

void measure_panel_crossings(const std::string& file, std::span<const Patch> patches,
                             const SurfaceMesh& panels, bool quiet, QualityOptions& qo) {
  const SelfIntersections crossings = measure_crossings(panels);
  qo.crossing_pairs = crossings.count;
  if (crossings.count == 0) return;
  qo.crossing_where = crossings.first.front().where;
  if (!quiet) {
    std::fprintf(stderr, "hullmesh: warning: %s\n",
                 describe_crossings(file, patches, panels, crossings, "the panel mesh").c_str());
  }
}

}  // namespace hm::cli
