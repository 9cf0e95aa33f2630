// Shared by the two meshers: import, place the hull afloat, tessellate it fine, merge the patches
// into one surface, cut it at the waterplane and (for one half of a full hull) at the centre
// plane, and find its knuckles and boundaries.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cli/floating_options.h"
#include "cli/knuckle_hints.h"
#include "core/parallel.h"
#include "iges/read_iges.h"
#include "mesh/adjacency.h"
#include "quality/hydrostatics.h"
#include "quality/quality_report.h"
#include "tessellate/tessellate.h"
#include "unstructured/cut_at_plane.h"
#include "unstructured/features.h"
#include "unstructured/merge.h"

namespace hm::cli {

// Fine triangles of the structured mesher's internal surface for a panel target (the rows are
// cut from it and refined on the NURBS): 5 per panel, within [10,000, 1,000,000].
inline std::size_t structured_fine_triangles(std::size_t panels) {
  return std::clamp<std::size_t>(5 * panels, 10'000, 1'000'000);
}

struct PrepareArgs {
  std::string file, units;
  FloatingArgs floating;
  // "half": keep the port half of a full hull (cut at y = 0 before meshing).
  bool cut_centre_plane = false;
  TessellateOptions tessellate;  // edge_length > 0 wins over fine_triangles
  std::size_t fine_triangles = 0;
  MergeOptions merge;
  FeatureOptions features;
  KnuckleHintSpecs knuckle_hints;  // added to `features` once the patches are placed
  bool quiet = false;
  // Times the fine mesh may be made denser, by retry_growth in triangle count, when the merge
  // leaves non-manifold or inconsistently oriented edges (only when fine_triangles sizes it).
  int finer_retries = 0;
  double retry_growth = 2;
  // --validate: the invariants of each stage's mesh are checked as it ends (validate_stage.h).
  bool validate = false;
  // Told each stage as it starts (import, tessellate, merge, cut, features); null: silent.
  Progress* progress = nullptr;
};

// Not movable: it is filled in place and read through its accessors.
struct PreparedHull {
  ImportResult hull;
  std::optional<Floating> floating;
  std::vector<Patch> placed;  // the patches in the floating frame (empty when not afloat)
  Tessellation tessellation;
  MergedSurface merged;
  // In order: the top cut (--above-waterline), the waterplane (a split when the hull is meshed
  // above it too), the centre plane.
  std::optional<PlaneCut> top_cut, waterplane_cut, centre_cut;
  bool file_half = false;                // the file holds one side of the centre plane
  bool mirrored_before_meshing = false;  // a heeled half hull, made whole
  double centre_tol = 0;                 // m: 2e-4 of the merged hull's largest extent
  EdgeAdjacency adjacency;               // of fine()
  FeatureSet features;                   // of fine()
  FeatureOptions feature_options;        // what found them (hints placed, waterline set)
  double seconds_import = 0, seconds_features = 0;
  std::size_t retried_triangles = 0;  // the fine triangle count of the last retry, 0 when none
  // The check of fine() for faces through each other, which only warns: prepare_hull starts it
  // beside the meshing and report_surface_crossings takes its result. The last member, so that
  // it is joined before what it reads goes.
  std::string crossing_warning;
  std::unique_ptr<BackgroundTask> crossing_check;

  PreparedHull() = default;
  PreparedHull(const PreparedHull&) = delete;
  PreparedHull& operator=(const PreparedHull&) = delete;

  std::span<const Patch> patches() const {
    return floating ? std::span<const Patch>(placed) : std::span<const Patch>(hull.patches);
  }
  // The surface the meshers work on: merged, then cut.
  const SurfaceMesh& fine() const {
    return centre_cut       ? centre_cut->mesh
           : waterplane_cut ? waterplane_cut->mesh
           : top_cut        ? top_cut->mesh
                            : merged.mesh;
  }
};

// Fills `out`. A heeled half hull (it has no y = 0 symmetry) is made whole by its mirror image
// first. Throws whatever import, merge and the cuts throw; GeometryError (exit 5) when the merged
// surface is not edge-manifold, naming where.
void prepare_hull(const PrepareArgs& args, PreparedHull& out);

// Waits for the merged surface's crossing check and, unless quiet, prints its warning. The
// meshing commands call it before they write (it rethrows what the check threw).
void report_surface_crossings(PreparedHull& hull, bool quiet);

// The panels checked for faces that pass through each other: the count and the first place go
// into `qo` for the report's hard rule, and unless quiet a warning names the patches.
void measure_panel_crossings(const std::string& file, std::span<const Patch> patches,
                             const SurfaceMesh& panels, bool quiet, QualityOptions& qo);

// The panels' hydrostatics at the waterplane z = 0 of the floating frame, and the same
// integrals on the NURBS (the exact values they approximate). Only for a floating hull.
struct HydrostaticsPair {
  Hydrostatics mesh, nurbs;
};
HydrostaticsPair compare_hydrostatics(const SurfaceMesh& panels, bool panels_half_hull,
                                      const Hydrostatics& nurbs);

// The NURBS half of that: it depends on the placed patches alone, so the meshing commands start
// it beside their mesher (BackgroundTask) and take it for the report.
Hydrostatics nurbs_hydrostatics(const PreparedHull& hull);

// One line: volume, wetted and waterplane area, LCB of the panels against the NURBS.
void print_hydrostatics(const Hydrostatics& mesh, const Hydrostatics& nurbs);

// Appends each patch's mirror image about y = 0 (u reversed, so normals still point out of the
// ship) and grows the bounding box to match.
void add_mirror_image(ImportResult& hull);

// Largest extent of the mesh's bounding box, m.
double hull_length(const SurfaceMesh& m);

}  // namespace hm::cli
